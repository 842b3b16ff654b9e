#pragma once
// The run's figures, accumulated cycle by cycle and sensor by sensor (ReplaySummary): target
// counts, GOSPA and its parts, residuals of the assigned pairs, merge artefacts, and the samples
// of the per-target quantities for the distribution distances (bounded: metrics/sample_summary.hpp); the targets of each class, GOSPA
// on the object targets, the background's samples (range, azimuth, targets per cycle), and the
// object targets' offsets in their object's frame (x, y of p_OT_O).
#include <array>
#include <string_view>
#include <vector>

#include "metrics/sample_summary.hpp"
#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

// The quantities whose recorded and simulated distributions every run compares (table
// distribution_distances; the criteria's wasserstein1.Q and kolmogorov_smirnov.Q), in order:
// those of all targets, of the stationary background's (background_*), and the offsets of the
// targets of class object from their box's centre in the object's frame (object_offset_*: x
// forward, y left, every object target of every object pooled).
struct ComparedQuantity {
  std::string_view name, unit;
};
inline constexpr std::array<ComparedQuantity, 10> kComparedQuantities = {{{"range", "m"},
                                                                         {"azimuth", "rad"},
                                                                         {"range_rate", "m/s"},
                                                                         {"amplitude", "dB"},
                                                                         {"targets_per_cycle", "1"},
                                                                         {"background_range", "m"},
                                                                         {"background_azimuth", "rad"},
                                                                         {"background_targets_per_cycle", "1"},
                                                                         {"object_offset_x", "m"},
                                                                         {"object_offset_y", "m"}}};

class RunAccumulators {
 public:
  // compare_range_rates false (a recording whose ego motion is unknown, schemas/recording.md):
  // no range-rate residual (NaN) and no range-rate distribution distance.
  explicit RunAccumulators(bool compare_range_rates = true) : compare_range_rates_(compare_range_rates) {}
  // One compared cycle of one sensor, after matching (ComparedTarget::match set); the merge
  // artefacts each list holds of the cycle's pairs.
  void add_cycle(const CycleComparison& cycle, long long merge_recorded, long long merge_simulated);
  // Means, RMS residuals and distribution distances into `summary` (its latencies untouched).
  void finish(ReplaySummary& summary);

 private:
  bool compare_range_rates_ = true;
  long long targets_recorded_ = 0, targets_simulated_ = 0, targets_matched_ = 0;
  long long merge_recorded_ = 0, merge_simulated_ = 0, merge_matched_ = 0;
  double gospa_sum_ = 0.0, ospa_sum_ = 0.0, localisation_sum_ = 0.0, missed_sum_ = 0.0, false_sum_ = 0.0;
  double gospa_object_sum_ = 0.0, ospa_object_sum_ = 0.0;
  ClassCounts classes_;
  long long sensor_cycles_ = 0;
  double range_sq_m2_ = 0.0, azimuth_sq_rad2_ = 0.0, rate_sq_m2ps2_ = 0.0, amplitude_sum_db_ = 0.0;
  double object_range_sq_m2_ = 0.0, object_azimuth_sq_rad2_ = 0.0;
  long long object_pairs_ = 0;
  // Samples per origin: [0] recorded, [1] simulated; exact up to SampleSummary::kExactCapacity
  // each, beyond in bins of these widths (the resolution of the distances of longer runs).
  static constexpr double kRangeBin_m = 0.01, kAzimuthBin_rad = 1e-4, kRateBin_mps = 0.01, kAmplitudeBin_db = 0.01,
                          kCountBin = 1.0, kOffsetBin_m = 0.01;
  using Samples = metrics::SampleSummary;
  Samples range_m_[2] = {Samples(kRangeBin_m), Samples(kRangeBin_m)};
  Samples azimuth_rad_[2] = {Samples(kAzimuthBin_rad), Samples(kAzimuthBin_rad)};
  Samples rate_mps_[2] = {Samples(kRateBin_mps), Samples(kRateBin_mps)};
  Samples amplitude_db_[2] = {Samples(kAmplitudeBin_db), Samples(kAmplitudeBin_db)};
  Samples count_[2] = {Samples(kCountBin), Samples(kCountBin)};
  Samples background_range_m_[2] = {Samples(kRangeBin_m), Samples(kRangeBin_m)};
  Samples background_azimuth_rad_[2] = {Samples(kAzimuthBin_rad), Samples(kAzimuthBin_rad)};
  Samples background_count_[2] = {Samples(kCountBin), Samples(kCountBin)};
  Samples object_offset_x_m_[2] = {Samples(kOffsetBin_m), Samples(kOffsetBin_m)};
  Samples object_offset_y_m_[2] = {Samples(kOffsetBin_m), Samples(kOffsetBin_m)};
};

}  // namespace rcsim::replay
