#include "replay/report/recording_birdseye.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "io/csv_reader.hpp"
#include "replay/report/svg_writer.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::replay::svg {

namespace {

// A sensor's view field from its configuration (built-in, or a file beside the recording).
std::optional<FieldOfView> field_of_view(const Recording& rec, const RecordingSensor& sensor) {
  if (is_builtin_sensor_config(sensor.type)) return builtin_sensor_config(sensor.type).fov;
  const std::filesystem::path file = rec.dir / sensor.type;
  if (rec.dir.empty() || !std::filesystem::is_regular_file(file)) return std::nullopt;
  return load_sensor_config_file(file.string()).fov;
}

// The last cycle at or before time_s (all cycles when time_s < 0).
int pictured_cycle(const Recording& rec, double time_s) {
  int last = rec.cycle_count() - 1;
  if (time_s >= 0.0) {
    for (int k = 0; k < rec.cycle_count(); ++k) {
      if (rec.cycle_t_s(k) <= time_s + 1e-9) last = k;
    }
  }
  return last;
}

// The cycles of the picture: targets of [first, last] are drawn, in the vehicle frame of `last`.
struct PicturedWindow {
  int first = 0, last = 0;
  Pose2 X_WV;  // the ego vehicle's pose at the pictured cycle
};

PicturedWindow pictured_window(const Recording& rec, const RecordingPictureOptions& options) {
  PicturedWindow w;
  w.last = pictured_cycle(rec, options.time_s);
  w.first = std::max(0, w.last - options.cycles + 1);
  const EgoSample ego = rec.ego_at_cycle(w.last);
  w.X_WV = Pose2{ego.x_m, ego.y_m, ego.yaw_rad};
  return w;
}

void add_sensors(const Recording& rec, BirdsEyeSpec& spec) {
  for (const RecordingSensor& s : rec.sensors) {
    const auto fov = field_of_view(rec, s);
    spec.sensors.push_back({s.id, Pose2{s.x_m, s.y_m, s.yaw_rad}, fov ? fov->azimuth_half_rad : 0.0,
                            fov ? fov->max_range_m : 0.0});
  }
}

// The annotated boxes at the pictured cycle's time; ids are shortened here and escaped when drawn.
void add_boxes(const Recording& rec, const PicturedWindow& w, BirdsEyeSpec& spec) {
  const double t_s = rec.cycle_t_s(w.last);
  for (std::size_t i = 0; i < rec.boxes.size(); ++i) {
    for (const AnnotatedBox& b : rec.boxes[i]) {
      if (std::abs(b.t_s - t_s) > 1e-6) continue;
      const Pose2 X_VO = compose(inverse(w.X_WV), Pose2{b.x_m, b.y_m, b.yaw_rad});
      spec.boxes.push_back({shorten(rec.objects[i].id, 14), X_VO, rec.objects[i].length_m, rec.objects[i].width_m, false});
    }
  }
}

// A target of `cycle` seen by `sensor` (range and azimuth in the sensor frame S of that cycle),
// into the pictured cycle's vehicle frame; targets outside the window are left out.
void add_target(const Recording& rec, const PicturedWindow& w, int cycle, int sensor, double range_m,
                double azimuth_rad, bool compared, BirdsEyeSpec& spec) {
  if (cycle < w.first || cycle > w.last) return;
  const EgoSample e = rec.ego_at_cycle(cycle);
  const RecordingSensor& s = rec.sensors[static_cast<std::size_t>(sensor)];
  const Pose2 X_WS = compose(Pose2{e.x_m, e.y_m, e.yaw_rad}, Pose2{s.x_m, s.y_m, s.yaw_rad});
  const Vec2 p_WT_W = transform_point(X_WS, point_from_polar(range_m, azimuth_rad));
  spec.targets.push_back({inverse_transform_point(w.X_WV, p_WT_W), compared, w.last - cycle, false, {}});
}

// The compared target list (rcsim simulate's CSV); its sensors must be the recording's.
void add_compared_targets(const Recording& rec, const PicturedWindow& w, const std::string& path, BirdsEyeSpec& spec) {
  CsvReader csv(path, {"cycle", "sensor", "range_m", "azimuth_rad"});
  const int c = csv.column("cycle"), s = csv.column("sensor"), r = csv.column("range_m"), az = csv.column("azimuth_rad");
  while (csv.next()) {
    const int sensor = rec.sensor_index(csv.text(s));
    if (sensor < 0) csv.fail(s, "sensor '" + csv.text(s) + "' is not a sensor of the recording");
    add_target(rec, w, static_cast<int>(csv.integer(c)), sensor, csv.number(r), csv.number(az), true, spec);
  }
}

}  // namespace

BirdsEyeSpec recording_birdseye(const Recording& rec, const RecordingPictureOptions& options) {
  BirdsEyeSpec spec;
  if (rec.cycle_count() == 0) return spec;
  const PicturedWindow w = pictured_window(rec, options);
  const double t_s = rec.cycle_t_s(w.last);
  spec.title = options.title.empty() ? rec.name : options.title;
  spec.notes.push_back(fmt::format("cycle {} at t = {:.2f} s; targets of cycles {} to {}", w.last, t_s, w.first, w.last));
  spec.trace_cycles = w.last - w.first;
  spec.recorded_label = options.recorded_label;
  spec.simulated_label = options.compared_label;
  spec.standalone = true;
  add_sensors(rec, spec);
  add_boxes(rec, w, spec);
  for (const RecordedTarget& t : rec.targets) add_target(rec, w, t.cycle, t.sensor, t.range_m, t.azimuth_rad, false, spec);
  if (!options.compare_path.empty()) add_compared_targets(rec, w, options.compare_path, spec);
  return spec;
}

}  // namespace rcsim::replay::svg
