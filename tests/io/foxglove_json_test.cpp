// Foxglove's messages as JSON (src/io/foxglove_json.cpp), by hand: times, a yaw as a quaternion,
// colours, a transform, a view field's line, and the frame names made from sensor ids.
#include "io/foxglove_json.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "common/target_colours.hpp"

namespace rcsim::foxglove_json_test {

using foxglove::Json;

TEST(FoxgloveJson, TimesPosesAndColoursByHand) {
  EXPECT_EQ(foxglove::time_ns(1.25), 1250000000u);
  EXPECT_EQ(foxglove::time_ns(-1.0), 0u);
  EXPECT_EQ(foxglove::time_json(3000000007ULL), Json({{"sec", 3}, {"nsec", 7}}));
  // A yaw of 90 deg about z: (0, 0, sin 45, cos 45).
  const Json q = foxglove::yaw_quaternion(kPi / 2.0);
  EXPECT_DOUBLE_EQ(q["x"].get<double>(), 0.0);
  EXPECT_NEAR(q["z"].get<double>(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q["w"].get<double>(), std::sqrt(0.5), 1e-15);
  // #1f5fbf: 31, 95, 191 over 255.
  EXPECT_EQ(foxglove::colour("#1f5fbf", 0.5), Json({{"r", 31 / 255.0}, {"g", 95 / 255.0}, {"b", 191 / 255.0}, {"a", 0.5}}));
}

TEST(FoxgloveJson, ATransformAndAnEntityCarryTheirFramesAndLifetimes) {
  const Json t = foxglove::frame_transform(2000000000ULL, "world", "ego", Pose2{1.0, -2.0, 0.0});
  EXPECT_EQ(t["parent_frame_id"], "world");
  EXPECT_EQ(t["child_frame_id"], "ego");
  EXPECT_EQ(t["translation"], Json({{"x", 1.0}, {"y", -2.0}, {"z", 0.0}}));
  EXPECT_EQ(t["timestamp"], Json({{"sec", 2}, {"nsec", 0}}));
  const Json e = foxglove::entity(5, "front", "recorded", 40000000ULL);
  EXPECT_EQ(e["frame_id"], "front");
  EXPECT_EQ(e["lifetime"], Json({{"sec", 0}, {"nsec", 40000000}}));
  for (const char* list : {"arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"}) {
    EXPECT_TRUE(e[list].is_array() && e[list].empty()) << list;
  }
  EXPECT_EQ(foxglove::scene_update(Json::array({e}))["entities"][0]["id"], "recorded");
}

TEST(FoxgloveJson, AViewFieldIsALineFromTheSensorAlongTheArcAndBack) {
  // +-30 deg at 10 m: 33 arc points between the origin at both ends; the first at -30 deg:
  // (10 cos 30, -10 sin 30) = (8.660, -5).
  const Json e = foxglove::view_field_entity("front", kPi / 6.0, 10.0, 0);
  const Json& points = e["lines"][0]["points"];
  ASSERT_EQ(points.size(), 35u);
  EXPECT_EQ(points.front(), Json({{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}));
  EXPECT_EQ(points.back(), points.front());
  EXPECT_NEAR(points[1]["x"].get<double>(), 8.660254037844387, 1e-12);
  EXPECT_NEAR(points[1]["y"].get<double>(), -5.0, 1e-12);
  EXPECT_EQ(e["frame_locked"], true);
  EXPECT_EQ(e["lifetime"], Json({{"sec", 0}, {"nsec", 0}}));  // for ever
}

// The text writers give the JSON the builders give, member for member and in the same order.
TEST(FoxgloveJson, TheTextWritersGiveTheBuildersJson) {
  const Pose2 X{12.5, -3.25, 0.7};
  EXPECT_EQ(Json::parse(foxglove::text::frame_transform(3000000007ULL, foxglove::text::quoted("world"), foxglove::text::quoted("ego"), X)),
            foxglove::frame_transform(3000000007ULL, "world", "ego", X));
  foxglove::text::Entity text(5, foxglove::text::quoted("fl \"1\""), foxglove::text::quoted("recorded"), 40000000ULL);
  Json built = foxglove::entity(5, "fl \"1\"", "recorded", 40000000ULL);
  text.sphere(1.0, 2.0, 0.25, 0.0, 0.5, 0.5, 0.5, foxglove::text::colour("#1f5fbf"));
  built["spheres"].push_back({{"pose", foxglove::pose_json(1.0, 2.0, 0.25, 0.0)}, {"size", foxglove::vec3(0.5, 0.5, 0.5)},
                              {"color", foxglove::colour("#1f5fbf")}});
  text.cube(-4.0, 1e-7, 0.0, 0.0, 0.5, 0.5, 0.5, foxglove::text::colour("#0ca678", 0.5));
  built["cubes"].push_back({{"pose", foxglove::pose_json(-4.0, 1e-7, 0.0, 0.0)}, {"size", foxglove::vec3(0.5, 0.5, 0.5)},
                            {"color", foxglove::colour("#0ca678", 0.5)}});
  text.box(X, 4.6, 1.8, foxglove::text::quoted("car\n7"));
  built["cubes"].push_back({{"pose", foxglove::pose_json(12.5, -3.25, 0.75, 0.7)}, {"size", foxglove::vec3(4.6, 1.8, 1.5)},
                            {"color", foxglove::colour(colours::kBackground, 0.35)}});
  built["texts"].push_back({{"pose", foxglove::pose_json(12.5, -3.25, 2.0, 0.0)}, {"billboard", true}, {"font_size", 14.0},
                            {"scale_invariant", true}, {"color", foxglove::colour(colours::kLabel)}, {"text", "car\n7"}});
  EXPECT_EQ(Json::parse(text.scene_update()), foxglove::scene_update(Json::array({built})));
  std::string n;
  foxglove::text::number(n, std::nan(""));
  EXPECT_EQ(n, "null");  // JSON has no NaN
}

TEST(FoxgloveJson, FramesAreSensorIdsMadeSafeAndUnique) {
  EXPECT_EQ(foxglove::frame_name("front_left", 0, {}), "front_left");
  EXPECT_EQ(foxglove::frame_name("F LRR/C", 1, {}), "F_LRR_C");
  EXPECT_EQ(foxglove::frame_name("", 2, {}), "sensor_2");
  EXPECT_EQ(foxglove::frame_name("ego", 3, {}), "sensor_3");  // a frame of the file's own
  EXPECT_EQ(foxglove::frame_name("a", 4, {"a"}), "sensor_4");
}

TEST(FoxgloveJson, TheSchemasAreJsonSchemasTitledWithFoxglovesNames) {
  EXPECT_EQ(Json::parse(foxglove::scene_update_schema())["title"], "foxglove.SceneUpdate");
  EXPECT_EQ(Json::parse(foxglove::frame_transform_schema())["title"], "foxglove.FrameTransform");
  EXPECT_TRUE(Json::parse(foxglove::scene_update_schema())["properties"]["entities"]["items"]["properties"].contains("spheres"));
}

}  // namespace rcsim::foxglove_json_test
