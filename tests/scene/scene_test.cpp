// Scene loading and its refusals of bad input: every message names the file and the field.
#include "scene/scene.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "common/json_reader.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

const std::string kValid = R"({
  "format": "rcsim-scene", "version": 1, "duration_s": 1.0,
  "ego": {"trajectory": [{"t_s": 0, "x_m": 0, "y_m": 0, "yaw_rad": 0, "speed_mps": 10}],
          "sensors": [{"id": "fr", "type": "srr24", "x_m": 3.7, "y_m": -0.7, "yaw_rad": -0.5}]},
  "objects": [{"id": "car1", "model": "passenger_car",
               "trajectory": [{"t_s": 0, "x_m": 20, "y_m": -3, "yaw_rad": 3.1416, "speed_mps": 5, "length_m": 4.0, "width_m": 1.7},
                              {"t_s": 5, "x_m": 0, "y_m": -3, "yaw_rad": 3.1416, "speed_mps": 3, "length_m": 4.2, "width_m": 1.7}]}]
})";

Scene parse(const std::string& text) {
  const auto json = parse_json_text(text, "scene.json");
  return parse_scene(JsonField(json, "scene.json", ""), testing::library(), "");
}

// Replaces the first occurrence of `from` by `to` in the valid scene and expects an error
// whose message contains every one of `needles`.
void expect_refused(const std::string& from, const std::string& to, std::initializer_list<std::string> needles) {
  std::string text = kValid;
  const auto pos = text.find(from);
  ASSERT_NE(pos, std::string::npos) << from;
  text.replace(pos, from.size(), to);
  try {
    parse(text);
    FAIL() << "accepted: " << to;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
    for (const auto& n : needles) EXPECT_NE(message.find(n), std::string::npos) << message << " lacks " << n;
  }
}

TEST(Scene, ValidSceneLoads) {
  const Scene s = parse(kValid);
  EXPECT_EQ(s.sensors.size(), 1u);
  EXPECT_DOUBLE_EQ(s.cycle_time_s, 0.04);  // from the sensor configuration
  EXPECT_EQ(s.cycle_count(), 26);          // t = 0, 0.04, ..., 1.0
  EXPECT_FALSE(s.effects.occlusion);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_DOUBLE_EQ(s.objects[0].model.length_m, 4.1);  // median of the annotated lengths
}

TEST(Scene, RefusesBadInput) {
  expect_refused("\"duration_s\": 1.0,", "\"duration_s\": 1.0,,", {"line 2", "invalid JSON"});
  expect_refused("\"duration_s\": 1.0", "\"duration_s\": -1.0", {"duration_s", "negative"});
  expect_refused("\"duration_s\": 1.0", "\"duration_s\": \"1\"", {"duration_s", "number"});
  expect_refused("\"version\": 1", "\"version\": 2", {"version", "unsupported"});
  expect_refused("\"passenger_car\"", "\"spaceship\"", {"objects[0].model", "unknown object model", "passenger_car"});
  expect_refused("\"srr24\"", "\"lrr77\"", {"ego.sensors[0].type", "unknown sensor type"});
  expect_refused("\"t_s\": 5", "\"t_s\": 0", {"objects[0].trajectory[1].t_s", "increase"});
  expect_refused("\"yaw_rad\": 3.1416, \"speed_mps\": 5", "\"yaw_deg\": 180, \"speed_mps\": 5",
                 {"objects[0].trajectory[0].yaw_deg", "unknown field"});
  expect_refused("\"length_m\": 4.0", "\"length_m\": -4.0", {"objects[0].trajectory[0].length_m", "positive"});
  expect_refused("\"length_m\": 4.0, \"width_m\": 1.7", "\"length_m\": 50.0, \"width_m\": 0.2",
                 {"objects[0].trajectory", "cannot scale model \"passenger_car\""});
  expect_refused("\"x_m\": 20", "\"x_m\": 1e999", {"number overflow", "1e999"});
  expect_refused("\"id\": \"car1\"", "\"id\": \"\"", {"objects[0].id", "empty"});
  expect_refused("\"sensors\": [", "\"sensors\": [{\"id\": \"fr\", \"type\": \"srr24\", \"x_m\": 0, \"y_m\": 0, \"yaw_rad\": 0},",
                 {"ego.sensors[1].id", "duplicate"});
  expect_refused("\"format\": \"rcsim-scene\"", "\"format\": \"rcsim-recording\"", {"format", "rcsim-scene"});
  expect_refused("\"trajectory\": [{\"t_s\": 0, \"x_m\": 0,", "\"trajectory\": [{\"t_s\": 0,", {"ego.trajectory[0].x_m", "missing"});
}

TEST(Scene, NaNIsNotJson) {
  expect_refused("\"x_m\": 20", "\"x_m\": NaN", {"invalid JSON", "line"});
}

TEST(Scene, SensorAndModelFilesResolveRelativeToTheScene) {
  const auto dir = std::filesystem::temp_directory_path() / "rcsim_scene_test";
  std::filesystem::create_directories(dir);
  std::string text = kValid;
  text.replace(text.find("\"passenger_car\""), 15, "\"my_pole.json\"");
  { std::ofstream(dir / "scene.json") << text; }
  {
    std::ofstream(dir / "my_pole.json") << R"({"format": "rcsim-object-model", "version": 1, "name": "my_pole",
      "length_m": 0.2, "width_m": 0.2, "point_reflectors": [{"name": "p", "x_m": 0, "y_m": 0, "ercs": 3,
      "visibility": {"center_deg": 0, "full_halfwidth_deg": 180, "falloff_deg": 0}}]})";
  }
  const Scene s = load_scene_file((dir / "scene.json").string(), testing::library());
  EXPECT_DOUBLE_EQ(s.objects[0].model.max_ercs(), 3.0);
  { std::ofstream(dir / "my_pole.json") << R"({"format": "rcsim-object-model", "version": 1, "name": "my_pole",
      "length_m": 0.2, "width_m": 0.2, "point_reflectors": [{"name": "p", "x_m": 0, "y_m": 0, "ercs": -3,
      "visibility": {"center_deg": 0, "full_halfwidth_deg": 180, "falloff_deg": 0}}]})"; }
  try {
    load_scene_file((dir / "scene.json").string(), testing::library());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("my_pole.json: point_reflectors[0].ercs"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(ModelLibrary, BuiltinsAreThere) {
  for (const char* name : {"passenger_car", "truck_trailer", "guide_board", "pole"}) {
    EXPECT_TRUE(testing::library().contains(name)) << name;
  }
  const auto& pole = testing::library().at("pole");
  ASSERT_EQ(pole.points.size(), 1u);
  EXPECT_DOUBLE_EQ(pole.points[0].ercs(1.234), 1.0);  // visible from every direction, ERCS 1
  EXPECT_EQ(testing::library().at("passenger_car").points.size(), 8u);  // Fig. 3: A..H
  EXPECT_EQ(testing::library().at("passenger_car").planes.size(), 4u);
}

// A cycle holds the reflectors of the objects present at one time: cars (12 reflectors: 8 points,
// 4 planes) that come and go count only while present, intervals closed at both ends; a pole
// without presence counts always.
TEST(Scene, TheMostReflectorsPresentAtOneTime) {
  Scene scene;
  const auto object = [&](const char* model, std::vector<TimeInterval> presence) {
    SceneObject o;
    o.model = testing::library().at(model);
    o.presence = std::move(presence);
    scene.objects.push_back(o);
  };
  object("passenger_car", {{0.0, 1.0}});
  object("passenger_car", {{2.0, 3.0}});
  object("passenger_car", {{2.5, 4.0}, {10.0, 11.0}});
  EXPECT_EQ(scene.most_reflectors_present(), 24u);  // two cars at 2.5-3 s, not three
  object("passenger_car", {{1.0, 1.5}});           // meets the first at 1 s: both present then
  object("pole", {});
  EXPECT_EQ(scene.most_reflectors_present(), 25u);  // 24 + the pole (cars 1 and 4: 24 at 1 s as well)
  object("passenger_car", {{1.0, 1.0}});
  EXPECT_EQ(scene.most_reflectors_present(), 37u);  // three cars at 1 s, and the pole
  const double inf = std::numeric_limits<double>::infinity();
  object("passenger_car", {{inf, inf}});  // a streamed scene's "not yet present": no time at all
  EXPECT_EQ(scene.most_reflectors_present(), 37u);
}

// A guard rail 3.5 m left of a road along x: its polyline runs against x so that its left (the
// side its posts face) is the road.
const std::string kRail = R"({
  "format": "rcsim-scene", "version": 1, "duration_s": 1.0, "cycle_time_s": 0.5,
  "ego": {"trajectory": [{"t_s": 0, "x_m": 0, "y_m": 0, "yaw_rad": 0, "speed_mps": 20}],
          "sensors": [{"id": "fr", "type": "srr24", "x_m": 0, "y_m": 0, "yaw_rad": 0}]},
  "objects": [{"id": "rail", "model": "guard_rail", "polyline": [{"x_m": 100, "y_m": 3.5}, {"x_m": -100, "y_m": 3.5}]}]
})";

TEST(Scene, PolylineObjectStandsStillAlongItsPoints) {
  const Scene scene = parse(kRail);
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& rail = scene.objects[0];
  // 200 m at 4 m: posts at 0, 4, ..., 200 m: 51; faces: 50 pieces of 4 m.
  EXPECT_EQ(rail.model.points.size(), 51u);
  EXPECT_EQ(rail.model.planes.size(), 50u);
  const BodyState state = rail.trajectory.state_at(0.7);
  EXPECT_NEAR(state.X_WB.x_m, 0.0, 1e-12);  // the points' mean, standing still
  EXPECT_NEAR(state.X_WB.y_m, 3.5, 1e-12);
  EXPECT_NEAR(rail.model.points[0].p_OR_O.x(), 100.0, 1e-12);

  // Ideal level: every rail target lies on the rail (y = 3.5 m) and has the range rate of a
  // stationary point seen at 20 m/s: -20 cos(az).
  SimulationOptions options;
  options.level = ListLevel::ideal;
  options.noise = false;
  Simulation simulation(scene, options);
  int targets = 0;
  simulation.run_at(0.0);
  for (const IdealTarget& t : simulation.sensor_state(0).ideal) {
    ++targets;
    EXPECT_NEAR(t.range_m * std::sin(t.azimuth_rad), 3.5, 0.011);  // faces bulge 1 cm
    EXPECT_NEAR(t.range_rate_mps, -20.0 * std::cos(t.azimuth_rad), 1e-9);
  }
  EXPECT_GT(targets, 3);

  // The same rail drawn the other way faces away from the road: no post is seen.
  std::string reversed = kRail;
  const std::string forward = R"([{"x_m": 100, "y_m": 3.5}, {"x_m": -100, "y_m": 3.5}])";
  reversed.replace(reversed.find(forward), forward.size(), R"([{"x_m": -100, "y_m": 3.5}, {"x_m": 100, "y_m": 3.5}])");
  const Scene reversed_scene = parse(reversed);  // the simulation keeps a reference to its scene
  Simulation other(reversed_scene, options);
  other.run_at(0.0);
  EXPECT_TRUE(other.sensor_state(0).ideal.empty());
}

TEST(Scene, PolylineObjectsRefusedWhereTheyDoNotFit) {
  const auto refused = [](const std::string& from, const std::string& to, const std::string& needle) {
    std::string text = kRail;
    text.replace(text.find(from), from.size(), to);
    try {
      parse(text);
      ADD_FAILURE() << "accepted: " << to;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  refused("\"model\": \"guard_rail\"", "\"model\": \"passenger_car\"", "objects[0].polyline");
  refused("\"polyline\": [{\"x_m\": 100, \"y_m\": 3.5}, ", "\"polyline\": [", "objects[0].polyline");
  refused("\"polyline\"", "\"trajectory\"", "polyline model");
  refused("\"y_m\": 3.5}]", "\"y_m\": 3.5}], \"trajectory\": []", "objects[0].trajectory");
}

}  // namespace
}  // namespace rcsim
