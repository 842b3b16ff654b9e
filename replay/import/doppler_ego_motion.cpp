#include "replay/import/doppler_ego_motion.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <random>

#include "common/range_rate_wrap.hpp"
#include "replay/import/annotation_smoothing.hpp"

namespace rcsim::replay {

namespace {

// Coefficients (c_x, c_y) of the sensor velocity in v_r = -(c_x v_Sx + c_y v_Sy).
Vec2 radial_direction(const DopplerTarget& t) {
  const double c = std::cos(t.elevation_rad);
  return {c * std::cos(t.azimuth_rad), c * std::sin(t.azimuth_rad)};
}

double residual_mps(const DopplerTarget& t, const Vec2& v_S_S) {
  return t.range_rate_mps + radial_direction(t).dot(v_S_S);
}

// Least squares of v_r = -(d . v) over the chosen targets.
std::optional<Vec2> least_squares_velocity(const std::vector<DopplerTarget>& targets,
                                           const std::vector<std::size_t>& chosen) {
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (const std::size_t i : chosen) {
    const Vec2 d = radial_direction(targets[i]);
    normal += d * d.transpose();
    rhs -= d * targets[i].range_rate_mps;
  }
  // Targets all in one direction leave the lateral component unknown.
  if (std::abs(normal.determinant()) < 1e-9 * (normal.trace() * normal.trace() + 1e-300)) return std::nullopt;
  return Vec2(normal.ldlt().solve(rhs));
}

std::vector<std::size_t> inliers_of(const std::vector<DopplerTarget>& targets, const Vec2& v_S_S, double threshold_mps) {
  std::vector<std::size_t> inliers;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (std::abs(residual_mps(targets[i], v_S_S)) <= threshold_mps) inliers.push_back(i);
  }
  return inliers;
}

double rms_mps(const std::vector<DopplerTarget>& targets, const std::vector<std::size_t>& chosen, const Vec2& v_S_S) {
  double sum_sq = 0.0;
  for (const std::size_t i : chosen) sum_sq += std::pow(residual_mps(targets[i], v_S_S), 2);
  return chosen.empty() ? 0.0 : std::sqrt(sum_sq / static_cast<double>(chosen.size()));
}

}  // namespace

SensorVelocityFit fit_sensor_velocity(const std::vector<DopplerTarget>& targets, const DopplerFitParameters& parameters) {
  SensorVelocityFit best;
  std::size_t best_count = 0;
  double best_rms = 0.0;
  // RANSAC with a pair as the minimal sample: the largest consensus, ties to the smaller RMS.
  const auto try_pair = [&](std::size_t a, std::size_t b) {
    const auto v = least_squares_velocity(targets, {a, b});
    if (!v) return;
    std::size_t count = 0;
    double sum_sq = 0.0;
    for (const DopplerTarget& t : targets) {
      const double r = residual_mps(t, *v);
      if (std::abs(r) <= parameters.inlier_threshold_mps) {
        ++count;
        sum_sq += r * r;
      }
    }
    const double rms = count > 0 ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
    if (count > best_count || (count == best_count && count > 0 && rms < best_rms)) {
      best.v_S_S = *v;
      best_count = count;
      best_rms = rms;
    }
  };
  const std::size_t n = targets.size();
  if (n >= 2 && n * (n - 1) / 2 <= parameters.max_hypotheses) {
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = a + 1; b < n; ++b) try_pair(a, b);
    }
  } else if (n >= 2) {
    std::mt19937_64 rng(0x5a4d0c1e);  // fixed: the same frame gives the same fit
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    for (std::size_t k = 0; k < parameters.max_hypotheses; ++k) {
      const std::size_t a = pick(rng), b = pick(rng);
      if (a != b) try_pair(a, b);
    }
  }
  if (best_count > 0) best.inliers = inliers_of(targets, best.v_S_S, parameters.inlier_threshold_mps);
  // Refit on the consensus, then once more on the refit's own inliers.
  for (int pass = 0; pass < 2 && best.inliers.size() >= 2; ++pass) {
    const auto v = least_squares_velocity(targets, best.inliers);
    if (!v) break;
    best.v_S_S = *v;
    best.inliers = inliers_of(targets, *v, parameters.inlier_threshold_mps);
  }
  best.residual_rms_mps = rms_mps(targets, best.inliers, best.v_S_S);
  best.valid = best.inliers.size() >= parameters.min_inliers;
  return best;
}

EgoMotionFit fit_ego_motion(const std::vector<std::vector<DopplerTarget>>& targets,
                            const std::vector<SensorVelocityFit>& fits, const std::vector<Pose2>& X_VS) {
  // v_r = -d_S . R(-psi) (v - w y_S, w x_S) = -(g_v v + g_w w), with g = R(psi) d_S in the vehicle frame.
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  std::vector<std::pair<Eigen::Vector2d, double>> rows;
  for (std::size_t s = 0; s < targets.size(); ++s) {
    if (!fits[s].valid) continue;
    for (const std::size_t i : fits[s].inliers) {
      const Vec2 d_V = rotate(X_VS[s].yaw_rad, radial_direction(targets[s][i]));
      const Eigen::Vector2d g(d_V.x(), -d_V.x() * X_VS[s].y_m + d_V.y() * X_VS[s].x_m);
      normal += g * g.transpose();
      rhs -= g * targets[s][i].range_rate_mps;
      rows.emplace_back(g, targets[s][i].range_rate_mps);
    }
  }
  EgoMotionFit fit;
  fit.inliers = rows.size();
  if (rows.size() < 2 || std::abs(normal.determinant()) < 1e-12) return fit;
  const Eigen::Vector2d x = normal.ldlt().solve(rhs);
  fit.speed_mps = x(0);
  fit.yaw_rate_radps = x(1);
  double sum_sq = 0.0;
  for (const auto& [g, v_r] : rows) sum_sq += std::pow(v_r + g.dot(x), 2);
  fit.residual_rms_mps = std::sqrt(sum_sq / static_cast<double>(rows.size()));
  fit.valid = true;
  return fit;
}

double speed_from_one_sensor_mps(const SensorVelocityFit& fit, const Pose2& X_VS) {
  const Vec2 v_S_V = rotate(X_VS.yaw_rad, fit.v_S_S);
  const double yaw_rate_radps = v_S_V.y() / X_VS.x_m;
  return v_S_V.x() + yaw_rate_radps * X_VS.y_m;
}

namespace {

struct SensorStats {
  double inliers = 0.0, targets = 0.0, residual_sq_sum = 0.0, fits = 0.0;
};

struct Summary {
  double mean = 0.0, std = 0.0;
};
Summary mean_and_std(const std::vector<double>& values) {
  Summary s;
  if (values.empty()) return s;
  for (const double v : values) s.mean += v;
  s.mean /= static_cast<double>(values.size());
  for (const double v : values) s.std += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(values.size()));
  return s;
}

// Poses from speed and yaw rate by the trapezoidal rule, starting at the origin.
void integrate_poses(std::vector<EgoSample>& samples) {
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const EgoSample& a = samples[k - 1];
    EgoSample& b = samples[k];
    const double dt_s = b.t_s - a.t_s;
    b.yaw_rad = a.yaw_rad + 0.5 * (a.yaw_rate_radps + b.yaw_rate_radps) * dt_s;
    const double yaw_mid = 0.5 * (a.yaw_rad + b.yaw_rad), speed = 0.5 * (a.speed_mps + b.speed_mps);
    b.x_m = a.x_m + speed * std::cos(yaw_mid) * dt_s;
    b.y_m = a.y_m + speed * std::sin(yaw_mid) * dt_s;
  }
}

}  // namespace

DopplerEgoTrack ego_track_from_doppler(const std::vector<double>& t_s,
                                       const std::vector<std::vector<std::vector<DopplerTarget>>>& targets,
                                       const std::vector<Pose2>& X_VS, const std::vector<std::string>& sensor_ids,
                                       const std::vector<double>* yaw_rate_radps, double half_window_s,
                                       const DopplerFitParameters& parameters) {
  const std::size_t n_sensors = X_VS.size();
  std::vector<SensorStats> stats(n_sensors);
  std::vector<double> fitted_t_s, fitted_speed, fitted_yaw_rate, joint_residual, speed_difference;
  std::vector<std::size_t> fitted_cycle;
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    std::vector<SensorVelocityFit> fits;
    for (std::size_t s = 0; s < n_sensors; ++s) {
      fits.push_back(fit_sensor_velocity(targets[k][s], parameters));
      stats[s].targets += static_cast<double>(targets[k][s].size());
      stats[s].inliers += static_cast<double>(fits[s].inliers.size());
      if (fits[s].valid) stats[s].residual_sq_sum += std::pow(fits[s].residual_rms_mps, 2), ++stats[s].fits;
    }
    // The sensors' agreement: the speed each one alone implies, against the first sensor's.
    for (std::size_t s = 1; s < n_sensors; ++s) {
      if (fits[0].valid && fits[s].valid && X_VS[0].x_m != 0.0 && X_VS[s].x_m != 0.0) {
        speed_difference.push_back(speed_from_one_sensor_mps(fits[0], X_VS[0]) - speed_from_one_sensor_mps(fits[s], X_VS[s]));
      }
    }
    const EgoMotionFit ego = fit_ego_motion(targets[k], fits, X_VS);
    if (!ego.valid) continue;
    fitted_cycle.push_back(k);
    fitted_t_s.push_back(t_s[k]);
    fitted_speed.push_back(ego.speed_mps);
    fitted_yaw_rate.push_back(ego.yaw_rate_radps);
    joint_residual.push_back(ego.residual_rms_mps);
  }
  DopplerEgoTrack track;
  if (fitted_cycle.empty()) return track;
  const std::vector<const std::vector<double>*> series{&fitted_speed, &fitted_yaw_rate};
  const auto smoothed = smooth_local_quadratic(fitted_t_s, series, half_window_s);
  track.samples.resize(t_s.size());
  std::vector<double> doppler_minus_used;
  std::size_t nearest = 0;  // index into fitted_cycle
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    while (nearest + 1 < fitted_cycle.size() &&
           std::abs(t_s[fitted_cycle[nearest + 1]] - t_s[k]) <= std::abs(t_s[fitted_cycle[nearest]] - t_s[k])) {
      ++nearest;
    }
    track.samples[k].t_s = t_s[k];
    track.samples[k].speed_mps = smoothed[0][nearest].value;
    track.samples[k].yaw_rate_radps = yaw_rate_radps != nullptr ? (*yaw_rate_radps)[k] : smoothed[1][nearest].value;
    doppler_minus_used.push_back(smoothed[1][nearest].value - track.samples[k].yaw_rate_radps);
  }
  integrate_poses(track.samples);
  if (fitted_cycle.size() < t_s.size()) {
    track.warnings.push_back(fmt::format("ego motion: {} of {} cycles had too few stationary targets and take their "
                                         "nearest fitted cycle's speed and yaw rate",
                                         t_s.size() - fitted_cycle.size(), t_s.size()));
  }

  const auto [speed_min, speed_max] = std::minmax_element(fitted_speed.begin(), fitted_speed.end());
  const auto [rate_min, rate_max] = std::minmax_element(fitted_yaw_rate.begin(), fitted_yaw_rate.end());
  const Summary residual = mean_and_std(joint_residual), difference = mean_and_std(speed_difference);
  nlohmann::json sensors = nlohmann::json::array();
  for (std::size_t s = 0; s < n_sensors; ++s) {
    sensors.push_back({{"id", sensor_ids[s]},
                       {"stationary_fraction", stats[s].targets > 0.0 ? stats[s].inliers / stats[s].targets : 0.0},
                       {"residual_rms_mps", stats[s].fits > 0.0 ? std::sqrt(stats[s].residual_sq_sum / stats[s].fits) : 0.0}});
  }
  track.report = {
      {"estimated", true},
      {"why", "the dataset has no ego log"},
      {"method", "Doppler of the stationary world (D. Kellner et al., Instantaneous ego-motion estimation using Doppler "
                 "radar, IEEE ITSC 2013): per sensor and cycle RANSAC over every pair of targets, then speed and yaw "
                 "rate from all sensors' stationary targets with no lateral speed at the vehicle origin"},
      {"inlier_threshold_mps", parameters.inlier_threshold_mps},
      {"smoothing", fmt::format("local quadratic regression, tricube weights, +-{} s", half_window_s)},
      {"cycles", t_s.size()},
      {"cycles_fitted", fitted_cycle.size()},
      {"residual_rms_mps", residual.mean},
      {"speed_mps", {{"min", *speed_min}, {"max", *speed_max}}},
      {"yaw_rate_source", yaw_rate_radps != nullptr ? "given (the annotated vehicles' heading drift)" : "Doppler"},
      {"doppler_yaw_rate_radps", {{"min", *rate_min}, {"max", *rate_max}}},
      {"doppler_yaw_rate_minus_used_radps", {{"mean", mean_and_std(doppler_minus_used).mean},
                                             {"std", mean_and_std(doppler_minus_used).std}}},
      {"sensors", sensors},
      {"speed_difference_mps",
       {{"between", n_sensors > 1 ? sensor_ids[0] + " and the others, each alone" : std::string("-")},
        {"cycles", speed_difference.size()},
        {"mean", difference.mean},
        {"std", difference.std}}}};
  return track;
}

AliasedSpeedFit fit_speed_aliased(const std::vector<DopplerTarget>& targets, double yaw_VS_rad, double min_mps,
                                  double max_mps, const AliasedSpeedParameters& parameters) {
  constexpr double kBin_mps = 0.05;
  const double width_mps = max_mps - min_mps;
  const auto bins = static_cast<std::size_t>(std::ceil(parameters.max_speed_mps / kBin_mps)) + 1;
  std::vector<std::size_t> votes(bins, 0);
  std::vector<double> cos_line(targets.size(), 0.0);  // cos of the angle between line of sight and driving direction
  AliasedSpeedFit fit;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const DopplerTarget& t = targets[i];
    cos_line[i] = std::cos(t.elevation_rad) * std::cos(t.azimuth_rad + yaw_VS_rad);
    if (!(cos_line[i] >= parameters.min_cos)) continue;
    ++fit.candidates;
    // v = -(range_rate + k width) / cos for every k with v in [0, max_speed].
    const double c = cos_line[i];
    const auto k_first = static_cast<long>(std::ceil((-parameters.max_speed_mps * c - t.range_rate_mps) / width_mps));
    const auto k_last = static_cast<long>(std::floor(-t.range_rate_mps / width_mps));
    for (long k = k_first; k <= k_last; ++k) {
      const double v_mps = -(t.range_rate_mps + static_cast<double>(k) * width_mps) / c;
      const auto bin = static_cast<std::size_t>(std::lround(v_mps / kBin_mps));
      if (bin < bins) ++votes[bin];
    }
  }
  std::size_t best_bin = 0, best_votes = 0;
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t around = votes[b] + (b > 0 ? votes[b - 1] : 0) + (b + 1 < bins ? votes[b + 1] : 0);
    if (around > best_votes) {
      best_votes = around;
      best_bin = b;
    }
  }
  if (best_votes == 0) return fit;
  // Least squares over the inliers of the bin's speed, each unwrapped next to its prediction.
  const double v0_mps = static_cast<double>(best_bin) * kBin_mps;
  double sum_cr = 0.0, sum_cc = 0.0;
  std::vector<std::pair<double, double>> inliers;  // (cos, unwrapped range rate)
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!(cos_line[i] >= parameters.min_cos)) continue;
    const double predicted_mps = -v0_mps * cos_line[i];
    const double difference_mps = wrap_range_rate_mps(targets[i].range_rate_mps - predicted_mps, -0.5 * width_mps, 0.5 * width_mps);
    if (std::abs(difference_mps) > parameters.inlier_threshold_mps) continue;
    inliers.emplace_back(cos_line[i], predicted_mps + difference_mps);
    sum_cr += cos_line[i] * (predicted_mps + difference_mps);
    sum_cc += cos_line[i] * cos_line[i];
  }
  fit.inliers = inliers.size();
  if (inliers.empty()) return fit;
  fit.speed_mps = -sum_cr / sum_cc;
  double sum_sq = 0.0;
  for (const auto& [c, range_rate_mps] : inliers) sum_sq += (range_rate_mps + fit.speed_mps * c) * (range_rate_mps + fit.speed_mps * c);
  fit.residual_rms_mps = std::sqrt(sum_sq / static_cast<double>(inliers.size()));
  fit.valid = fit.inliers >= parameters.min_inliers &&
              static_cast<double>(fit.inliers) >= parameters.min_inlier_share * static_cast<double>(fit.candidates);
  return fit;
}

}  // namespace rcsim::replay
