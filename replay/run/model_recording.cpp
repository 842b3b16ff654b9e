#include "replay/run/model_recording.hpp"

#include <algorithm>
#include <cmath>

#include "common/rng.hpp"
#include "sim/amplitude.hpp"
#include "sim/simulation.hpp"

namespace rcsim::replay {

namespace {

// A radar whose detections are SNRs on the radar equation reports their cross-sections beside
// them, as the aiMotive radars do; a recording with any sensor that does not gets no column.
bool reports_cross_sections(const SensorConfig& config) {
  return config.reports == ListLevel::detections && config.amplitude.kind == AmplitudeLawKind::radar_equation &&
         config.amplitude.unit == AmplitudeUnit::snr_db;
}

}  // namespace

Recording model_recording(const Scene& scene, const std::string& name, std::uint64_t seed,
                          const AnnotationNoise& noise) {
  Recording rec;
  rec.name = name;
  rec.description = "made by the reflection-center model (rcsim), not a measurement";
  rec.cycle_time_s = scene.cycle_time_s;
  rec.source = {{"generator", "rcsim reflection-center model"},
                {"seed", seed},
                {"effects",
                 {{"clutter", scene.effects.clutter},
                  {"multibounce", scene.effects.multibounce},
                  {"occlusion", scene.effects.occlusion}}}};
  // Each sensor written as what it is: its reporting level, its amplitude's unit, the radial
  // speeds it wraps.
  std::vector<MonopulseAntenna> antennas;
  for (const auto& s : scene.sensors) {
    RecordingSensor& sensor = rec.sensors.emplace_back();
    sensor.id = s.id, sensor.type = s.config.name;
    sensor.x_m = s.X_VS.x_m, sensor.y_m = s.X_VS.y_m, sensor.yaw_rad = s.X_VS.yaw_rad;
    sensor.z_m = s.z_m, sensor.pitch_rad = s.pitch_rad;
    sensor.reports = s.config.reports;
    sensor.amplitude_unit = s.config.amplitude.unit;
    if (s.config.resolution.aliases_range_rate()) {
      sensor.range_rate_interval_mps = RangeRateInterval{s.config.resolution.unambiguous_min_mps, s.config.resolution.unambiguous_max_mps};
    }
    antennas.emplace_back(s.config.antenna);
  }
  rec.boxes.resize(scene.objects.size());
  SimulationOptions options;
  options.seed = seed;
  Simulation simulation(scene, options);
  Rng annotation(seed, 1000);  // its own stream: the sensors' draws stay those of a plain simulation
  for (int k = 0; k < scene.cycle_count(); ++k) {
    const double t_s = scene.cycle_time_at(k);
    simulation.run_cycle(k);
    const BodyState& ego = simulation.snapshot().ego;
    rec.ego.push_back(ego_sample(t_s, ego));
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      if (!scene.objects[o].present_at(t_s)) continue;
      const BodyState s = simulation.object_state(o);
      if ((s.X_WB.translation() - ego.X_WB.translation()).norm() > noise.max_range_m) continue;
      AnnotatedBox box;
      box.t_s = t_s;
      box.x_m = s.X_WB.x_m + noise.position_sigma_m * annotation.normal();
      box.y_m = s.X_WB.y_m + noise.position_sigma_m * annotation.normal();
      box.yaw_rad = s.X_WB.yaw_rad + noise.yaw_sigma_rad * annotation.normal();
      box.speed_mps = s.heading_speed_mps();
      rec.boxes[o].push_back(box);
    }
    for (std::size_t i = 0; i < simulation.sensor_count(); ++i) {
      const SensorConfig& config = scene.sensors[i].config;
      for (const auto& t : simulation.sensor_state(i).reported) {
        RecordedTarget& target = rec.targets.emplace_back(RecordedTarget{t_s, k, static_cast<int>(i), t.id, t.range_m,
                                                                         t.azimuth_rad, t.range_rate_mps, t.amplitude_db});
        if (reports_cross_sections(config)) {
          target.rcs_dbsm = radar_cross_section_estimate_dbsm(config.amplitude, antennas[i], t.range_m, t.azimuth_rad, t.amplitude_db);
        }
        if (config.fov.measures_elevation()) target.elevation_rad = t.elevation_rad;
      }
    }
  }
  // targets.csv gives a column for every target or none.
  const bool every_cross_section = std::all_of(rec.targets.begin(), rec.targets.end(),
                                               [](const RecordedTarget& t) { return std::isfinite(t.rcs_dbsm); });
  if (!every_cross_section) {
    for (RecordedTarget& t : rec.targets) t.rcs_dbsm = RecordedTarget::kNoValue;
  }
  const bool every_elevation = std::all_of(rec.targets.begin(), rec.targets.end(),
                                           [](const RecordedTarget& t) { return std::isfinite(t.elevation_rad); });
  if (!every_elevation) {
    for (RecordedTarget& t : rec.targets) t.elevation_rad = RecordedTarget::kNoValue;
  }
  // Objects never annotated are not listed (a recording lists what was annotated).
  Recording listed = std::move(rec);
  rec = Recording{};
  std::vector<std::vector<AnnotatedBox>> boxes = std::move(listed.boxes);
  listed.boxes.clear();
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    if (boxes[o].empty()) continue;
    const SceneObject& object = scene.objects[o];
    listed.objects.push_back({object.id, object.model_name, object.model.length_m, object.model.width_m});
    listed.boxes.push_back(std::move(boxes[o]));
  }
  return listed;
}

}  // namespace rcsim::replay
