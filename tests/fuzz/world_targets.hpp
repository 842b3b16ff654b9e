#pragma once
// Fuzz entry points of the world's parsers (docs/fuzzing.md): a scene (`rcsim simulate`'s
// load_scene_file), an object model and a sensor configuration (the files a scene or a
// calibration names). Each parses as the command line does; what is accepted is then simulated
// for a few cycles, so that nonsense the parser lets through and the model cannot take is found.
#include <algorithm>
#include <sstream>

#include "common/embedded_data.hpp"
#include "common/json_reader.hpp"
#include "fuzz/fuzz_support.hpp"
#include "model/model_library.hpp"
#include "scene/scene.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/simulation.hpp"
#include "sim/target_list_writer.hpp"

namespace rcsim::fuzz {

// The first cycles (tracks confirm after four hits) and the last one, written as target lists.
inline void simulate_a_few_cycles(const Scene& scene) {
  constexpr int kFirstCycles = 5;
  SimulationOptions options;
  options.seed = 1;
  Simulation simulation(scene, options);
  std::ostringstream out;
  TargetListWriter writer(out, TargetListFormat::Csv, options.level);
  writer.write_header();
  const int n = simulation.cycle_count();
  const auto run = [&](int cycle) {
    simulation.run_cycle(cycle);
    for (std::size_t s = 0; s < simulation.sensor_count(); ++s) {
      writer.write_sensor_cycle(scene, cycle, scene.cycle_time_at(cycle), scene.sensors[s].id, simulation.sensor_state(s));
    }
  };
  for (int cycle = 0; cycle < std::min(n, kFirstCycles); ++cycle) run(cycle);
  if (n > kFirstCycles) run(n - 1);
}

// The built-in model library, and a directory holding a model and a sensor file beside the scene
// (a scene may name either by a relative path).
struct SceneWorld {
  ModelLibrary library = ModelLibrary::builtin();
  std::filesystem::path dir = fresh_dir("scene");
  SceneWorld() {
    for (const auto& file : embedded_object_models()) write_file(dir / ("model_" + std::string(file.name) + ".json"), file.text);
    for (const auto& file : embedded_sensor_configs()) write_file(dir / ("sensor_" + std::string(file.name) + ".json"), file.text);
  }
};

// Input: a scene file (schemas/scene.md).
inline void fuzz_scene(Input data) {
  static const SceneWorld world;
  refusals_are_fine([&] {
    const std::string file = (world.dir / "scene.json").string();
    const nlohmann::json json = parse_json_text(as_text(data), file);
    const Scene scene = parse_scene(JsonField(json, file, ""), world.library, world.dir.string());
    simulate_a_few_cycles(scene);
  });
}

// Input: an object model file (schemas/object-model.md). Accepted, it is the model of an object
// in a small scene (tests/fuzz/base/model_scene.json; a polyline template along the polyline of
// model_polyline_scene.json), loaded from a file as a scene loads one, and simulated.
inline void fuzz_object_model(Input data) {
  static const ModelLibrary library = ModelLibrary::builtin();
  static const std::string object_scene = read_source_file("tests/fuzz/base/model_scene.json");
  static const std::string polyline_scene = read_source_file("tests/fuzz/base/model_polyline_scene.json");
  refusals_are_fine([&] {
    const nlohmann::json json = parse_json_text(as_text(data), "model.json");
    const ObjectModel model = parse_object_model(JsonField(json, "model.json", ""));
    const std::filesystem::path dir = fresh_dir("object_model");
    write_file(dir / "model.json", as_text(data));
    const std::string file = (dir / "scene.json").string();
    const nlohmann::json scene_json = parse_json_text(model.polyline ? polyline_scene : object_scene, file);
    simulate_a_few_cycles(parse_scene(JsonField(scene_json, file, ""), library, dir.string()));
  });
}

// Input: a sensor configuration file (schemas/sensor-config.md). Accepted, it is the type of
// both sensors of a small scene (tests/fuzz/base/sensor_scene.json), loaded from a file as a
// scene loads one, and simulated.
inline void fuzz_sensor_config(Input data) {
  static const ModelLibrary library = ModelLibrary::builtin();
  static const std::string scene_text = read_source_file("tests/fuzz/base/sensor_scene.json");
  refusals_are_fine([&] {
    const nlohmann::json json = parse_json_text(as_text(data), "sensor.json");
    (void)parse_sensor_config(JsonField(json, "sensor.json", ""));
    const std::filesystem::path dir = fresh_dir("sensor_config");
    write_file(dir / "sensor.json", as_text(data));
    const std::string file = (dir / "scene.json").string();
    const nlohmann::json scene_json = parse_json_text(scene_text, file);
    simulate_a_few_cycles(parse_scene(JsonField(scene_json, file, ""), library, dir.string()));
  });
}

}  // namespace rcsim::fuzz
