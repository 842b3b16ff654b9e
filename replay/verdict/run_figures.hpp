#pragma once
// The figures a campaign judges and ranks its runs by (schemas/campaign.md, "Figures"): one value
// per stored run, computed from a report database's per-run tables (summaries, object_figures,
// distribution_distances), read in a few queries whatever the number of runs
// (replay/store/campaign_store.hpp). A figure is missing (nullopt) where the run has nothing to
// compute it from: no latency pair, no object in view, nothing recorded, a run stored before the
// figure existed.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "replay/run/run_kind.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::verdict {

// Which way a figure gets worse (for "the worst recordings by each figure").
enum class Worse { higher, lower, away_from_zero, away_from_one };

struct FigureInfo {
  std::string name;     // gospa_mean_m, wasserstein1.background_range, ...
  std::string unit;     // m, s, rad, 1, ...
  std::string meaning;  // one line
  Worse worse = Worse::higher;
};

// The fixed figures, in the order the report lists them.
const std::vector<FigureInfo>& figure_catalogue();

// A figure by name: one of the catalogue, or `wasserstein1.Q` / `kolmogorov_smirnov.Q` for a
// quantity Q of the table distribution_distances (docs/metrics.md). nullopt if unknown.
std::optional<FigureInfo> find_figure(std::string_view name);

// Every known figure name, comma-separated (for error messages).
std::string figure_names();

struct RunFigureRow {
  std::int64_t run_id = 0;
  std::string recording_name, recording_dir;
  std::int64_t seed = 0;
  double duration_s = 0.0;  // cycles x cycle time
  ListLevel kind = ListLevel::tracks;
  std::vector<std::optional<double>> values;  // one per figure asked for, in that order
};

// The figures asked for (names as find_figure accepts; unknown ones throw std::invalid_argument)
// of every run, by run id.
std::vector<RunFigureRow> read_run_figures(ReportDatabase& db, const std::vector<std::string>& figures);

}  // namespace rcsim::replay::verdict
