#pragma once
// Confirmation latency per (sensor, object) and detectable episode (docs/metrics.md; table
// latencies). The same rule for the recorded and the simulated target lists, and nothing in it
// depends on either list's start:
//   - an episode starts in the first cycle the scene geometry says the object is detectable by
//     that sensor (SceneGeometry: in view, not occluded, a reflector's noise-free echo above the
//     threshold) and ends after kEpisodeGapCycles cycles in which it is not;
//   - a side confirms the object in the first cycle of the episode in which targets of that
//     object (class object, so never a merge artefact) were reported in at least
//     kConfirmHits of the last kConfirmWindow cycles of the episode: one stray target cannot
//     confirm it, one missed cycle cannot reset it;
//   - latency = confirmation time - episode start. An episode a side never confirms is kept,
//     censored (no latency on that side), and counted.
#include <cstddef>
#include <vector>

#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

class LatencyEpisodes {
 public:
  static constexpr int kEpisodeGapCycles = 10;  // longer than any track survives without hits
  static constexpr int kConfirmHits = 3, kConfirmWindow = 4;

  LatencyEpisodes(std::size_t sensors, std::size_t objects);

  // Opens an episode for every object detectable now (detectable[object] != 0) and closes the
  // ones not detectable for kEpisodeGapCycles cycles.
  void update_detectable(std::size_t sensor, const std::vector<char>& detectable, double t_s);

  // Notes, for every object with an open episode, whether each side reported targets of it in
  // this cycle, and confirms it where the rule is met.
  void note_targets(std::size_t sensor, const CycleComparison& cycle, double t_s);

  // Closes every open episode: summary.latencies and the per-run latency figures.
  void finish(ReplaySummary& summary);

 private:
  struct Open {
    LatencyRow row;      // row.detectable_from_s < 0: no open episode
    unsigned hits[2] = {0, 0};  // last kConfirmWindow cycles as bits, [0] recorded, [1] simulated
    int undetectable_cycles = kEpisodeGapCycles;
    int episodes = 0;
  };
  void close(Open& open);

  std::size_t objects_;
  std::vector<Open> open_;   // [sensor * objects + object]
  std::vector<char> seen_[2];  // per object, this cycle: targets of it on each side
  std::vector<LatencyRow> closed_;
};

}  // namespace rcsim::replay
