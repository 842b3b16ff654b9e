#pragma once
// The campaign overview at the top of `rcsim report` (docs/report.md, "Campaign report"): the
// verdicts (counts, the criteria with their values, the failed runs with each failed criterion),
// the worst runs by each figure, and the figures' distributions over the campaign (quantiles,
// histograms with the criteria's thresholds), every run linked to its detail. Built from
// CampaignData alone in time linear in the runs (the worst runs by partial sorts), so that a
// campaign of 10,000 runs renders in well under a second; long lists are capped and the rest folded.
// Every text from the database is escaped here.
#include <cstdint>
#include <string>
#include <vector>

#include "replay/report/campaign_data.hpp"

namespace rcsim::replay::report {

// Where the overview's links to a run point.
struct RunLinks {
  std::string db_label;               // the database, in the command that renders a run's page
  std::vector<std::int64_t> on_page;  // sorted: the runs detailed on this page (#run-ID)
  std::string pages_href;             // the directory of run pages relative to this page, with a
                                      // trailing slash ("c-runs/"); empty: none written
  std::vector<std::int64_t> pages;    // sorted: the runs with a page there (run-ID.html)

  // A link to the run's section on this page, else to its page; else the run's id alone, and with
  // `with_hint` the command that renders it as its tooltip.
  std::string link(std::int64_t run_id, bool with_hint) const;
};

struct CampaignOverviewOptions {
  int worst = 5;           // runs listed per figure
  int failed_rows = 50;    // failed runs listed before the rest is folded into a <details> block
  int histogram_bins = 30;
};

// The runs the overview's tables link to (the worst by each figure, the failed runs listed before
// the fold), ascending: those `rcsim report --runs-dir` writes pages of.
std::vector<std::int64_t> overview_linked_runs(const CampaignData& data, const CampaignOverviewOptions& options);

// The indices into data.runs of the `n` worst runs by figure `figure` (by its Worse direction;
// ties by run id), worst first; runs without the figure are left out.
std::vector<std::size_t> worst_runs(const CampaignData& data, std::size_t figure, int n);

// The overview as an HTML <section id="campaign">.
std::string campaign_overview(const CampaignData& data, const RunLinks& links, const CampaignOverviewOptions& options);

// A figure's value for a table: four significant digits, no "-0".
std::string figure_value(double value);

// The figures' quantile table and histograms (campaign_distributions.cpp).
std::string campaign_distributions(const CampaignData& data, int histogram_bins);

}  // namespace rcsim::replay::report
