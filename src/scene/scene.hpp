#pragma once
// A traffic scene (`rcsim-scene`, schemas/scene.md): the ego vehicle with its mounted sensors and
// the objects, each with a trajectory; built once, validated, then read-only.
#include <limits>
#include <string>
#include <vector>

#include "model/model_library.hpp"
#include "scene/trajectory.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim {

struct Effects {
  bool clutter = false;      // sporadic false detections (paper VI)
  bool multibounce = false;  // back-and-forth reflections at short range (paper V, Fig. 17)
  bool occlusion = false;    // reflection centers hidden behind nearer objects
};

struct MountedSensor {
  std::string id;
  SensorConfig config;
  Pose2 X_VS;  // sensor pose in the ego vehicle frame
  // A radar that measures elevation reads these (planar ones ignore them): the sensor's height
  // above the road and its pitch, positive with the boresight tilted down (ISO 8855: about y).
  double z_m = 0.0;
  double pitch_rad = 0.0;
  double cycle_time_s = 0.0;  // a sensor on its own clock (a replayed recording v4): its cycle time; 0: the scene's
};

struct TimeInterval {
  double from_s = 0.0;
  double until_s = 0.0;
};

struct SceneObject {
  std::string id;
  std::string model_name;
  ObjectModel model;  // scaled to the object's size
  Trajectory trajectory;
  // The object takes part in the scene only within these closed time intervals (imported
  // recordings: the spans of its annotation); empty: always.
  std::vector<TimeInterval> presence;
  bool present_at(double t_s) const {
    if (presence.empty()) return true;
    for (const TimeInterval& i : presence) {
      if (t_s >= i.from_s && t_s <= i.until_s) return true;
    }
    return false;
  }
};

struct Scene {
  std::string source;  // file it came from, for messages
  double duration_s = 0.0;
  double cycle_time_s = 0.0;
  Effects effects;
  Trajectory ego;
  std::vector<MountedSensor> sensors;
  std::vector<SceneObject> objects;

  // Cycles k = 0..n-1 at t = k * cycle_time_s, the last one at or before duration_s.
  int cycle_count() const;
  // The most reflection centres of objects present at one time (each object's presence closed):
  // what one cycle's ideal target list can hold, far below every object's together where the
  // objects come and go (a dataset of snapshots: every frame's objects are one scene's). A span
  // that is not finite counts as none: a streamed scene learns its objects' spans as it goes, and
  // the buffers then grow to what the cycles need.
  std::size_t most_reflectors_present() const;
  double cycle_time_at(int cycle) const { return cycle * cycle_time_s; }
  // Sensor i's cycle time: its own (on its own clock) or the scene's.
  double sensor_cycle_time_s(std::size_t i) const {
    return sensors.at(i).cycle_time_s > 0.0 ? sensors[i].cycle_time_s : cycle_time_s;
  }
};

// A sensor type or model name that names a file (contains '/' or ends in .json), and its path:
// relative names are relative to base_dir (the scene file's or recording's directory).
bool looks_like_path(const std::string& name);
std::string resolve_relative(const std::string& base_dir, const std::string& name);
// A sensor `type`: a built-in configuration name or a file path relative to base_dir.
// Throws std::invalid_argument with a message when neither.
SensorConfig sensor_config_for_type(const std::string& type, const std::string& base_dir);
// An object `model`: a library model name or a file path relative to base_dir; throws likewise.
ObjectModel object_model_for_name(const std::string& name, const ModelLibrary& library, const std::string& base_dir);

std::vector<TrajectorySample> parse_trajectory(const JsonField& owner, std::string_view key);
Scene parse_scene(const JsonField& root, const ModelLibrary& library, const std::string& base_dir);
Scene load_scene_file(const std::string& path, const ModelLibrary& library);

}  // namespace rcsim
