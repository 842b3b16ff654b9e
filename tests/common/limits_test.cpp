// The stated limits of what rcsim reads (schemas/limits.md), as issue 21 found them missing:
// a track table of INT_MAX, an ERCS or a length of 1e308, headings and mounting angles in
// degrees. Each is refused naming the file and the field or line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "scene/scene.hpp"
#include "scratch_dir.hpp"
#include "sensor/sensor_config.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string refusal_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

json srr24() {
  const fs::path path = fs::path(RCSIM_SOURCE_DIR) / "src/sensor/sensors/srr24.json";
  return json::parse(std::ifstream(path));
}

std::string sensor_refusal(const json& doc) {
  return refusal_of([&] { parse_sensor_config(JsonField(doc, "sensor.json", "")); });
}

TEST(InputLimits, ASensorOfAbsurdSizeIsRefusedByField) {
  json doc = srr24();
  doc["tracking"]["max_tracks"] = 2147483647;
  EXPECT_NE(sensor_refusal(doc).find("sensor.json: tracking.max_tracks: must be a whole number from 1 to 100000"),
            std::string::npos)
      << sensor_refusal(doc);
  doc = srr24();
  doc["tracking"]["max_tracks"] = 1e308;  // beyond INT_MAX: checked before any conversion
  EXPECT_NE(sensor_refusal(doc).find("max_tracks"), std::string::npos);
  doc = srr24();
  doc["field_of_view"]["max_range_m"] = 1e308;
  EXPECT_NE(sensor_refusal(doc).find("field_of_view.max_range_m: 1e+308 is beyond the limits [0, 10000]"),
            std::string::npos)
      << sensor_refusal(doc);
  doc = srr24();
  doc["cycle_time_s"] = 40;  // milliseconds?
  EXPECT_NE(sensor_refusal(doc).find("cycle_time_s: 40 is beyond the limits [0, 10]"), std::string::npos)
      << sensor_refusal(doc);
  EXPECT_EQ(sensor_refusal(srr24()), "accepted");
}

TEST(InputLimits, AModelWithAHugeErcsOrSizeIsRefusedByField) {
  const fs::path path = fs::path(RCSIM_SOURCE_DIR) / "src/model/models/passenger_car.json";
  const json car = json::parse(std::ifstream(path));
  const auto refusal = [](const json& doc) {
    return refusal_of([&] { parse_object_model(JsonField(doc, "model.json", "")); });
  };
  EXPECT_EQ(refusal(car), "accepted");
  json doc = car;
  doc["point_reflectors"][0]["ercs"] = 1e308;
  EXPECT_NE(refusal(doc).find("model.json: point_reflectors[0].ercs: 1e+308 is beyond the limits [0, 10000]"),
            std::string::npos)
      << refusal(doc);
  doc = car;
  doc["length_m"] = 4500;  // millimetres?
  EXPECT_NE(refusal(doc).find("length_m: 4500 is beyond the limits [0, 100] m"), std::string::npos) << refusal(doc);
}

TEST(InputLimits, ASceneWithAHugeLengthOrAnglesInDegreesIsRefusedByField) {
  const auto scene_refusal = [](const json& doc) {
    return refusal_of([&] { parse_scene(JsonField(doc, "scene.json", ""), ModelLibrary::builtin(), "."); });
  };
  const json sample = {{"t_s", 0.0}, {"x_m", 10.0}, {"y_m", 0.0}, {"yaw_rad", 3.14}, {"speed_mps", 0.0}};
  json doc = {{"format", "rcsim-scene"},
              {"version", 1},
              {"name", "limits"},
              {"duration_s", 1.0},
              {"ego",
               {{"trajectory", json::array({{{"t_s", 0.0}, {"x_m", 0.0}, {"y_m", 0.0}, {"yaw_rad", 0.0}, {"speed_mps", 0.0}}})},
                {"sensors", json::array({{{"id", "s"}, {"type", "srr24"}, {"x_m", 3.7}, {"y_m", 0.0}, {"yaw_rad", 0.5}}})}}},
              {"objects", json::array({{{"id", "car"}, {"model", "passenger_car"}, {"trajectory", json::array({sample})}}})}};
  EXPECT_EQ(scene_refusal(doc), "accepted");
  json bad = doc;
  bad["objects"][0]["trajectory"][0]["length_m"] = 1e308;
  EXPECT_NE(scene_refusal(bad).find("scene.json: objects[0].trajectory[0].length_m: 1e+308 is beyond the limits [0, 100] m"),
            std::string::npos)
      << scene_refusal(bad);
  bad = doc;
  bad["objects"][0]["trajectory"][0]["yaw_rad"] = 180.0;
  EXPECT_NE(scene_refusal(bad).find("objects[0].trajectory[0].yaw_rad: 180 rad is beyond ±6.2832 rad: is it in degrees?"),
            std::string::npos)
      << scene_refusal(bad);
  bad = doc;
  bad["ego"]["sensors"][0]["yaw_rad"] = 30.0;
  EXPECT_NE(scene_refusal(bad).find("ego.sensors[0].yaw_rad: 30 rad is beyond ±3.1416 rad: is it in degrees?"),
            std::string::npos)
      << scene_refusal(bad);
  bad = doc;
  bad["duration_s"] = 1e308;
  EXPECT_NE(scene_refusal(bad).find("duration_s: 1e+308 is beyond the limits"), std::string::npos) << scene_refusal(bad);
}

TEST(InputLimits, ARecordingWithAnglesInDegreesIsRefusedByFieldAndLine) {
  const fs::path dir = testing::fresh_scratch_dir("input_limits") / "rec";
  Recording rec;
  rec.name = "limits";
  rec.cycle_time_s = 0.04;
  rec.sensors = {{"front", "srr24", 3.7, 0.0, 0.0}};
  rec.objects = {{"car1", "passenger_car", 4.5, 1.8}};
  rec.boxes.resize(1);
  for (int k = 0; k < 3; ++k) {
    rec.ego.push_back({0.04 * k, 0.0, 0.0, 0.0, 0.0, 0.0});
    rec.boxes[0].push_back({0.04 * k, 20.0, 1.0, 90.0, 0.0, 0});  // heading in degrees
  }
  write_recording(dir, rec);
  EXPECT_NE(refusal_of([&] { read_recording(dir); }).find("objects.csv: line 2, column 'yaw_rad': yaw beyond ±2π: is it in degrees?"),
            std::string::npos)
      << refusal_of([&] { read_recording(dir); });
  for (auto& b : rec.boxes[0]) b.yaw_rad = 1.57;
  rec.sensors[0].yaw_rad = 45.0;  // mounting in degrees
  write_recording(dir, rec);
  EXPECT_NE(refusal_of([&] { read_recording(dir); }).find("recording.json: sensors[0].yaw_rad: 45 rad is beyond ±3.1416 rad"),
            std::string::npos)
      << refusal_of([&] { read_recording(dir); });
  rec.sensors[0].yaw_rad = 0.5;
  write_recording(dir, rec);
  EXPECT_EQ(refusal_of([&] { read_recording(dir); }), "accepted");
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

TEST(InputLimits, ACsvWithAByteOrderMarkOrCarriageReturnsAloneSaysSo) {
  const fs::path dir = testing::fresh_scratch_dir("csv_line_ends");
  for (const auto& [name, text, expected] :
       {std::tuple{"bom", "\xEF\xBB\xBFt_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,0,0,0\n",
                   "ego.csv: line 1: starts with a UTF-8 byte-order mark"},
        std::tuple{"cr", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\r0,0,0,0,0,0\r",
                   "ego.csv: line 1: holds a carriage return inside the line"}}) {
    const fs::path copy = dir / name;
    fs::copy(testing::kBundledRecordings / "close_front", copy);
    std::ofstream(copy / "ego.csv", std::ios::binary | std::ios::trunc) << text;
    const std::string refusal = refusal_of([&] { read_recording(copy); });
    EXPECT_NE(refusal.find(expected), std::string::npos) << refusal;
  }
}

}  // namespace
}  // namespace rcsim
