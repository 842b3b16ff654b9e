#pragma once
// The ego vehicle's motion from the Doppler of the stationary world, for recordings whose ego log
// is missing (D. Kellner, M. Barjenbruch, J. Klappstein, J. Dickmann, K. Dietmayer,
// "Instantaneous ego-motion estimation using Doppler radar", IEEE ITSC 2013).
//
// A stationary target seen by a sensor moving with velocity v_S (sensor frame) has the radial
// speed v_r = -cos(el) (v_Sx cos(az) + v_Sy sin(az)) (negative approaching). Per sensor and cycle
// the stationary targets are found by RANSAC over that model; since a cycle holds only tens of
// targets, every pair of targets is tried as the minimal sample (deterministic, no random draws).
// Then all sensors' inliers give the vehicle's motion at once, under Kellner's Ackermann
// condition (no lateral speed at the vehicle frame's origin, the rear axle): a sensor mounted at
// p_VS with yaw psi moves with v_S^V = (v - w y_S, w x_S), so v_r is linear in (v, w).
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/pose2.hpp"
#include "io/recording.hpp"

namespace rcsim::replay {

// One detection as a sensor reported it.
struct DopplerTarget {
  double azimuth_rad = 0.0, elevation_rad = 0.0, range_rate_mps = 0.0;
};

struct SensorVelocityFit {
  Vec2 v_S_S = Vec2::Zero();  // the sensor's velocity over the ground, in its own frame
  std::vector<std::size_t> inliers;  // indices of the targets taken as stationary
  double residual_rms_mps = 0.0;     // over the inliers
  bool valid = false;                // at least min_inliers stationary targets
};

struct DopplerFitParameters {
  double inlier_threshold_mps = 0.2;  // |measured - predicted| radial speed of a stationary target
  std::size_t min_inliers = 5;
  // RANSAC's hypotheses: every pair of targets while there are at most this many pairs (64 targets),
  // else this many pairs drawn with a fixed seed. The cost is hypotheses x targets, linear in the
  // targets of a frame (an imaging radar gives 10,000).
  std::size_t max_hypotheses = 2048;
};

// Kellner's first step: the velocity of one sensor from its targets of one cycle.
SensorVelocityFit fit_sensor_velocity(const std::vector<DopplerTarget>& targets, const DopplerFitParameters& parameters);

struct EgoMotionFit {
  double speed_mps = 0.0;        // along the vehicle's x axis, at the vehicle frame's origin
  double yaw_rate_radps = 0.0;
  double residual_rms_mps = 0.0;  // of all sensors' inliers under the joint motion
  std::size_t inliers = 0;
  bool valid = false;
};

// Kellner's second step for several sensors: the vehicle motion (speed, yaw rate) that explains
// every sensor's stationary targets. `targets[s]` are sensor s's targets, `fits[s]` its first step,
// `X_VS[s]` its mounting.
EgoMotionFit fit_ego_motion(const std::vector<std::vector<DopplerTarget>>& targets,
                            const std::vector<SensorVelocityFit>& fits, const std::vector<Pose2>& X_VS);

// The vehicle speed one sensor alone implies under the Ackermann condition: its velocity in the
// vehicle frame is (v - w y_S, w x_S), so w = v_y / x_S and v = v_x + w y_S (needs x_S != 0).
double speed_from_one_sensor_mps(const SensorVelocityFit& fit, const Pose2& X_VS);

// The ego log of a recording without one: per cycle Kellner's two steps over all sensors, the
// speed and yaw rate smoothed over time (local quadratic regression, +-half_window_s; a cycle
// without a fit takes its nearest fitted neighbour's), and the pose integrated from the origin.
// The Doppler yaw rate rests on the sensors' lateral speeds over the lever arm between them: a
// relative boresight error of 0.5 deg at 30 m/s is 0.26 m/s of lateral speed, 0.05 rad/s over
// 5 m. Where a better yaw rate is known (`yaw_rate_radps`, one per cycle), it is used instead
// and the Doppler one only reported beside it.
struct DopplerEgoTrack {
  std::vector<EgoSample> samples;  // one per cycle; empty when no cycle could be fitted
  nlohmann::json report;           // method, residuals, inliers, the sensors' agreement
  std::vector<std::string> warnings;
};
// targets[k][s]: sensor s's targets in cycle k at time t_s[k].
DopplerEgoTrack ego_track_from_doppler(const std::vector<double>& t_s,
                                       const std::vector<std::vector<std::vector<DopplerTarget>>>& targets,
                                       const std::vector<Pose2>& X_VS, const std::vector<std::string>& sensor_ids,
                                       const std::vector<double>* yaw_rate_radps = nullptr,
                                       double half_window_s = 0.5, const DopplerFitParameters& parameters = {});

// The speed of a vehicle driving straight, from one radar whose Doppler aliases (an imaging radar's
// small unambiguous interval [min_mps, max_mps)): a stationary target at azimuth az and elevation
// el (sensor frame; the sensor yawed by yaw_VS on the vehicle) has the radial speed
// -v cos(el) cos(az + yaw_VS), read wrapped into the interval. Each target with cos(el) cos(az +
// yaw_VS) >= min_cos votes for every v in [0, max_speed_mps] that explains it; the most voted
// 0.05-m/s bin (with its neighbours) is refined by least squares over its inliers (|wrapped
// difference| <= inlier_threshold_mps), each unwrapped next to the bin's prediction. Several
// widths of the interval can explain one target, but only the true v aligns targets at many
// angles. Without yaw rate: a turning vehicle's lateral speed is not modelled.
struct AliasedSpeedFit {
  double speed_mps = 0.0;
  std::size_t inliers = 0, candidates = 0;  // candidates: the targets that voted
  double residual_rms_mps = 0.0;            // over the inliers
  bool valid = false;                       // at least min_inliers and min_inlier_share of the candidates
};
struct AliasedSpeedParameters {
  double max_speed_mps = 40.0;
  double min_cos = 0.3;  // targets further off the driving direction say little about v and alias more
  double inlier_threshold_mps = 0.1;
  std::size_t min_inliers = 20;
  double min_inlier_share = 0.1;
};
AliasedSpeedFit fit_speed_aliased(const std::vector<DopplerTarget>& targets, double yaw_VS_rad, double min_mps,
                                  double max_mps, const AliasedSpeedParameters& parameters = {});

}  // namespace rcsim::replay
