#include "synth/synth_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim::synth {

void SynthTracker::confirm_if_due(SynthTrack& track) const {
  if (track.hits >= config_.confirmation_hits) track.status = TrackStatus::confirmed;
}

std::vector<ReportedTarget> SynthTracker::step(const std::vector<Detection>& detections) {
  const double dt = cycle_time_s_;
  // Predict: constant range rate and constant azimuth rate.
  for (auto& t : tracks_) {
    t.range_m += t.range_rate_mps * dt;
    t.azimuth_rad = wrap_angle_rad(t.azimuth_rad + t.azimuth_rate_radps * dt);
    t.updated = false;
  }

  // Associate: every (track, detection) pair inside the gates, cheapest first.
  struct Pair {
    double cost;
    std::size_t track, detection;
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    for (std::size_t j = 0; j < detections.size(); ++j) {
      const double er = (detections[j].range_m - tracks_[i].range_m) / config_.gate_range_m;
      const double ev = (detections[j].range_rate_mps - tracks_[i].range_rate_mps) / config_.gate_range_rate_mps;
      const double ea = angle_difference_rad(detections[j].azimuth_rad, tracks_[i].azimuth_rad) / config_.gate_azimuth_rad;
      if (std::abs(er) > 1.0 || std::abs(ev) > 1.0 || std::abs(ea) > 1.0) continue;
      pairs.push_back({er * er + ev * ev + ea * ea, i, j});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.cost != b.cost ? a.cost < b.cost : (a.track != b.track ? a.track < b.track : a.detection < b.detection);
  });
  std::vector<bool> detection_used(detections.size(), false);
  for (const auto& p : pairs) {
    SynthTrack& t = tracks_[p.track];
    if (t.updated || detection_used[p.detection]) continue;
    const Detection& z = detections[p.detection];
    detection_used[p.detection] = true;
    t.updated = true;
    // Update: alpha-beta on range with the measured range rate blended in.
    const double er = z.range_m - t.range_m;
    t.range_m += config_.alpha_range * er;
    const double rate_from_range = t.range_rate_mps + config_.beta_range * er / dt;
    t.range_rate_mps = (1.0 - config_.alpha_range_rate) * rate_from_range + config_.alpha_range_rate * z.range_rate_mps;
    const double ea = angle_difference_rad(z.azimuth_rad, t.azimuth_rad);
    t.azimuth_rad = wrap_angle_rad(t.azimuth_rad + config_.alpha_azimuth * ea);
    t.azimuth_rate_radps += config_.beta_azimuth * ea / dt;
    t.amplitude_db += config_.alpha_amplitude * (z.amplitude_db - t.amplitude_db);
    ++t.hits;
    t.misses = 0;
    confirm_if_due(t);
  }

  // Delete tracks missed too often.
  for (auto& t : tracks_) {
    if (!t.updated) ++t.misses;
  }
  std::erase_if(tracks_, [&](const SynthTrack& t) {
    const int allowed = t.status == TrackStatus::confirmed ? config_.max_misses_confirmed : config_.max_misses_tentative;
    return t.misses > allowed;
  });

  // Initiate from the unused detections, strongest first (detections come sorted by power).
  for (std::size_t j = 0; j < detections.size(); ++j) {
    if (detection_used[j] || static_cast<int>(tracks_.size()) >= config_.max_tracks) continue;
    SynthTrack t;
    t.id = next_id_++;
    t.range_m = detections[j].range_m;
    t.range_rate_mps = detections[j].range_rate_mps;
    t.azimuth_rad = detections[j].azimuth_rad;
    t.amplitude_db = detections[j].amplitude_db;
    t.hits = 1;
    t.updated = true;
    confirm_if_due(t);
    tracks_.push_back(t);
  }

  std::vector<ReportedTarget> out;
  for (const auto& t : tracks_) {
    if (t.status != TrackStatus::confirmed || !t.updated) continue;
    out.push_back({t.id, std::max(0.0, t.range_m), wrap_angle_rad(t.azimuth_rad), t.range_rate_mps, t.amplitude_db});
  }
  std::sort(out.begin(), out.end(), [](const ReportedTarget& a, const ReportedTarget& b) { return a.range_m < b.range_m; });
  return out;
}

}  // namespace rcsim::synth
