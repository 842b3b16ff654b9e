#pragma once
// What the campaign overview of `rcsim report` reads (docs/report.md, "Campaign report"): every
// run's figures (replay/verdict/run_figures.hpp: a few queries, whatever the number of runs), the
// verdicts of the stored criteria (replay/verdict/criteria.hpp), the campaign's name
// (replay/store/campaign_store.hpp), and the figures the overview ranks and plots: those of the
// catalogue and the distribution distances that some run has, and every criterion's figure. Text
// fields are as stored (unescaped).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/quantile.hpp"
#include "replay/verdict/criteria.hpp"
#include "replay/verdict/run_figures.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::report {

struct CampaignData {
  std::string name;  // the campaign's name (table campaign); empty if the database has none
  // The criteria's figures first (in the criteria's order), then the catalogue's and the
  // distribution distances' that some run has.
  std::vector<verdict::FigureInfo> figures;
  std::vector<verdict::RunFigureRow> runs;   // by run id; values[i] is figures[i]
  verdict::Verdicts verdicts;                // by the stored criteria; no criteria: every run passed

  // The values of figure i that runs have, ascending.
  std::vector<double> sorted_values(std::size_t figure) const;
  // The index of the figure named `figure` in `figures`, if listed.
  std::optional<std::size_t> figure_index(const std::string& figure) const;
};

// Whether the database belongs to a campaign or holds criteria: cheap, for deciding whether the
// page starts with the campaign overview.
bool is_campaign_database(ReportDatabase& db);

CampaignData read_campaign_data(ReportDatabase& db);

}  // namespace rcsim::replay::report
