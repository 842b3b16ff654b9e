#include "replay/import/calibration.hpp"

#include <filesystem>
#include <fmt/format.h>

#include "common/json_reader.hpp"
#include "common/text_file.hpp"
#include "model/model_library.hpp"

namespace rcsim::replay {

namespace {

// The {name: file} object `key` of the index, as (name, path) pairs; every file must exist.
std::vector<std::pair<std::string, std::string>> listed_files(const JsonField& root, std::string_view key,
                                                              const std::string& dir) {
  const JsonField files = root.member(key);
  if (!files.json().is_object()) root.fail(key, "must be an object of name: file");
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, file] : files.json().items()) {
    if (!file.is_string()) files.fail(name, "must be a file name");
    const std::string path = (std::filesystem::path(dir) / file.get<std::string>()).string();
    if (!std::filesystem::is_regular_file(path)) files.fail(name, "file not found: " + path);
    out.emplace_back(name, path);
  }
  return out;
}

}  // namespace

std::shared_ptr<const Calibration> load_calibration(const std::string& dir) {
  const std::filesystem::path index_path = std::filesystem::path(dir) / kCalibrationIndexFile;
  if (!std::filesystem::is_regular_file(index_path)) {
    throw InputError(index_path.string(), "", "no calibration here (rcsim calibrate -o DIR writes one)");
  }
  const auto json = parse_json_file(index_path.string());
  const JsonField root(json, index_path.string(), "");
  root.expect_format(kCalibrationFormat, kCalibrationVersion);
  auto calibration = std::make_shared<Calibration>();
  calibration->source = dir;
  std::uint64_t hash = fnv1a64_file(index_path, 0xcbf29ce484222325ULL);
  for (const auto& [name, path] : listed_files(root, "sensors", dir)) {
    hash = fnv1a64_file(path, hash);
    SensorConfig config = load_sensor_config_file(path);
    if (config.name != name) root.fail("sensors", path + " holds \"" + config.name + "\", not \"" + name + "\"");
    calibration->sensors.insert_or_assign(name, std::move(config));
  }
  for (const auto& [name, path] : listed_files(root, "models", dir)) {
    hash = fnv1a64_file(path, hash);
    ObjectModel model = load_object_model_file(path);
    if (model.name != name) root.fail("models", path + " holds \"" + model.name + "\", not \"" + name + "\"");
    calibration->models.insert_or_assign(name, std::move(model));
  }
  calibration->checksum = fmt::format("{:016x}", hash);
  if (const auto it = json.find("fitted_on"); it != json.end() && it->is_array()) {  // informational
    for (const auto& r : *it) {
      if (r.is_object() && r.contains("checksum") && r["checksum"].is_string()) {
        calibration->fitted_on_checksums.push_back(r["checksum"].get<std::string>());
      }
    }
  }
  const auto is_true = [](const nlohmann::json& j, const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_boolean() && it->get<bool>();
  };
  calibration->partial = is_true(json, "partial") || (json.contains("fit") && json["fit"].is_object() && is_true(json["fit"], "partial"));
  return calibration;
}

const SensorConfig& calibrated_sensor(const Calibration* calibration, const SensorConfig& fallback) {
  if (calibration == nullptr) return fallback;
  const auto it = calibration->sensors.find(fallback.name);
  return it == calibration->sensors.end() ? fallback : it->second;
}

const ObjectModel& calibrated_model(const Calibration* calibration, const ObjectModel& fallback) {
  if (calibration == nullptr) return fallback;
  const auto it = calibration->models.find(fallback.name);
  return it == calibration->models.end() ? fallback : it->second;
}

}  // namespace rcsim::replay
