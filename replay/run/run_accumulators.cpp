#include "replay/run/run_accumulators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angles.hpp"

namespace rcsim::replay {

void RunAccumulators::add_cycle(const CycleComparison& cycle, long long merge_recorded, long long merge_simulated) {
  for (const ComparedTarget& a : cycle.recorded) {
    if (a.match < 0) continue;
    const ComparedTarget& b = cycle.simulated[static_cast<std::size_t>(a.match)];
    range_sq_m2_ += std::pow(b.range_m - a.range_m, 2);
    azimuth_sq_rad2_ += std::pow(angle_difference_rad(b.azimuth_rad, a.azimuth_rad), 2);
    rate_sq_m2ps2_ += std::pow(b.range_rate_mps - a.range_rate_mps, 2);
    amplitude_sum_db_ += b.amplitude_db - a.amplitude_db;
    ++targets_matched_;
    if (a.target_class == metrics::TargetClass::object && b.target_class == metrics::TargetClass::object &&
        a.object == b.object) {
      object_range_sq_m2_ += std::pow(b.range_m - a.range_m, 2);
      object_azimuth_sq_rad2_ += std::pow(angle_difference_rad(b.azimuth_rad, a.azimuth_rad), 2);
      ++object_pairs_;
    }
  }
  merge_recorded_ += merge_recorded;
  merge_simulated_ += merge_simulated;
  merge_matched_ += cycle.merge_matched;
  targets_recorded_ += static_cast<long long>(cycle.recorded.size());
  targets_simulated_ += static_cast<long long>(cycle.simulated.size());
  gospa_sum_ += cycle.gospa.gospa_m;
  ospa_sum_ += cycle.gospa.ospa_m;
  localisation_sum_ += cycle.gospa.localisation_mp;
  missed_sum_ += cycle.gospa.missed_mp;
  false_sum_ += cycle.gospa.false_mp;
  gospa_object_sum_ += cycle.gospa_object.gospa_m;
  ospa_object_sum_ += cycle.gospa_object.ospa_m;
  ++sensor_cycles_;
  for (int origin = 0; origin < 2; ++origin) {
    const auto& list = origin == 0 ? cycle.recorded : cycle.simulated;
    int background = 0;
    for (const auto& t : list) {
      range_m_[origin].add(static_cast<float>(t.range_m));
      azimuth_rad_[origin].add(static_cast<float>(t.azimuth_rad));
      if (compare_range_rates_) rate_mps_[origin].add(static_cast<float>(t.range_rate_mps));
      amplitude_db_[origin].add(static_cast<float>(t.amplitude_db));
      switch (t.target_class) {
        case metrics::TargetClass::object:
          ++classes_.object[origin];
          object_offset_x_m_[origin].add(static_cast<float>(t.p_OT_O.x()));
          object_offset_y_m_[origin].add(static_cast<float>(t.p_OT_O.y()));
          break;
        case metrics::TargetClass::other: ++classes_.other[origin]; break;
        case metrics::TargetClass::stationary_background:
          ++classes_.background[origin];
          ++background;
          background_range_m_[origin].add(static_cast<float>(t.range_m));
          background_azimuth_rad_[origin].add(static_cast<float>(t.azimuth_rad));
          break;
      }
    }
    count_[origin].add(static_cast<float>(list.size()));
    background_count_[origin].add(static_cast<float>(background));
  }
}

void RunAccumulators::finish(ReplaySummary& summary) {
  summary.targets_recorded = targets_recorded_;
  summary.targets_simulated = targets_simulated_;
  summary.targets_matched = targets_matched_;
  summary.merge_artefacts_recorded = merge_recorded_;
  summary.merge_artefacts_simulated = merge_simulated_;
  summary.merge_artefacts_matched = merge_matched_;
  const double n = std::max<double>(1.0, static_cast<double>(sensor_cycles_));
  summary.gospa_mean_m = gospa_sum_ / n;
  summary.ospa_mean_m = ospa_sum_ / n;
  summary.gospa_localisation_mean_mp = localisation_sum_ / n;
  summary.gospa_missed_mean_mp = missed_sum_ / n;
  summary.gospa_false_mean_mp = false_sum_ / n;
  summary.gospa_object_mean_m = gospa_object_sum_ / n;
  summary.ospa_object_mean_m = ospa_object_sum_ / n;
  summary.classes = classes_;
  const double m = std::max<double>(1.0, static_cast<double>(targets_matched_));
  summary.residual_range_rms_m = std::sqrt(range_sq_m2_ / m);
  summary.residual_azimuth_rms_rad = std::sqrt(azimuth_sq_rad2_ / m);
  summary.residual_range_rate_rms_mps =
      compare_range_rates_ ? std::sqrt(rate_sq_m2ps2_ / m) : std::numeric_limits<double>::quiet_NaN();
  summary.residual_amplitude_mean_db = amplitude_sum_db_ / m;
  summary.object_pairs_matched = object_pairs_;
  const double m_object = std::max<double>(1.0, static_cast<double>(object_pairs_));
  summary.residual_object_range_rms_m = std::sqrt(object_range_sq_m2_ / m_object);
  summary.residual_object_azimuth_rms_rad = std::sqrt(object_azimuth_sq_rad2_ / m_object);

  // Each of kComparedQuantities, in its order: [0] recorded, [1] simulated.
  const std::array<const Samples*, kComparedQuantities.size()> samples = {
      range_m_,           azimuth_rad_,           rate_mps_,        amplitude_db_,     count_,
      background_range_m_, background_azimuth_rad_, background_count_, object_offset_x_m_, object_offset_y_m_};
  for (std::size_t q = 0; q < kComparedQuantities.size(); ++q) {
    summary.distances.push_back({std::string(kComparedQuantities[q].name), std::string(kComparedQuantities[q].unit),
                                 metrics::distribution_distance(samples[q][0], samples[q][1])});
  }
}

}  // namespace rcsim::replay
