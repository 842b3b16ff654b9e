#include "replay/profile/detection_pool.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/input_error.hpp"
#include "common/range_rate_wrap.hpp"
#include "replay/import/doppler_ego_motion.hpp"

namespace rcsim::replay::profile {
namespace {

constexpr int kMinCycles = 2;
constexpr long long kMinDetections = 100;

double cos_elevation(const PooledDetection& d) { return std::isnan(d.elevation_rad) ? 1.0 : std::cos(d.elevation_rad); }

// Kellner's first step on one cycle (a radar without aliasing): the stationary targets and the
// sensor's velocity; each inlier keeps its residual.
void fit_stationary(PooledCycle& cycle) {
  std::vector<DopplerTarget> targets;
  for (const PooledDetection& d : cycle.detections) targets.push_back({d.azimuth_rad, std::isnan(d.elevation_rad) ? 0.0 : d.elevation_rad, d.range_rate_mps});
  const SensorVelocityFit fit = fit_sensor_velocity(targets, {});
  if (!fit.valid) return;
  cycle.valid_fit = true;
  cycle.v_S_S = fit.v_S_S;
  for (const std::size_t i : fit.inliers) {
    PooledDetection& d = cycle.detections[i];
    // v_r = -cos(el) (v_x cos az + v_y sin az): doppler_ego_motion.hpp.
    const double predicted_mps = -cos_elevation(d) * (fit.v_S_S.x() * std::cos(d.azimuth_rad) + fit.v_S_S.y() * std::sin(d.azimuth_rad));
    d.stationary_residual_mps = std::abs(d.range_rate_mps - predicted_mps);
  }
}

// The same for a radar whose Doppler aliases: the speed along the vehicle's axis, wrapped.
void fit_stationary_aliased(PooledCycle& cycle, const RangeRateInterval& interval) {
  std::vector<DopplerTarget> targets;
  for (const PooledDetection& d : cycle.detections) targets.push_back({d.azimuth_rad, std::isnan(d.elevation_rad) ? 0.0 : d.elevation_rad, d.range_rate_mps});
  const AliasedSpeedParameters parameters;
  const AliasedSpeedFit fit = fit_speed_aliased(targets, cycle.X_VS.yaw_rad, interval.min_mps, interval.max_mps, parameters);
  if (!fit.valid) return;
  cycle.valid_fit = true;
  cycle.v_S_S = rotate(-cycle.X_VS.yaw_rad, Vec2(fit.speed_mps, 0.0));
  for (PooledDetection& d : cycle.detections) {
    const double predicted_mps = -fit.speed_mps * cos_elevation(d) * std::cos(d.azimuth_rad + cycle.X_VS.yaw_rad);
    const double difference_mps = wrap_range_rate_mps(d.range_rate_mps - predicted_mps + 0.5 * (interval.min_mps + interval.max_mps),
                                                      interval.min_mps, interval.max_mps) -
                                  0.5 * (interval.min_mps + interval.max_mps);
    if (std::abs(difference_mps) <= parameters.inlier_threshold_mps) d.stationary_residual_mps = std::abs(difference_mps);
  }
}

void check_sensors(const Recording& r, DetectionPool& pool, bool first) {
  for (const RecordingSensor& s : r.sensors) {
    if (s.reports != ListLevel::detections) {
      throw InputError(r.dir.string(), fmt::format("sensor {}", s.id),
                       "reports tracks; a profile is derived from raw detections (a recording whose sensors report "
                       "\"detections\", schemas/recording.md)");
    }
    if (first && &s == &r.sensors.front()) {
      pool.sensor_type = s.type, pool.amplitude_unit = s.amplitude_unit, pool.range_rate_interval_mps = s.range_rate_interval_mps;
      continue;
    }
    if (s.type != pool.sensor_type || s.amplitude_unit != pool.amplitude_unit ||
        s.range_rate_interval_mps.has_value() != pool.range_rate_interval_mps.has_value()) {
      throw InputError(r.dir.string(), fmt::format("sensor {}", s.id),
                       fmt::format("is of type \"{}\", the first sensor of \"{}\": one profile is derived from one "
                                   "kind of radar (give its recordings only)",
                                   s.type, pool.sensor_type));
    }
  }
}

}  // namespace

DetectionPool pool_detections(const std::vector<const Recording*>& recordings) {
  DetectionPool pool;
  for (const Recording* r : recordings) {
    check_sensors(*r, pool, pool.recordings == 0);
    if (pool.recordings == 0) pool.recorded_cycle_time_s = r->cycle_time_s;
    pool.snapshots = pool.snapshots || r->timeline == Timeline::snapshots;
    const std::size_t first = pool.cycles.size();
    // One pooled cycle per sensor and cycle: every sensor's in each cycle of a shared clock, the
    // one sensor's of a cycle on its own clock.
    const bool own_clocks = r->clock == Clock::per_sensor;
    std::vector<int> cycles_of_sensor(r->sensors.size(), 0);
    for (int k = 0; k < r->cycle_count(); ++k) {
      for (int s = 0; s < static_cast<int>(r->sensors.size()); ++s) {
        if (own_clocks && r->cycle_sensor(k) != s) continue;
        const EgoSample e = r->ego_at_cycle(k);
        const RecordingSensor& sensor = r->sensors[static_cast<std::size_t>(s)];
        PooledCycle& cycle = pool.cycles.emplace_back();
        cycle.recording = pool.recordings, cycle.sensor = s, cycle.cycle = k, cycle.t_s = e.t_s;
        cycle.sensor_cycle = cycles_of_sensor[static_cast<std::size_t>(s)]++;
        cycle.X_WV = {e.x_m, e.y_m, e.yaw_rad}, cycle.X_VS = {sensor.x_m, sensor.y_m, sensor.yaw_rad};
      }
    }
    const std::size_t sensors = r->sensors.size();
    for (const RecordedTarget& t : r->targets) {
      const std::size_t k = static_cast<std::size_t>(t.cycle);
      PooledCycle& cycle = pool.cycles[first + (own_clocks ? k : k * sensors + static_cast<std::size_t>(t.sensor))];
      cycle.detections.push_back({t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db, t.rcs_dbsm, t.elevation_rad});
      ++pool.detections;
    }
    ++pool.recordings;
  }
  const std::string names = recordings.size() == 1 ? recordings.front()->dir.string() : fmt::format("{} recordings", recordings.size());
  const std::size_t cycles = pool.cycles.size();
  if (cycles < kMinCycles) throw InputError(names, "", fmt::format("{} sensor cycle(s): a profile needs at least {}", cycles, kMinCycles));
  if (pool.detections < kMinDetections) {
    throw InputError(names, "targets.csv", fmt::format("{} detection(s): a profile needs at least {}", pool.detections, kMinDetections));
  }
  double min_range_m = INFINITY, max_range_m = -INFINITY, min_azimuth_rad = INFINITY, max_azimuth_rad = -INFINITY;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) {
      min_range_m = std::min(min_range_m, d.range_m), max_range_m = std::max(max_range_m, d.range_m);
      min_azimuth_rad = std::min(min_azimuth_rad, d.azimuth_rad), max_azimuth_rad = std::max(max_azimuth_rad, d.azimuth_rad);
    }
  }
  if (max_range_m - min_range_m < 1.0 || max_azimuth_rad - min_azimuth_rad < 1e-3) {
    throw InputError(names, "targets.csv",
                     fmt::format("every detection lies at one range ({:.3f}-{:.3f} m) or one azimuth ({:.5f}-{:.5f} rad): "
                                 "nothing of the radar's view, law or cells can be read",
                                 min_range_m, max_range_m, min_azimuth_rad, max_azimuth_rad));
  }
  for (PooledCycle& c : pool.cycles) {
    if (pool.range_rate_interval_mps) {
      fit_stationary_aliased(c, *pool.range_rate_interval_mps);
    } else {
      fit_stationary(c);
    }
  }
  return pool;
}

}  // namespace rcsim::replay::profile
