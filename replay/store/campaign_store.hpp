#pragma once
// What campaigns read and write in a report database (schemas/report-database.md, schema v5):
// the tables `campaign` and `criteria` as stored, and the sources of every run's figures
// (replay/verdict/run_figures.hpp) in a few queries, whatever the number of runs. Plain rows
// out: the campaign layer parses, judges and ranks them.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "replay/run/run_kind.hpp"

namespace rcsim::replay {

// One row of the table criteria, as stored: scope recording | campaign, statistic value | mean |
// median | p95 | min | max, bound min | max, if_missing fail | pass.
struct CriterionRow {
  std::string figure, scope, statistic, bound;
  double threshold = 0.0;
  std::string if_missing;
};

// The criteria stored, in order.
std::vector<CriterionRow> read_criterion_rows(SQLite::Database& db);

// Replaces the stored criteria by these, in this order: all or nothing (a savepoint), on its own
// or within the caller's transaction.
void replace_criterion_rows(SQLite::Database& db, const std::vector<CriterionRow>& rows);

// How many criteria are stored.
std::int64_t count_criterion_rows(SQLite::Database& db);

// The name of the campaign the report belongs to (the first row of the table campaign); nullopt
// if it belongs to none.
std::optional<std::string> read_campaign_name(SQLite::Database& db);

// The campaign a report was claimed for, as stored.
struct StoredCampaign {
  std::string name;
  std::vector<CriterionRow> criteria;
};

// In one transaction: the campaign the report belongs to already, with its criteria (nothing is
// written); or, if it belongs to none, nullopt after writing the campaign's name, manifest and
// criteria.
std::optional<StoredCampaign> claim_campaign(SQLite::Database& db, const std::string& name, const std::string& manifest,
                                             const std::vector<CriterionRow>& criteria);

// What a run's figures are computed from: its row of runs, its row of summaries, and the sums of
// its object_figures. A NULL column, or a run without object_figures, gives NaN.
struct RunFigureSources {
  std::int64_t run_id = 0;
  std::string recording_name, recording_dir;
  std::int64_t seed = 0;
  double duration_s = 0.0;  // cycles x cycle time
  ListLevel kind = ListLevel::tracks;  // what the run compares (compared_level): tracks or detections
  // summaries
  double gospa_mean = 0.0, ospa_mean = 0.0, gospa_object_mean = 0.0, ospa_object_mean = 0.0;
  double targets_recorded = 0.0, targets_simulated = 0.0, targets_matched = 0.0;
  double latency_recorded_s = 0.0, latency_simulated_s = 0.0, latency_difference_mean_s = 0.0, latency_pairs = 0.0,
         latency_episodes = 0.0, latency_unconfirmed_recorded = 0.0, latency_unconfirmed_simulated = 0.0;
  double merge_recorded = 0.0, merge_simulated = 0.0, merge_matched = 0.0;  // merge artefacts
  double residual_range_rms_m = 0.0, residual_azimuth_rms_rad = 0.0, residual_range_rate_rms_mps = 0.0,
         residual_amplitude_mean_db = 0.0;
  double simulate_cpu_s = 0.0, wall_s = 0.0;  // wall_s: total_wall_s
  // sums over object_figures: cycles in view, and detected in the recording and the simulation
  double in_view = 0.0, detected_recorded = 0.0, detected_simulated = 0.0;
  // target classes (schema v3; NaN in older runs)
  double object_recorded = 0.0, object_simulated = 0.0, background_recorded = 0.0, background_simulated = 0.0;
};

// Every run that has a row of summaries, by run id.
std::vector<RunFigureSources> read_run_figure_sources(SQLite::Database& db);

// One row of the table distribution_distances, of any run.
struct RunDistance {
  std::int64_t run_id = 0;
  std::string quantity;
  std::optional<double> wasserstein1, kolmogorov_smirnov;
};

// Every row of distribution_distances, as SQLite scans the table.
std::vector<RunDistance> read_run_distances(SQLite::Database& db);

// The quantities of distribution_distances with their units, in the order they were first stored.
struct DistanceQuantity {
  std::string quantity, unit;
};
std::vector<DistanceQuantity> read_distance_quantities(SQLite::Database& db);

}  // namespace rcsim::replay
