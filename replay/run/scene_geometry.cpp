#include "replay/run/scene_geometry.hpp"

#include <algorithm>
#include <tuple>

#include "sim/amplitude.hpp"

namespace rcsim::replay {

namespace {

SimulationOptions geometry_options() {
  SimulationOptions options;
  options.level = ListLevel::ideal;  // ideal targets and their echoes; no cells, noise or tracks
  options.noise = false;
  options.fidelity = Fidelity::full;
  return options;
}

}  // namespace

SceneGeometry::SceneGeometry(const Scene& scene)
    : simulation_(scene, geometry_options()), merge_cells_(scene.sensors.size()) {}

void SceneGeometry::run_at(double t_scene_s, int only_sensor) {
  simulation_.run_at(t_scene_s, only_sensor);
  for (std::size_t s = 0; s < simulation_.sensor_count(); ++s) {
    if (only_sensor < 0 || static_cast<std::size_t>(only_sensor) == s) find_merge_cells(s);
  }
}

// The ideal targets are the visible reflectors in the view field, those hidden behind other
// objects removed; their ERCS carries the reflector's angle-dependent visibility.
void SceneGeometry::mark_detectable(std::size_t sensor, std::vector<char>& detectable) const {
  const SensorCycleState& state = simulation_.sensor_state(sensor);
  const AmplitudeLaw& law = simulation_.sensor_model(sensor).mount.config.amplitude;
  for (const IdealTarget& t : state.ideal) {
    if (t.bounce_order == 1 && t.object_index >= 0 && t.ercs > 0.0 && t.range_m <= detection_range_bound_m(law, t.ercs)) {
      detectable[static_cast<std::size_t>(t.object_index)] = 1;  // eq. (1) at or above the threshold
    }
  }
}

// The sensor model's own cells (form_resolution_cells) over this cycle's echoes; a cell with
// echoes of several objects gives one MergeCell per pair, spanning their echoes' azimuths.
void SceneGeometry::find_merge_cells(std::size_t sensor) {
  const SensorCycleState& state = simulation_.sensor_state(sensor);
  const SensorModel& model = simulation_.sensor_model(sensor);
  std::vector<metrics::MergeCell>& out = merge_cells_[sensor];
  out.clear();
  form_resolution_cells(model.mount.config.resolution, model.cell_gate_amplitude, state.echoes, buffers_, cells_,
                        &cell_of_echo_);
  // (cell, object, azimuth) of every echo in a cell, grouped by cell then object.
  std::vector<std::tuple<int, int, double>>& members = members_;  // reused: no allocation per cycle
  members.clear();
  for (std::size_t i = 0; i < state.echoes.size(); ++i) {
    const IdealTarget& t = state.ideal[static_cast<std::size_t>(state.echoes[i].ideal_index)];
    if (cell_of_echo_[i] >= 0 && t.object_index >= 0) members.emplace_back(cell_of_echo_[i], t.object_index, t.azimuth_rad);
  }
  std::sort(members.begin(), members.end());
  for (std::size_t begin = 0; begin < members.size();) {
    std::size_t end = begin;
    while (end < members.size() && std::get<0>(members[end]) == std::get<0>(members[begin])) ++end;
    const ResolutionCellSum& cell = cells_[static_cast<std::size_t>(std::get<0>(members[begin]))];
    std::vector<int>& objects = cell_objects_;  // distinct, ascending (members are sorted by object within a cell)
    objects.clear();
    for (std::size_t k = begin; k < end; ++k) {
      if (objects.empty() || objects.back() != std::get<1>(members[k])) objects.push_back(std::get<1>(members[k]));
    }
    for (std::size_t i = 0; i < objects.size(); ++i) {
      for (std::size_t j = i + 1; j < objects.size(); ++j) {
        metrics::MergeCell m{objects[i], objects[j], cell.range_m, cell.range_rate_mps, 0.0, 0.0};
        bool first = true;
        for (std::size_t k = begin; k < end; ++k) {  // the span of both objects' echoes in the cell
          const auto& [c, o, azimuth_rad] = members[k];
          if (o != m.object_a && o != m.object_b) continue;
          m.azimuth_lo_rad = first ? azimuth_rad : std::min(m.azimuth_lo_rad, azimuth_rad);
          m.azimuth_hi_rad = first ? azimuth_rad : std::max(m.azimuth_hi_rad, azimuth_rad);
          first = false;
        }
        out.push_back(m);
      }
    }
    begin = end;
  }
}

}  // namespace rcsim::replay
