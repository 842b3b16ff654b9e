#pragma once
// What the report's pictures read from the report database (schemas/report-database.md), block
// by block through run_rows.hpp into plain structs: the cycles worth picturing, a window of
// cycles for a bird's-eye picture, time series thinned to every stride-th cycle, and the matched
// pairs' residuals (summarised, then streamed, never loaded whole). A summary run (RunInfo::store)
// has no targets and no boxes: what is read from them comes back empty.
#include <SQLiteCpp/SQLiteCpp.h>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::replay::report {

// A cycle found by a query, with the value it was found by and its sensor (-1: all sensors).
struct CycleFound {
  int cycle = 0;
  double value = 0.0;
  int sensor = -1;
};

struct CycleHighlights {
  std::optional<CycleFound> largest_gospa;             // value: GOSPA / m, with its sensor
  std::optional<CycleFound> most_merge_artefacts;       // value: recorded + simulated, all sensors
  std::optional<CycleFound> first_recorded, first_simulated;  // first cycle with a target
  std::optional<CycleFound> largest_count_difference;  // value: sum over sensors of |recorded - simulated|
};
CycleHighlights read_cycle_highlights(SQLite::Database& db, std::int64_t run_id);

struct CycleRow {
  int cycle = 0, sensor = 0;
  double t_s = 0.0;
  Pose2 X_WS;
  std::int64_t n_recorded = 0, n_simulated = 0;
  double gospa_m = 0.0;
};

struct ObjectStateRow {
  int object = 0;
  Pose2 X_WO;  // annotated (smoothed) box, world
};

struct TargetRow {
  int cycle = 0, sensor = 0, idx = 0;
  bool simulated = false;
  Vec2 p_ST_S = Vec2::Zero();
  std::optional<int> match_idx;
  bool merge_artefact = false;
  std::string target_class;  // object | background | other; empty in runs stored before schema v3
};

// Cycles first_cycle..cycle: their cycle rows and targets; the merge pairs and object states of
// `cycle` itself.
struct CycleWindow {
  int first_cycle = 0, cycle = 0;
  std::vector<CycleRow> cycles;  // by cycle, sensor
  std::vector<std::pair<int, int>> merge_pairs;
  std::vector<ObjectStateRow> objects;
  std::vector<TargetRow> targets;
};
CycleWindow read_cycle_window(SQLite::Database& db, std::int64_t run_id, int first_cycle, int cycle);

// The nearest target of an annotated object (class `object`) of one origin in one cycle and
// sensor; of any class in runs stored before target classes (schema v3).
struct NearestTargetRow {
  int sensor = 0;
  bool simulated = false;
  double t_s = 0.0, range_m = 0.0;
  Vec2 p_ST_S = Vec2::Zero();
};
// Of every stride-th cycle, in cycle, sensor, origin order.
std::vector<NearestTargetRow> read_nearest_targets(SQLite::Database& db, std::int64_t run_id, int stride);

// Means over buckets of `stride` cycles, per sensor.
struct CycleBucketRow {
  int sensor = 0;
  double t_s = 0.0;  // of the bucket's first cycle
  double recorded_mean = 0.0, simulated_mean = 0.0, gospa_mean_m = 0.0, gospa_max_m = 0.0;
};
std::vector<CycleBucketRow> read_cycle_buckets(SQLite::Database& db, std::int64_t run_id, int stride);

// Residuals of an assigned pair, simulated - recorded: range / m, azimuth / rad (wrapped to
// [-pi, pi]), range rate / (m/s), amplitude / dB.
using Residuals = std::array<double, 4>;

struct ResidualSampleStats {
  std::int64_t count = 0;
  Residuals mean{}, mean_square{}, min{}, max{};
  Residuals q1{}, q3{};  // the quartiles (nearest rank)
};
// Over the pairs of every stride-th cycle.
ResidualSampleStats read_residual_sample_stats(SQLite::Database& db, std::int64_t run_id, int stride);
// Every pair of the run, streamed; returns how many.
std::int64_t for_each_residual(SQLite::Database& db, std::int64_t run_id, const std::function<void(const Residuals&)>& visit);

// The object targets of one object over the run, in its own frame (x forward, y left, from the
// box centre): at most max_per_origin of each origin, evenly thinned.
struct ObjectFrameTarget {
  int sensor = 0;
  bool simulated = false;
  Vec2 p_OT_O = Vec2::Zero();
};
std::vector<ObjectFrameTarget> read_object_frame_targets(SQLite::Database& db, std::int64_t run_id, int object,
                                                         int max_per_origin);
// The same for several objects in one pass over the run's targets (a report's pictures: one pass,
// not one each), by object.
std::map<int, std::vector<ObjectFrameTarget>> read_objects_frame_targets(SQLite::Database& db, std::int64_t run_id,
                                                                         const std::vector<int>& objects, int max_per_origin);

// Counts of the background targets in bins of range or azimuth, per origin, counted in SQL; the
// end bins hold what lies beyond them.
enum class BackgroundQuantity { range, azimuth };
struct BackgroundHistogram {
  double lo = 0.0, bin_width = 1.0;
  std::array<std::vector<std::int64_t>, 2> counts;  // [0] recorded, [1] simulated
};
BackgroundHistogram read_background_histogram(SQLite::Database& db, std::int64_t run_id, BackgroundQuantity quantity,
                                              double lo, double bin_width, int bins);
// Range's and azimuth's in one pass over the run's targets: {range, azimuth}.
struct BackgroundBins {
  double lo = 0.0, bin_width = 1.0;
  int bins = 0;
};
std::pair<BackgroundHistogram, BackgroundHistogram> read_background_histograms(SQLite::Database& db, std::int64_t run_id,
                                                                               const BackgroundBins& range_bins,
                                                                               const BackgroundBins& azimuth_bins);

}  // namespace rcsim::replay::report
