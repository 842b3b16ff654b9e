#pragma once
// The detections of the recordings a profile is derived from, per sensor cycle, with what every
// stage needs besides: which ones the stationary world explains (Kellner's Doppler fit, or its
// aliased form for a radar with a small unambiguous interval) and how far from it.
#include <optional>
#include <string>
#include <vector>

#include "common/amplitude_unit.hpp"
#include "common/pose2.hpp"
#include "io/recording.hpp"

namespace rcsim::replay::profile {

struct PooledDetection {
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
  double rcs_dbsm = RecordedTarget::kNoValue, elevation_rad = RecordedTarget::kNoValue;
  // |measured - predicted| radial speed of the cycle's stationary fit; NaN: not taken as stationary.
  double stationary_residual_mps = RecordedTarget::kNoValue;
  bool stationary() const { return stationary_residual_mps == stationary_residual_mps; }
};
inline double range_of(const PooledDetection& d) { return d.range_m; }
inline double range_rate_of(const PooledDetection& d) { return d.range_rate_mps; }

// One sensor's detections of one cycle.
struct PooledCycle {
  int recording = 0, sensor = 0, cycle = 0;
  int sensor_cycle = 0;    // the sensor's own count of its cycles (its clock's: cycle itself on a shared clock)
  double t_s = 0.0;
  Pose2 X_WV;              // the ego in the world at the cycle (ego.csv)
  Pose2 X_VS;              // the sensor's mounting
  Vec2 v_S_S = Vec2::Zero();  // the sensor's velocity over the ground from the stationary fit (valid_fit)
  bool valid_fit = false;
  std::vector<PooledDetection> detections;
};

struct DetectionPool {
  std::vector<PooledCycle> cycles;  // every recording's sensor cycles, in order
  long long detections = 0;
  std::string sensor_type;          // the sensors' one type
  AmplitudeUnit amplitude_unit = AmplitudeUnit::snr_db;
  std::optional<RangeRateInterval> range_rate_interval_mps;
  bool snapshots = false;            // some recording is a set of single frames (no frame follows another)
  double recorded_cycle_time_s = 0.0;  // the recordings' header clock (the first's)
  int recordings = 0;
};

// Pools the detections of every sensor; refuses (InputError naming the recording and what is
// missing) recordings of tracks only, sensors of different types or units, fewer than 2 cycles or
// 100 detections, and detections that all lie at one range or one azimuth.
DetectionPool pool_detections(const std::vector<const Recording*>& recordings);

}  // namespace rcsim::replay::profile
