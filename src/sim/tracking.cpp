#include "sim/tracking.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim {

KalmanModel::KalmanModel(const TrackerConfig& c, double dt) {
  F.setIdentity();
  F(0, 1) = dt;
  const double qa = c.process_accel_sigma_mps2 * c.process_accel_sigma_mps2;
  Q.setZero();
  // Discrete white-noise acceleration for [range, range rate] (Blackman [3]).
  Q(0, 0) = qa * dt * dt * dt * dt / 4.0;
  Q(0, 1) = Q(1, 0) = qa * dt * dt * dt / 2.0;
  Q(1, 1) = qa * dt * dt;
  Q(2, 2) = c.process_azimuth_rate_sigma_radps * c.process_azimuth_rate_sigma_radps * dt * dt;
  Q(3, 3) = c.process_amplitude_sigma_db * c.process_amplitude_sigma_db;  // per cycle
  R.setZero();
  R(0, 0) = c.measurement_sigma_range_m * c.measurement_sigma_range_m;
  R(1, 1) = c.measurement_sigma_range_rate_mps * c.measurement_sigma_range_rate_mps;
  R(2, 2) = c.measurement_sigma_azimuth_rad * c.measurement_sigma_azimuth_rad;
  R(3, 3) = c.measurement_sigma_amplitude_db * c.measurement_sigma_amplitude_db;
}

// F, Q, R and the initial P are block-diagonal in (range, range rate) | azimuth | amplitude, so P
// stays block-diagonal and the filter splits exactly into a 2-state and two 1-state filters; the
// code below is the 4x4 filter written block by block.
void kalman_predict(const KalmanModel& model, Track& track) {
  track.x(0) += model.F(0, 1) * track.x(1);
  track.x(2) = wrap_angle_rad(track.x(2));
  const Eigen::Matrix2d F2 = model.F.topLeftCorner<2, 2>();
  Eigen::Matrix2d P2 = F2 * track.P.topLeftCorner<2, 2>() * F2.transpose() + model.Q.topLeftCorner<2, 2>();
  track.P.topLeftCorner<2, 2>() = 0.5 * (P2 + P2.transpose());
  track.P(2, 2) += model.Q(2, 2);
  track.P(3, 3) += model.Q(3, 3);
}

Eigen::Vector4d innovation(const Track& track, const Detection& d) {
  return {d.range_m - track.x(0), d.range_rate_mps - track.x(1), angle_difference_rad(d.azimuth_rad, track.x(2)),
          d.amplitude_db - track.x(3)};
}

double mahalanobis2(const KalmanModel& model, const Track& track, const Eigen::Vector4d& nu) {
  // (range, range rate): S = P + R is symmetric, S^-1 = [s11 -s01; -s01 s00] / det, written out
  // (through Eigen's 2x2 inverse GCC's vectorizer stalls on store forwarding).
  const double s00 = track.P(0, 0) + model.R(0, 0);
  const double s01 = track.P(0, 1) + model.R(0, 1);
  const double s11 = track.P(1, 1) + model.R(1, 1);
  const double det = s00 * s11 - s01 * s01;
  const double range_part = (s11 * nu(0) * nu(0) - 2.0 * s01 * nu(0) * nu(1) + s00 * nu(1) * nu(1)) / det;
  return range_part + nu(2) * nu(2) / (track.P(2, 2) + model.R(2, 2)) +
         nu(3) * nu(3) / (track.P(3, 3) + model.R(3, 3));
}

void kalman_update(const KalmanModel& model, const Detection& detection, Track& track) {
  const Eigen::Vector4d nu = innovation(track, detection);
  // (range, range rate): K = P S^-1, Joseph form P = (I-K) P (I-K)' + K R K'.
  const Eigen::Matrix2d P2 = track.P.topLeftCorner<2, 2>();
  const Eigen::Matrix2d R2 = model.R.topLeftCorner<2, 2>();
  const Eigen::Matrix2d K2 = P2 * (P2 + R2).inverse();
  track.x.head<2>() += K2 * nu.head<2>();
  const Eigen::Matrix2d I_K = Eigen::Matrix2d::Identity() - K2;
  const Eigen::Matrix2d P2_new = I_K * P2 * I_K.transpose() + K2 * R2 * K2.transpose();
  track.P.topLeftCorner<2, 2>() = 0.5 * (P2_new + P2_new.transpose());
  // azimuth and amplitude: scalar Joseph form p = (1-k)^2 p + k^2 r.
  for (int i = 2; i < 4; ++i) {
    const double p = track.P(i, i), r = model.R(i, i);
    const double k = p / (p + r);
    track.x(i) += k * nu(i);
    track.P(i, i) = (1.0 - k) * (1.0 - k) * p + k * k * r;
  }
  track.x(2) = wrap_angle_rad(track.x(2));
}

Tracker::Tracker(const TrackerConfig& config, double cycle_time_s) : config_(config), model_(config, cycle_time_s) {
  tracks_.reserve(static_cast<std::size_t>(config.max_tracks));
  candidates_.reserve(static_cast<std::size_t>(config.max_tracks) * 16);
  detection_taken_.reserve(256);
  detections_by_range_.reserve(256);
}

void Tracker::predict() {
  for (auto& t : tracks_) {
    kalman_predict(model_, t);
    t.updated = false;
    ++t.age_cycles;
  }
}

void Tracker::associate(const Detections& detections) {
  // Gater: every (track, detection) pair inside the chi-square gate.
  candidates_.clear();
  detections_by_range_.clear();
  for (std::size_t j = 0; j < detections.size(); ++j) {
    detections_by_range_.push_back({detections[j].range_m, static_cast<int>(j)});
  }
  std::sort(detections_by_range_.begin(), detections_by_range_.end(),
            [](const RangeEntry& a, const RangeEntry& b) { return a.range_m < b.range_m; });
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    // For a positive definite S, nu' S^-1 nu >= nu_r^2 / S_rr: the range innovation alone rules
    // most pairs out exactly, before any solve. Only detections in a window twice that gate are
    // looked at (so that rounding cannot leave one out), found by bisection: O(n log n), not O(n^2).
    const double range_gate_m2 = config_.gate_chi2 * (tracks_[i].P(0, 0) + model_.R(0, 0));
    const double window_m = 2.0 * std::sqrt(range_gate_m2);
    const double track_range_m = tracks_[i].x(0);
    auto it = std::lower_bound(detections_by_range_.begin(), detections_by_range_.end(), track_range_m - window_m,
                               [](const RangeEntry& e, double range_m) { return e.range_m < range_m; });
    for (; it != detections_by_range_.end() && it->range_m <= track_range_m + window_m; ++it) {
      const auto j = static_cast<std::size_t>(it->detection);
      const double range_innovation_m = detections[j].range_m - track_range_m;
      if (range_innovation_m * range_innovation_m > range_gate_m2) continue;
      const Eigen::Vector4d nu = innovation(tracks_[i], detections[j]);
      const double d2 = mahalanobis2(model_, tracks_[i], nu);
      if (d2 <= config_.gate_chi2) candidates_.push_back({d2, static_cast<int>(i), static_cast<int>(j)});
    }
  }
  // Associator: global nearest neighbour, greedily by distance with a total order. When no two
  // candidates share a track or a detection (the usual case), every one of them is taken whatever
  // the order, so the sort is skipped. Candidates come track by track: a shared track is adjacent.
  detection_taken_.assign(detections.size(), 0);
  bool shared = false;
  for (std::size_t k = 0; k < candidates_.size(); ++k) {
    char& seen = detection_taken_[static_cast<std::size_t>(candidates_[k].detection)];
    shared = shared || seen || (k > 0 && candidates_[k].track == candidates_[k - 1].track);
    seen = 1;
  }
  if (shared) {
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
      if (a.distance2 != b.distance2) return a.distance2 < b.distance2;
      if (a.track != b.track) return a.track < b.track;
      return a.detection < b.detection;
    });
  }
  detection_taken_.assign(detections.size(), 0);
  for (const auto& c : candidates_) {
    Track& track = tracks_[static_cast<std::size_t>(c.track)];
    if (track.updated || detection_taken_[static_cast<std::size_t>(c.detection)]) continue;
    const Detection& d = detections[static_cast<std::size_t>(c.detection)];
    kalman_update(model_, d, track);  // updater
    track.updated = true;
    track.object_index = d.object_index;
    track.elevation_rad = d.elevation_rad;
    ++track.hits;
    track.misses = 0;
    confirm_if_due(track);
    detection_taken_[static_cast<std::size_t>(c.detection)] = 1;
  }
  for (auto& t : tracks_) {
    if (!t.updated) ++t.misses;
  }
}

void Tracker::confirm_if_due(Track& track) const {
  // Paper III-E: a track is confirmed (and reported from then on) after confirmation_hits hits.
  if (track.hits >= config_.confirmation_hits) track.status = TrackStatus::Confirmed;
}

void Tracker::initiate(const Detections& detections) {
  for (std::size_t j = 0; j < detections.size(); ++j) {
    if (detection_taken_[j]) continue;
    if (tracks_.size() >= static_cast<std::size_t>(config_.max_tracks)) {
      ++dropped_initiations_;
      continue;
    }
    const Detection& d = detections[j];
    Track t;
    t.id = next_id_++;
    t.hits = 1;
    t.updated = true;
    t.object_index = d.object_index;
    t.x << d.range_m, d.range_rate_mps, d.azimuth_rad, d.amplitude_db;
    t.elevation_rad = d.elevation_rad;
    t.P = model_.R;
    confirm_if_due(t);
    tracks_.push_back(t);
  }
}

void Tracker::delete_stale() {
  std::erase_if(tracks_, [&](const Track& t) {
    const int allowed = t.status == TrackStatus::Confirmed ? config_.max_misses_confirmed : config_.max_misses_tentative;
    return t.misses > allowed;
  });
}

void Tracker::step(const Detections& detections, ReportedTargets& reported) {
  predict();
  associate(detections);
  initiate(detections);
  delete_stale();
  reported.clear();
  for (const auto& t : tracks_) {
    if (t.status != TrackStatus::Confirmed || !t.updated) continue;
    reported.push_back({t.id, std::max(0.0, t.x(0)), t.x(2), t.x(1), t.x(3), t.elevation_rad});
  }
}

void report_detections_directly(const Detections& detections, ReportedTargets& reported) {
  reported.clear();
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const Detection& d = detections[i];
    ReportedTarget& r = reported.emplace_back();
    r.id = static_cast<int>(i);
    r.range_m = d.range_m;
    r.azimuth_rad = d.azimuth_rad;
    r.elevation_rad = d.elevation_rad;
    r.range_rate_mps = d.range_rate_mps;
    r.amplitude_db = d.amplitude_db;
  }
}

}  // namespace rcsim
