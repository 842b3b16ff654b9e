#include "replay/import/importer.hpp"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/angles.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "replay/import/annotation_smoothing.hpp"

namespace rcsim::replay {

namespace {

std::string header_file(const Recording& rec) { return (rec.dir / "recording.json").string(); }
std::string boxes_file(const Recording& rec) { return (rec.dir / "objects.csv").string(); }

std::vector<TrajectorySample> ego_trajectory(const Recording& rec, double t0_s) {
  std::vector<TrajectorySample> samples;
  samples.reserve(rec.ego.size());
  for (const EgoSample& e : rec.ego) {
    TrajectorySample s;
    s.t_s = e.t_s - t0_s;
    s.x_m = e.x_m;
    s.y_m = e.y_m;
    s.yaw_rad = e.yaw_rad;
    s.speed_mps = e.speed_mps;
    s.yaw_rate_radps = e.yaw_rate_radps;  // the ego log is measured (INS), not annotated: used as is
    samples.push_back(s);
  }
  return samples;
}

ImportedObject import_object(const Recording& rec, std::size_t index, double t0_s, const ImportOptions& options,
                             std::vector<std::string>& warnings) {
  const RecordingObject& object = rec.objects[index];
  const std::vector<AnnotatedBox>& boxes = rec.boxes[index];
  ImportedObject out;
  out.id = object.id;
  out.model = object.object_class;
  out.length_m = object.length_m;
  out.width_m = object.width_m;

  std::vector<double> t_s, x_m, y_m, yaw_rad, speed_mps;
  std::vector<char> gap_after(boxes.size(), 0);  // absent from the scene until the next box
  // Present over the annotated spans, widened by half a cycle so that a cycle whose time carries
  // rounding still sees the object at both ends.
  const double half_cycle_s = 0.5 * rec.cycle_time_s;
  out.presence.push_back({boxes.front().t_s - t0_s - half_cycle_s, 0.0});
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const AnnotatedBox& b = boxes[i];
    if (i > 0) {
      const double gap_s = b.t_s - boxes[i - 1].t_s;
      if (gap_s > options.max_gap_s) {
        warnings.push_back(annotation_gap_warning(boxes_file(rec), boxes[i - 1].line, b.line, object.id, gap_s, true));
        out.presence.back().until_s = boxes[i - 1].t_s - t0_s + half_cycle_s;
        gap_after[i - 1] = 1;
        out.presence.push_back({b.t_s - t0_s - half_cycle_s, 0.0});
      } else if (gap_s > 1.5 * rec.cycle_time_s) {
        warnings.push_back(annotation_gap_warning(boxes_file(rec), boxes[i - 1].line, b.line, object.id, gap_s, false));
      }
    }
    t_s.push_back(b.t_s - t0_s);
    x_m.push_back(b.x_m);
    y_m.push_back(b.y_m);
    // Unwrapped, so that the fit never sees a jump of 2π.
    yaw_rad.push_back(i == 0 ? b.yaw_rad : yaw_rad.back() + angle_difference_rad(b.yaw_rad, boxes[i - 1].yaw_rad));
    speed_mps.push_back(b.speed_mps);
  }
  const double h = options.smoothing_half_window_s;
  const auto fits = smooth_local_quadratic(t_s, {&x_m, &y_m, &yaw_rad, &speed_mps}, h);
  const auto& x_fit = fits[0];
  const auto& y_fit = fits[1];
  const auto& yaw_fit = fits[2];
  const auto& speed_fit = fits[3];
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    TrajectorySample s;
    s.t_s = t_s[i];
    s.x_m = x_fit[i].value;
    s.y_m = y_fit[i].value;
    s.yaw_rad = yaw_fit[i].value;
    s.speed_mps = speed_fit[i].value;
    s.yaw_rate_radps = yaw_fit[i].slope_per_s;
    s.gap_after = gap_after[i] != 0;
    out.trajectory.push_back(s);
  }
  out.presence.back().until_s = t_s.back() + half_cycle_s;
  return out;
}

}  // namespace

std::string annotation_gap_warning(const std::string& file, int line_before, int line_after, const std::string& object,
                                   double gap_s, bool absent) {
  return fmt::format("{}: lines {} and {}: object '{}' not annotated for {:.3f} s; {}", file, line_before, line_after,
                     object, gap_s, absent ? "absent from the scene in between" : "interpolated");
}

ImportedScene import_header(const Recording& rec, double time_offset_s, const ModelLibrary& library,
                            const ImportOptions& options) {
  ImportedScene out;
  out.name = rec.name;
  out.description = rec.description.empty() ? "imported from recording " + rec.name
                                            : "imported from recording " + rec.name + ": " + rec.description;
  out.time_offset_s = time_offset_s;
  out.cycle_time_s = rec.cycle_time_s;
  out.effects = options.effects;
  if (const auto declared = rec.source.find("effects"); declared != rec.source.end()) {
    // What made the recording: an object of three booleans, each optional (false when absent).
    if (!declared->is_object()) {
      throw InputError(header_file(rec), "source.effects", "expected an object of clutter, multibounce, occlusion: true|false");
    }
    for (const auto& [name, value] : declared->items()) {
      if (name != "clutter" && name != "multibounce" && name != "occlusion") {
        throw InputError(header_file(rec), "source.effects." + name, "unknown effect (clutter, multibounce, occlusion)");
      }
      if (!value.is_boolean()) throw InputError(header_file(rec), "source.effects." + name, "expected true or false");
    }
    if (options.effects_from_recording) {
      const auto flag = [&](const char* name) { return declared->contains(name) && declared->at(name) == true; };
      out.effects = {flag("clutter"), flag("multibounce"), flag("occlusion")};
    }
  }
  out.sensors = rec.sensors;
  if (!options.sensor_type_override.empty()) {
    for (auto& sensor : out.sensors) sensor.type = options.sensor_type_override;
  }
  if (!options.calibration_dir.empty()) out.calibration = load_calibration(options.calibration_dir);
  for (std::size_t i = 0; i < rec.objects.size(); ++i) {
    const RecordingObject& object = rec.objects[i];
    if (!library.contains(object.object_class)) {
      std::string known;
      for (const auto& [name, model] : library.models()) known += (known.empty() ? "" : ", ") + name;
      throw InputError(header_file(rec), fmt::format("objects[{}].class", i),
                       fmt::format("unknown class '{}' of object '{}' (the object library has: {})",
                                   object.object_class, object.id, known));
    }
    ImportedObject imported;
    imported.id = object.id;
    imported.model = object.object_class;
    imported.length_m = object.length_m;
    imported.width_m = object.width_m;
    out.objects.push_back(std::move(imported));
  }
  return out;
}

ImportedScene import_recording(const Recording& rec, const ModelLibrary& library, const ImportOptions& options) {
  ImportedScene out = import_header(rec, rec.ego.front().t_s, library, options);
  out.duration_s = rec.ego.back().t_s - out.time_offset_s;
  out.ego = ego_trajectory(rec, out.time_offset_s);
  for (std::size_t i = 0; i < rec.objects.size(); ++i) {
    out.objects[i] = import_object(rec, i, out.time_offset_s, options, out.warnings);
  }
  return out;
}

Scene build_scene(const ImportedScene& in, const ModelLibrary& library, const std::string& base_dir) {
  Scene scene;
  scene.source = in.name;
  scene.duration_s = in.duration_s;
  scene.cycle_time_s = in.cycle_time_s;
  scene.effects = in.effects;
  scene.ego = Trajectory(in.ego);
  for (std::size_t i = 0; i < in.sensors.size(); ++i) {
    const RecordingSensor& s = in.sensors[i];
    MountedSensor sensor;
    sensor.id = s.id;
    try {
      sensor.config = calibrated_sensor(in.calibration.get(), sensor_config_for_type(s.type, base_dir));
    } catch (const std::invalid_argument& e) {
      throw InputError((std::filesystem::path(base_dir) / "recording.json").string(),
                       fmt::format("sensors[{}].type", i), e.what());
    }
    sensor.X_VS = {s.x_m, s.y_m, s.yaw_rad};
    sensor.z_m = s.z_m;  // version 5: a radar that measures elevation reads them
    sensor.pitch_rad = s.pitch_rad;
    sensor.cycle_time_s = s.cycle_time_s;  // its own clock (recording v4), else 0: the scene's
    scene.sensors.push_back(std::move(sensor));
  }
  for (std::size_t i = 0; i < in.objects.size(); ++i) {
    const ImportedObject& o = in.objects[i];
    SceneObject object;
    object.id = o.id;
    object.model_name = o.model;
    try {
      const ObjectModel model = object_model_for_name(o.model, library, base_dir);
      object.model = scale_model(calibrated_model(in.calibration.get(), model), o.length_m, o.width_m);
    } catch (const std::invalid_argument& e) {
      throw InputError((std::filesystem::path(base_dir) / "recording.json").string(), fmt::format("objects[{}]", i),
                       fmt::format("cannot use model '{}' at {} m x {} m: {}", o.model, o.length_m, o.width_m,
                                   e.what()));
    }
    object.trajectory = Trajectory(o.trajectory);
    object.presence = o.presence;
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

void write_scene_file(const std::string& path, const ImportedScene& in) {
  using Json = nlohmann::ordered_json;
  const auto sample_json = [](const TrajectorySample& s) {
    Json j{{"t_s", s.t_s}, {"x_m", s.x_m}, {"y_m", s.y_m}, {"yaw_rad", s.yaw_rad}, {"speed_mps", s.speed_mps}};
    if (s.yaw_rate_radps) j["yaw_rate_radps"] = *s.yaw_rate_radps;
    return j;
  };
  Json scene;
  scene["format"] = "rcsim-scene";
  scene["version"] = 1;
  scene["name"] = in.name;
  scene["description"] = in.description + fmt::format(" (scene time = recording time - {} s)", in.time_offset_s);
  scene["duration_s"] = in.duration_s;
  scene["cycle_time_s"] = in.cycle_time_s;
  scene["effects"] = {{"clutter", in.effects.clutter}, {"multibounce", in.effects.multibounce},
                      {"occlusion", in.effects.occlusion}};
  Json ego_trajectory = Json::array();
  for (const auto& s : in.ego) ego_trajectory.push_back(sample_json(s));
  Json sensors = Json::array();
  for (const auto& s : in.sensors) {
    sensors.push_back({{"id", s.id}, {"type", s.type}, {"x_m", s.x_m}, {"y_m", s.y_m}, {"yaw_rad", s.yaw_rad}});
    if (s.z_m != 0.0) sensors.back()["z_m"] = s.z_m;
    if (s.pitch_rad != 0.0) sensors.back()["pitch_rad"] = s.pitch_rad;
  }
  scene["ego"] = {{"trajectory", std::move(ego_trajectory)}, {"sensors", std::move(sensors)}};
  Json objects = Json::array();
  for (const auto& o : in.objects) {
    Json trajectory = Json::array();
    for (const auto& s : o.trajectory) {
      Json j = sample_json(s);
      j["length_m"] = o.length_m;  // the annotated size scales the model
      j["width_m"] = o.width_m;
      trajectory.push_back(std::move(j));
    }
    Json presence = Json::array();
    for (const TimeInterval& i : o.presence) presence.push_back({i.from_s, i.until_s});
    objects.push_back({{"id", o.id}, {"model", o.model}, {"present_s", std::move(presence)},
                       {"trajectory", std::move(trajectory)}});
  }
  scene["objects"] = std::move(objects);
  AtomicFileWriter file(path);
  file.stream() << scene.dump(1) << '\n';
  file.commit();
}

}  // namespace rcsim::replay
