#include "sim/background.hpp"

#include <algorithm>

namespace rcsim {

void add_stationary_background(const StationaryBackground& background, const SensorKinematics& sensor, Rng& rng,
                               Detections& detections) {
  if (background.empty()) return;
  const int count = rng.poisson(background.targets_per_cycle);
  const std::size_t columns = background.azimuth_bins();
  for (int i = 0; i < count; ++i) {
    // The cell: the first whose cumulative weight passes a uniform draw.
    double u = rng.uniform01();
    std::size_t cell = 0;
    while (cell + 1 < background.weights.size() && u >= background.weights[cell]) u -= background.weights[cell++];
    const std::size_t r = cell / columns, a = cell % columns;
    Detection& d = detections.emplace_back();
    d.range_m = rng.uniform(background.range_edges_m[r], background.range_edges_m[r + 1]);
    d.azimuth_rad = rng.uniform(background.azimuth_edges_rad[a], background.azimuth_edges_rad[a + 1]);
    const Vec2 u_W = rotate(sensor.X_WS.yaw_rad + d.azimuth_rad, Vec2(1.0, 0.0));
    d.range_rate_mps = -sensor.v_WS_W.dot(u_W);  // a stationary reflector
    const auto& q = background.amplitude_deciles_db[r];
    const double position = rng.uniform01() * (kAmplitudeQuantiles - 1);
    const auto k = std::min(static_cast<std::size_t>(position), static_cast<std::size_t>(kAmplitudeQuantiles - 2));
    d.amplitude_db = q[k] + (position - static_cast<double>(k)) * (q[k + 1] - q[k]);
    d.object_index = -1;
  }
}

}  // namespace rcsim
