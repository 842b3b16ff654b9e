#pragma once
// What the scene's geometry says, per sensor and cycle, independent of either target list: which
// annotated objects the sensor can detect (a reflector in the view field, visible and not hidden
// behind another object, whose ERCS passes the detection threshold at its range by the sensor's
// amplitude law, eq. (1); the antenna pattern of eq. (6) is left out, so that the start of an
// episode does not hang on the model's antenna), and which pairs of objects share a resolution
// cell (the sensor's merging rule over the noise-free echoes, eqs. (1)-(6)). Latency
// episodes start from the first, merge artefacts are judged against the second, for the recorded
// and the simulated target lists alike (docs/metrics.md).
#include <tuple>
#include <vector>

#include "metrics/merge_artefacts.hpp"
#include "sim/resolution_cells.hpp"
#include "sim/simulation.hpp"

namespace rcsim::replay {

class SceneGeometry {
 public:
  // The scene's objects as reflection centres, with its effects (occlusion); no noise, no tracker.
  explicit SceneGeometry(const Scene& scene);

  // Every sensor at scene time t (times increasing).
  void run_at(double t_scene_s, int only_sensor = -1);  // only_sensor >= 0: that sensor alone
  void cull_within(double t0_s, double t1_s) { simulation_.cull_within(t0_s, t1_s); }
  // detectable[object] = 1 for every object with a reflector detectable by eq. (1) now.
  void mark_detectable(std::size_t sensor, std::vector<char>& detectable) const;
  // The cells of that sensor holding echoes of two objects, one entry per pair of objects.
  const std::vector<metrics::MergeCell>& merge_cells(std::size_t sensor) const { return merge_cells_[sensor]; }

 private:
  void find_merge_cells(std::size_t sensor);

  Simulation simulation_;
  ResolutionCellBuffers buffers_;
  ResolutionCells cells_;
  std::vector<int> cell_of_echo_;
  std::vector<std::tuple<int, int, double>> members_;  // (cell, object, azimuth) of this sensor's echoes in cells
  std::vector<int> cell_objects_;                      // the distinct objects of one cell
  std::vector<std::vector<metrics::MergeCell>> merge_cells_;  // per sensor, this cycle
};

}  // namespace rcsim::replay
