#pragma once
// Per annotated object and sensor, for both target lists: the cycles the object was in view, the
// cycles it was detected (at least one target of that object), its targets, and the same counts
// in bins of the range of its nearest point: the detection probability and the targets per
// object-cycle against range (docs/metrics.md, "Real drives"). A (sensor, object)'s bins add up
// to its totals.
#include <vector>

#include "metrics/sensor_view.hpp"
#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

class ObjectFigures {
 public:
  ObjectFigures(std::size_t sensors, std::size_t objects, double range_bin_m);
  // One compared cycle of one sensor (targets classified); `in_field`: the present boxes whose
  // nearest point lies in that sensor's field of view and range.
  void add_cycle(const CycleComparison& cycle, const std::vector<metrics::BoxInSensor>& in_field);
  // The rows of every (sensor, object) that was ever in view, in that order, into `summary`.
  void finish(ReplaySummary& summary) const;

 private:
  struct Counts {
    int in_view = 0, detected_recorded = 0, detected_simulated = 0;
    long long targets_recorded = 0, targets_simulated = 0;
  };
  struct PerObject {
    Counts all;
    std::vector<Counts> by_range;  // bin b: [b, b + 1) * range_bin_m
  };
  std::size_t objects_;
  double range_bin_m_;
  std::vector<PerObject> figures_;  // [sensor * objects + object]
  std::vector<int> recorded_, simulated_;  // per object, this cycle's targets (reused)
};

}  // namespace rcsim::replay
