#pragma once
// A calibration (rcsim-calibration v1, schemas/calibration.md): sensor configurations and object
// models fitted to recordings by rcsim calibrate (replay/calibrate/calibration_fit.hpp), which replace the
// built-ins of the same name when rcsim replay or rcsim bench is given --calibration DIR.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "model/object_model.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::replay {

inline constexpr std::string_view kCalibrationFormat = "rcsim-calibration";
inline constexpr int kCalibrationVersion = 1;
inline constexpr std::string_view kCalibrationIndexFile = "calibration.json";

struct Calibration {
  std::string source;                           // the directory it was read from ("" if in memory)
  std::string checksum;                         // FNV-1a 64 of calibration.json and the files it lists, 16 hex digits
  std::map<std::string, SensorConfig> sensors;  // by the configuration's name (srr24, ...)
  std::map<std::string, ObjectModel> models;    // by the model's name (the class)
  std::vector<std::string> fitted_on_checksums;  // of the recordings it was fitted on (16 hex digits)
  // The fit was interrupted (Ctrl-C): the best values so far, not a finished fit (the index's
  // "partial": true; a --real-drive index's fit.partial too).
  bool partial = false;
};

// Reads DIR/calibration.json and the sensor and model files it lists; errors name the file and
// field.
std::shared_ptr<const Calibration> load_calibration(const std::string& dir);

// The configuration a calibration holds for this name, else `fallback`.
const SensorConfig& calibrated_sensor(const Calibration* calibration, const SensorConfig& fallback);
// The model a calibration holds for this name, else `fallback`.
const ObjectModel& calibrated_model(const Calibration* calibration, const ObjectModel& fallback);

}  // namespace rcsim::replay
