#include "common/quantile.hpp"
#include "scene/scene.hpp"

#include "common/limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <system_error>

namespace rcsim {
namespace {

SensorConfig sensor_config_for(const JsonField& sensor, const std::string& base_dir) {
  try {
    return sensor_config_for_type(sensor.string("type"), base_dir);
  } catch (const std::invalid_argument& e) {
    sensor.fail("type", e.what());
  }
}

ObjectModel model_for(const JsonField& object, const ModelLibrary& library, const std::string& base_dir) {
  try {
    return object_model_for_name(object.string("model"), library, base_dir);
  } catch (const std::invalid_argument& e) {
    object.fail("model", e.what());
  }
}

std::vector<TimeInterval> parse_presence(const JsonField& o);

// A static object along a polyline (docs/static-world.md): its model a polyline template, its
// points in the world; the object frame is the world frame moved to the points' mean.
void parse_polyline_object(const JsonField& o, SceneObject& object) {
  if (!object.model.polyline) o.fail("polyline", "model \"" + object.model_name + "\" is no polyline model (guard_rail is one)");
  if (!o.has("polyline")) o.fail("model \"" + object.model_name + "\" is a polyline model: give a polyline, not a trajectory");
  if (o.has("trajectory")) o.fail("trajectory", "a polyline object stands still: give its polyline only");
  std::vector<Vec2> points_W;
  for (const auto& p : o.array("polyline")) {
    p.expect_only({"x_m", "y_m"});
    points_W.emplace_back(p.number("x_m"), p.number("y_m"));
    if (points_W.back().cwiseAbs().maxCoeff() > 1e7) p.fail("x_m", "beyond 10^7 m");
  }
  if (points_W.size() < 2 || points_W.size() > 100000) o.fail("polyline", "needs 2 to 100000 points");
  Vec2 mean_W = Vec2::Zero();
  for (const Vec2& p : points_W) mean_W += p / static_cast<double>(points_W.size());
  std::vector<Vec2> points_O;
  for (const Vec2& p : points_W) points_O.push_back(p - mean_W);
  try {
    object.model = expand_polyline(object.model, points_O);
  } catch (const std::invalid_argument& e) {
    o.fail("polyline", e.what());
  }
  TrajectorySample at_rest;
  at_rest.x_m = mean_W.x();
  at_rest.y_m = mean_W.y();
  object.trajectory = Trajectory({at_rest});
  object.presence = parse_presence(o);
}

// Either present_from_s / present_until_s (one interval, either end open) or present_s: a list of
// [from_s, until_s] pairs in increasing, non-overlapping order.
std::vector<TimeInterval> parse_presence(const JsonField& o) {
  std::vector<TimeInterval> presence;
  if (o.has("present_s")) {
    if (o.has("present_from_s") || o.has("present_until_s")) {
      o.fail("present_s", "give either present_s or present_from_s/present_until_s, not both");
    }
    const auto intervals = o.array("present_s");
    if (intervals.empty()) o.fail("present_s", "needs at least one [from_s, until_s] interval");
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      const nlohmann::json& pair = intervals[i].json();
      if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number() || !pair[1].is_number()) {
        intervals[i].fail("must be [from_s, until_s] with two numbers");
      }
      const TimeInterval interval{pair[0].get<double>(), pair[1].get<double>()};
      if (!std::isfinite(interval.from_s) || !std::isfinite(interval.until_s) || interval.until_s < interval.from_s) {
        intervals[i].fail(fmt::format("[{}, {}] is not an interval", interval.from_s, interval.until_s));
      }
      if (!presence.empty() && interval.from_s <= presence.back().until_s) {
        intervals[i].fail("intervals must be in increasing order and must not overlap");
      }
      presence.push_back(interval);
    }
    return presence;
  }
  if (o.has("present_from_s") || o.has("present_until_s")) {
    const TimeInterval interval{o.number_or("present_from_s", -std::numeric_limits<double>::infinity()),
                                o.number_or("present_until_s", std::numeric_limits<double>::infinity())};
    if (interval.until_s < interval.from_s) {
      o.fail("present_until_s", fmt::format("{} s is before present_from_s {} s", interval.until_s, interval.from_s));
    }
    presence.push_back(interval);
  }
  return presence;
}

}  // namespace

bool looks_like_path(const std::string& name) {
  return name.find('/') != std::string::npos || name.ends_with(".json");
}

std::string resolve_relative(const std::string& base_dir, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() || base_dir.empty() ? name : (std::filesystem::path(base_dir) / p).string();
}

namespace {

// A name read as a file: missing, or one the file system refuses to look up (too long, a loop of
// links), is the same refusal, saying why.
void require_file(const std::string& path, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw std::invalid_argument(what + " file not found: " + path + (error ? " (" + error.message() + ")" : ""));
  }
}

}  // namespace

SensorConfig sensor_config_for_type(const std::string& type, const std::string& base_dir) {
  if (is_builtin_sensor_config(type)) return builtin_sensor_config(type);
  if (looks_like_path(type)) {
    const std::string path = resolve_relative(base_dir, type);
    require_file(path, "sensor configuration");
    return load_sensor_config_file(path);
  }
  throw std::invalid_argument(unknown_sensor_message(type));
}

ObjectModel object_model_for_name(const std::string& name, const ModelLibrary& library, const std::string& base_dir) {
  if (library.contains(name)) return library.at(name);
  if (looks_like_path(name)) {
    const std::string path = resolve_relative(base_dir, name);
    require_file(path, "object model");
    return load_object_model_file(path);
  }
  std::string known;
  for (const auto& [n, m] : library.models()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown object model \"" + name + "\" (built-in: " + known + ")");
}

std::vector<TrajectorySample> parse_trajectory(const JsonField& owner, std::string_view key) {
  const auto entries = owner.array(key);
  if (entries.empty()) owner.fail(key, "needs at least one sample");
  std::vector<TrajectorySample> samples;
  samples.reserve(entries.size());
  for (const auto& e : entries) {
    e.expect_only({"t_s", "x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps", "length_m", "width_m"});
    TrajectorySample s;
    using namespace limits;
    s.t_s = e.number_within("t_s", -kMaxTime_s, kMaxTime_s, "s");
    s.x_m = e.number_within("x_m", -kMaxCoordinate_m, kMaxCoordinate_m, "m");
    s.y_m = e.number_within("y_m", -kMaxCoordinate_m, kMaxCoordinate_m, "m");
    // The first heading is wrapped (±2π: beyond, degrees); later ones may be unwrapped.
    s.yaw_rad = samples.empty() ? e.angle_rad("yaw_rad", kMaxYaw_rad) : e.angle_rad("yaw_rad", kMaxUnwrappedYaw_rad);
    s.speed_mps = e.number_within("speed_mps", -kMaxSpeed_mps, kMaxSpeed_mps, "m/s");
    if (e.has("yaw_rate_radps")) s.yaw_rate_radps = e.number_within("yaw_rate_radps", -kMaxYawRate_radps, kMaxYawRate_radps, "rad/s");
    const auto size_m = [&e](const char* name) -> std::optional<double> {
      if (!e.has(name)) return std::nullopt;
      require_positive(e, name, e.number(name));
      return e.number_within(name, 0.0, kMaxSize_m, "m");
    };
    s.length_m = size_m("length_m");
    s.width_m = size_m("width_m");
    if (!samples.empty() && !(s.t_s > samples.back().t_s)) {
      e.fail("t_s", fmt::format("times must increase: {} follows {}", s.t_s, samples.back().t_s));
    }
    samples.push_back(s);
  }
  return samples;
}

int Scene::cycle_count() const {
  return static_cast<int>(std::floor(duration_s / cycle_time_s + 1e-9)) + 1;
}

std::size_t Scene::most_reflectors_present() const {
  std::size_t always = 0;
  std::vector<std::pair<double, long long>> changes;  // (time, +count at its start, -count after its end)
  for (const SceneObject& o : objects) {
    const auto n = static_cast<long long>(o.model.reflector_count());
    if (o.presence.empty()) always += static_cast<std::size_t>(n);
    for (const TimeInterval& i : o.presence) {
      // A span that is not finite is no time at all (a streamed scene's "not yet present").
      if (std::isfinite(i.from_s) && std::isfinite(i.until_s)) changes.emplace_back(i.from_s, n), changes.emplace_back(i.until_s, -n);
    }
  }
  // At one time starts before ends: the intervals are closed.
  std::sort(changes.begin(), changes.end(), [](const auto& a, const auto& b) { return a.first != b.first ? a.first < b.first : a.second > b.second; });
  long long present = 0, most = 0;
  for (const auto& [t_s, change] : changes) most = std::max(most, present += change);
  return always + static_cast<std::size_t>(most);
}

Scene parse_scene(const JsonField& root, const ModelLibrary& library, const std::string& base_dir) {
  root.expect_only({"format", "version", "name", "description", "duration_s", "cycle_time_s", "effects", "ego",
                    "objects"});
  root.expect_format("rcsim-scene", 1);
  if (root.has("name")) root.string("name");
  if (root.has("description")) root.string("description");
  Scene scene;
  scene.source = root.file();
  require_non_negative(root, "duration_s", root.number("duration_s"));
  scene.duration_s = root.number_within("duration_s", 0.0, limits::kMaxTime_s, "s");
  require_non_negative(root, "duration_s", scene.duration_s);

  if (const auto effects = root.optional_member("effects")) {
    effects->expect_only({"clutter", "multibounce", "occlusion"});
    scene.effects.clutter = effects->boolean_or("clutter", false);
    scene.effects.multibounce = effects->boolean_or("multibounce", false);
    scene.effects.occlusion = effects->boolean_or("occlusion", false);
  }

  const auto ego = root.member("ego");
  ego.expect_only({"trajectory", "sensors"});
  scene.ego = Trajectory(parse_trajectory(ego, "trajectory"));
  const auto sensors = ego.array("sensors");
  if (sensors.empty()) ego.fail("sensors", "the ego vehicle needs at least one sensor");
  std::set<std::string> sensor_ids;
  for (const auto& s : sensors) {
    s.expect_only({"id", "type", "x_m", "y_m", "yaw_rad", "z_m", "pitch_rad"});
    MountedSensor sensor;
    sensor.id = s.string("id");
    if (!sensor_ids.insert(sensor.id).second) s.fail("id", "duplicate sensor id \"" + sensor.id + "\"");
    sensor.config = sensor_config_for(s, base_dir);
    sensor.X_VS = {s.number_within("x_m", -limits::kMaxMountOffset_m, limits::kMaxMountOffset_m, "m"),
                   s.number_within("y_m", -limits::kMaxMountOffset_m, limits::kMaxMountOffset_m, "m"),
                   s.angle_rad("yaw_rad", limits::kMaxMountYaw_rad)};
    sensor.z_m = s.has("z_m") ? s.number_within("z_m", 0.0, limits::kMaxMountOffset_m, "m") : 0.0;
    sensor.pitch_rad = s.has("pitch_rad") ? s.angle_rad("pitch_rad", limits::kMaxMountPitch_rad) : 0.0;
    scene.sensors.push_back(std::move(sensor));
  }

  scene.cycle_time_s = root.has("cycle_time_s")
                           ? root.number_within("cycle_time_s", 0.0, limits::kMaxCycleTime_s, "s")
                           : scene.sensors.front().config.cycle_time_s;
  require_positive(root, "cycle_time_s", scene.cycle_time_s);
  if (scene.duration_s / scene.cycle_time_s > 1e8) root.fail("duration_s", "more than 10^8 cycles");

  std::set<std::string> object_ids;
  if (root.has("objects")) {
    for (const auto& o : root.array("objects")) {
      o.expect_only({"id", "model", "trajectory", "polyline", "present_from_s", "present_until_s", "present_s"});
      SceneObject object;
      object.id = o.string("id");
      if (!object_ids.insert(object.id).second) o.fail("id", "duplicate object id \"" + object.id + "\"");
      object.model_name = o.string("model");
      object.model = model_for(o, library, base_dir);
      if (object.model.polyline || o.has("polyline")) {
        parse_polyline_object(o, object);
        scene.objects.push_back(std::move(object));
        continue;
      }
      const auto samples = parse_trajectory(o, "trajectory");
      // Sizes given on the samples (annotated boxes) scale the model; the median resists outliers.
      std::vector<double> lengths, widths;
      for (const auto& s : samples) {
        if (s.length_m) lengths.push_back(*s.length_m);
        if (s.width_m) widths.push_back(*s.width_m);
      }
      if (!lengths.empty() || !widths.empty()) {
        const double length_m = lengths.empty() ? object.model.length_m : median(lengths);
        const double width_m = widths.empty() ? object.model.width_m : median(widths);
        try {
          object.model = scale_model(object.model, length_m, width_m);
        } catch (const std::invalid_argument& e) {
          o.fail("trajectory", fmt::format("cannot scale model \"{}\" to {} m x {} m: {}", object.model_name, length_m,
                                           width_m, e.what()));
        }
      }
      object.trajectory = Trajectory(samples);
      object.presence = parse_presence(o);
      scene.objects.push_back(std::move(object));
    }
  }
  return scene;
}

Scene load_scene_file(const std::string& path, const ModelLibrary& library) {
  const auto json = parse_json_file(path);
  return parse_scene(JsonField(json, path, ""), library, std::filesystem::path(path).parent_path().string());
}

}  // namespace rcsim
