// Calibration files (replay/import/calibration.hpp): the bundled calibration loads with its
// sensors, models and the recordings it was fitted on; what it holds replaces the built-in of the
// same name and nothing else; a file listed under the wrong name is refused naming it.
#include "replay/import/calibration.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "model/model_library.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;
const fs::path kBundled = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "calibration";

TEST(CalibrationFile, TheBundledCalibrationLoads) {
  const auto calibration = load_calibration(kBundled.string());
  EXPECT_EQ(calibration->source, kBundled.string());
  ASSERT_EQ(calibration->sensors.count("srr24"), 1u);
  EXPECT_EQ(calibration->models.count("passenger_car"), 1u);
  EXPECT_EQ(calibration->models.count("pole"), 1u);
  EXPECT_FALSE(calibration->fitted_on_checksums.empty());
  for (const auto& checksum : calibration->fitted_on_checksums) EXPECT_EQ(checksum.size(), 16u) << checksum;
}

TEST(CalibrationFile, ReplacesOnlyWhatItHolds) {
  const auto calibration = load_calibration(kBundled.string());
  const SensorConfig srr24 = builtin_sensor_config("srr24");
  const SensorConfig& used = calibrated_sensor(calibration.get(), srr24);
  EXPECT_NE(&used, &srr24);
  EXPECT_EQ(used.name, "srr24");
  EXPECT_EQ(&calibrated_sensor(nullptr, srr24), &srr24);  // no calibration: the built-in
  const ModelLibrary library = ModelLibrary::builtin();
  Calibration only_sensors = *calibration;
  only_sensors.models.clear();
  const ObjectModel& car = library.at("passenger_car");
  EXPECT_EQ(&calibrated_model(&only_sensors, car), &car);
  EXPECT_NE(&calibrated_model(calibration.get(), car), &car);
}

class CalibrationFileRefusals : public rcsim::testing::ScratchDirTest {
 protected:
  CalibrationFileRefusals() : ScratchDirTest("calibration_file") {}
};

TEST_F(CalibrationFileRefusals, AFileUnderTheWrongNameIsRefusedNamingIt) {
  fs::copy_file(kBundled / "sensor_srr24.json", dir_ / "sensor_srr24.json");
  std::ofstream(dir_ / "calibration.json")
      << R"({"format": "rcsim-calibration", "version": 1, "sensors": {"lrr77": "sensor_srr24.json"}, "models": {}})";
  try {
    load_calibration(dir_.string());
    FAIL() << "a sensor file listed under another name was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("calibration.json"), std::string::npos) << what;
    EXPECT_NE(what.find("lrr77"), std::string::npos) << what;
    EXPECT_NE(what.find("not \"lrr77\""), std::string::npos) << what;
  }
  std::ofstream(dir_ / "calibration.json")
      << R"({"format": "rcsim-calibration", "version": 1, "sensors": {}, "models": {"pole": "missing.json"}})";
  EXPECT_THROW(load_calibration(dir_.string()), InputError);
}

}  // namespace
}  // namespace rcsim::replay
