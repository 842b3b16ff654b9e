#pragma once
// Recording -> scene (rcsim import, and the first step of rcsim replay): the ego log becomes the
// ego trajectory as it is; each annotated object gets the library model its class names, scaled
// to its annotated length and width, and a trajectory through its smoothed annotated boxes
// (annotation_smoothing.hpp); it takes part only over the spans of its annotation.
#include <memory>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/import/calibration.hpp"
#include "scene/scene.hpp"

namespace rcsim::replay {

struct ImportOptions {
  double smoothing_half_window_s = 0.5;  // ±0.5 s: about 25 boxes at 25 Hz
  // A hole in an object's annotation up to this long is bridged by interpolation; a longer one
  // means the object was out of sight: it is absent from the scene in between.
  double max_gap_s = 0.5;
  Effects effects{true, true, true};  // a real drive has clutter, multiple reflections, occlusion
  // When the recording declares the effects of its scene (recording.json source.effects, written
  // by rcsim synth), those are simulated instead of `effects`.
  bool effects_from_recording = true;
  // When set, every sensor is simulated with this configuration (a built-in name or a file path)
  // instead of the type the recording names: to compare sensor configurations on one drive.
  std::string sensor_type_override;
  // When set, a calibration directory (rcsim calibrate -o DIR): its sensors and models replace
  // the ones of the same name.
  std::string calibration_dir;
};

struct ImportedObject {
  std::string id;
  std::string model;  // the class
  double length_m = 0.0, width_m = 0.0;
  std::vector<TimeInterval> presence;  // the spans of its annotation, ± half a cycle
  std::vector<TrajectorySample> trajectory;
};

struct ImportedScene {
  std::string name;
  std::string description;
  double time_offset_s = 0.0;  // scene time = recording time − time_offset_s (the first ego row)
  double duration_s = 0.0;
  double cycle_time_s = 0.0;
  Effects effects;
  std::vector<TrajectorySample> ego;
  std::vector<RecordingSensor> sensors;
  std::vector<ImportedObject> objects;
  std::vector<std::string> warnings;  // things a person should know (bridged annotation gaps)
  long long warnings_not_kept = 0;    // a streaming import keeps the first kMaxWarnings and counts the rest
  static constexpr std::size_t kMaxWarnings = 100;
  std::shared_ptr<const Calibration> calibration;  // used by build_scene; null: none
};

ImportedScene import_recording(const Recording& recording, const ModelLibrary& library, const ImportOptions& options);

// What an import knows from recording.json alone: names, effects, sensors, calibration and the
// objects' models and sizes (no trajectories, no presence); refuses unknown classes.
ImportedScene import_header(const Recording& recording, double time_offset_s, const ModelLibrary& library,
                            const ImportOptions& options);

// The scene the simulation runs, built without a detour through JSON (an hour-long recording has
// hundreds of thousands of samples). Sensor types resolve relative to the recording directory;
// the imported scene's calibration, if any, replaces sensors and models of the same name.
Scene build_scene(const ImportedScene& imported, const ModelLibrary& library, const std::string& base_dir);

// The warning for a hole in an object's annotation: bridged (interpolated) or not (absent).
std::string annotation_gap_warning(const std::string& file, int line_before, int line_after, const std::string& object,
                                   double gap_s, bool absent);

// Writes the imported scene as an `rcsim-scene` file, atomically.
void write_scene_file(const std::string& path, const ImportedScene& imported);

}  // namespace rcsim::replay
