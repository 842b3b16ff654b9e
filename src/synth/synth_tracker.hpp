#pragma once
// The reference sensor's internal tracker (paper III-E), written apart from the model's Kalman
// tracker so that its latency and smoothing are data to be matched: per track an alpha-beta
// filter on range (aided by the measured range rate), one on azimuth, exponential smoothing of the
// amplitude; greedy nearest-neighbour association inside rectangular gates; a track is reported
// once it has collected confirmation_hits detections and only in cycles in which it was updated.
#include <vector>

#include "synth/signal_chain.hpp"
#include "synth/synth_config.hpp"

namespace rcsim::synth {

enum class TrackStatus { tentative, confirmed };

struct SynthTrack {
  int id = 0;
  TrackStatus status = TrackStatus::tentative;
  double range_m = 0.0, range_rate_mps = 0.0;
  double azimuth_rad = 0.0, azimuth_rate_radps = 0.0;
  double amplitude_db = 0.0;
  int hits = 0;
  int misses = 0;   // consecutive
  bool updated = false;
};

struct ReportedTarget {
  int id = 0;
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
};

class SynthTracker {
 public:
  SynthTracker(const TrackerConfig& config, double cycle_time_s) : config_(config), cycle_time_s_(cycle_time_s) {}

  // predict => associate => update => initiate => delete; returns the confirmed, updated tracks.
  std::vector<ReportedTarget> step(const std::vector<Detection>& detections);
  const std::vector<SynthTrack>& tracks() const { return tracks_; }

 private:
  void confirm_if_due(SynthTrack& track) const;  // paper III-E: confirmed after confirmation_hits hits
  TrackerConfig config_;
  double cycle_time_s_;
  std::vector<SynthTrack> tracks_;
  int next_id_ = 0;
};

}  // namespace rcsim::synth
