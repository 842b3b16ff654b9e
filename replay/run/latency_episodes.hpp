#pragma once
// Confirmation latency per (sensor, object) and detectability episode (schemas/report-database.md,
// table latencies). An episode starts when the re-simulation's sensor model first detects the
// object (a detection before tracking, SimulatedSource::mark_detected_objects) and ends after
// kEpisodeGapCycles cycles without one; the latency of each side is the time from that start to
// its first reported target belonging to the object.
#include <cstddef>
#include <vector>

#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

class LatencyEpisodes {
 public:
  // An episode ends after this many cycles without a detection (longer than any track survives
  // without hits).
  static constexpr int kEpisodeGapCycles = 10;

  LatencyEpisodes(std::size_t sensors, std::size_t objects);

  // Opens an episode for every object detected now (detected[object] != 0) and closes the ones
  // not detected for kEpisodeGapCycles cycles.
  void update_detected(std::size_t sensor, const std::vector<char>& detected, double t_s);

  // Records, for every object with an open episode, the first recorded and the first simulated
  // target that belongs to it.
  void note_first_targets(std::size_t sensor, const CycleComparison& cycle, double t_s);

  // Closes every open episode and fills summary.latencies, latency_pairs and the mean latencies
  // over the episodes where both sides reported the object.
  void finish(ReplaySummary& summary);

 private:
  LatencyRow& row(std::size_t sensor, std::size_t object) { return open_[sensor * objects_ + object]; }
  void close(std::size_t key);

  std::size_t objects_;
  std::vector<LatencyRow> open_;  // detectable_from_s < 0: no open episode
  std::vector<int> undetected_cycles_;
  std::vector<int> episodes_;
  std::vector<LatencyRow> closed_;
};

}  // namespace rcsim::replay
