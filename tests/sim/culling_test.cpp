// The broad phase (sim/culling.hpp) never changes the output: byte-identical target lists with
// culling on and off, on every example scene, every synthetic recording and random traffic.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "app/cli/run_rcsim.hpp"
#include "common/angles.hpp"
#include "common/rng.hpp"
#include "io/recording.hpp"
#include "replay/import/importer.hpp"
#include "sim/scene_culling.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;

std::string target_lists(const Scene& scene, ListLevel level, bool culling, std::uint64_t seed = 3) {
  SimulationOptions options;
  options.level = level;
  options.seed = seed;
  options.culling = culling;
  return testing::simulate_rows(scene, options);
}

void expect_culling_invisible(const Scene& scene, const std::string& name) {
  for (const ListLevel level : {ListLevel::ideal, ListLevel::detections, ListLevel::tracks}) {
    const std::string on = target_lists(scene, level, true);
    const std::string off = target_lists(scene, level, false);
    EXPECT_GT(on.size(), 0u);
    EXPECT_TRUE(on == off) << name << " level " << static_cast<int>(level);
  }
  // The srr24's 40 m view range lies inside its detectable range, so the range bound never cuts
  // there; with a 400 m view range it does (BoundsCullFarAndBehind), and must not change anything.
  Scene long_range = scene;
  for (auto& sensor : long_range.sensors) sensor.config.fov.max_range_m = 400.0;
  for (const ListLevel level : {ListLevel::detections, ListLevel::tracks}) {
    EXPECT_TRUE(target_lists(long_range, level, true) == target_lists(long_range, level, false))
        << name << " (400 m view range) level " << static_cast<int>(level);
  }
}

// Present objects at t = 0 more than 5 m beyond the first sensor's cull distance (and within
// 395 m): where the range bound culls, so that an on/off comparison tests it.
int objects_beyond_cull_distance(const Scene& scene) {
  const CullingBounds b = make_culling_bounds(scene.sensors[0].config, scene.effects, scene.objects, true, true);
  const Vec2 p_WE_W = scene.ego.state_at(0.0).X_WB.translation();
  int beyond = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const double d_m = (scene.objects[i].trajectory.state_at(0.0).X_WB.translation() - p_WE_W).norm();
    if (scene.objects[i].present_at(0.0) && d_m > b.cull_distance_m[i] + 5.0 && d_m < 395.0) ++beyond;
  }
  return beyond;
}

TEST(Culling, ExampleScenesByteIdentical) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RCSIM_SOURCE_DIR) / "docs/examples")) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene_file(entry.path().string(), testing::library());
    expect_culling_invisible(scene, entry.path().filename().string());
    ++scenes;
  }
  EXPECT_GE(scenes, 7);
}

TEST(Culling, SyntheticRecordingsByteIdentical) {
  int recordings = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic")) {
    if (!fs::exists(entry.path() / "recording.json")) continue;
    const Recording recording = read_recording(entry.path());
    const replay::ImportedScene imported = import_recording(recording, testing::library(), replay::ImportOptions{});
    const Scene scene = replay::build_scene(imported, testing::library(), recording.dir.string());
    expect_culling_invisible(scene, recording.name);
    ++recordings;
  }
  EXPECT_GE(recordings, 9);
}

TEST(Culling, RandomTrafficByteIdentical) {
  const fs::path dir = fs::temp_directory_path() / ("rcsim_culling_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const char* layouts[] = {"highway", "ring", "intersection"};
  for (int seed = 1; seed <= 6; ++seed) {
    const fs::path scene_path = dir / ("traffic_" + std::to_string(seed) + ".json");
    const std::string layout = layouts[seed % 3];
    ASSERT_EQ(testing::run_rcsim("traffic --layout " + layout + " --duration-s 8 --seed " + std::to_string(seed) +
                                 " -o " + scene_path.string())
                  .exit_code,
              0);
    const Scene scene = load_scene_file(scene_path.string(), testing::library());
    expect_culling_invisible(scene, scene_path.filename().string());
    // The range bound does cull here (so the 400 m comparison above tests it): some present object
    // at t = 0 lies beyond its cull distance from the first sensor.
    const int beyond = objects_beyond_cull_distance(scene);
    EXPECT_GT(beyond, 0) << layout;
  }
  // And through the command line, as a user runs it.
  const fs::path scene_path = dir / "traffic_1.json";
  const auto on = testing::run_rcsim("simulate " + scene_path.string() + " --seed 9", false);
  const auto off = testing::run_rcsim("simulate " + scene_path.string() + " --seed 9 --no-culling", false);
  ASSERT_EQ(on.exit_code, 0);
  ASSERT_EQ(off.exit_code, 0);
  EXPECT_TRUE(on.output == off.output);
  fs::remove_all(dir);
}

// The bound culls something where it should: a car far beyond its detectable range and a car
// behind the sensor produce no ideal targets with culling on at the tracks level.
TEST(Culling, BoundsCullFarAndBehind) {
  Scene scene = testing::single_sensor_scene(0.2);
  const SensorConfig& config = scene.sensors[0].config;
  const std::vector<SceneObject> objects = [&] {
    std::vector<SceneObject> v(1);
    v[0].model = testing::library().at("passenger_car");
    return v;
  }();
  const CullingBounds b = make_culling_bounds(config, scene.effects, objects, true, true);
  ASSERT_TRUE(b.by_range);
  ASSERT_EQ(b.cull_distance_m.size(), 1u);
  // The bound lies beyond the single strongest reflector's detectable range (eq. (1)).
  const double single_m = (config.amplitude.reference_level_db - config.amplitude.detection_threshold_db +
                           20.0 * std::log10(objects[0].model.max_ercs())) /
                          config.amplitude.reference_slope_db_per_m;
  EXPECT_GT(b.cull_distance_m[0], single_m);
  EXPECT_LT(b.cull_distance_m[0], 400.0);  // cuts inside a 400 m view range
  EXPECT_GE(b.radius_m[0], objects[0].model.bounding_radius_m());
  // Off at the ideal level: only the (exact) view culling.
  const CullingBounds ideal = make_culling_bounds(config, scene.effects, objects, false, true);
  EXPECT_FALSE(ideal.by_range);
}

// A flat side is an arc of a large circle: its reach is that of its farther end, not
// |centre| + radius (which made every car 144 m wide to the broad phase).
TEST(Culling, ArcReachByHand) {
  // A 1.5 m chord at x = 2.2 with 1 cm sagitta: circle radius (0.75^2 + 0.01^2) / 0.02 = 28.13 m.
  const PlaneReflector side = plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.01, 1.0);
  EXPECT_NEAR(side.radius_m, (0.75 * 0.75 + 0.01 * 0.01) / 0.02, 1e-9);
  // The arc does not face the centre (which lies behind it, at x = 2.21 - 28.13): ends at |(2.2, 0.75)|.
  EXPECT_NEAR(arc_reach_m(side), std::hypot(2.2, 0.75), 1e-9);
  // A quarter arc of radius 1 about (3, 0) from 135 deg to 225 deg does not cover the direction
  // of the centre (0 deg): its ends (3 - 0.7071, +-0.7071) are farthest, 2.3801 m.
  PlaneReflector quarter;
  quarter.center_O = {3.0, 0.0};
  quarter.radius_m = 1.0;
  quarter.set_arc(0.75 * kPi, 0.5 * kPi);
  EXPECT_NEAR(arc_reach_m(quarter), std::hypot(3.0 - std::sqrt(0.5), std::sqrt(0.5)), 1e-12);
  // Turned to face away from the origin (-45 deg .. 45 deg): it covers the centre's direction, 4 m.
  quarter.set_arc(-0.25 * kPi, 0.5 * kPi);
  EXPECT_NEAR(arc_reach_m(quarter), 4.0, 1e-12);
  // Property: no sampled arc point lies farther than the reach, and the farthest comes within 1e-6.
  Rng rng(5);
  for (int trial = 0; trial < 500; ++trial) {
    PlaneReflector p;
    p.center_O = {rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0)};
    p.radius_m = rng.uniform(0.1, 100.0);
    p.set_arc(rng.uniform(-kPi, kPi), rng.uniform(0.0, kTwoPi));
    const double reach_m = arc_reach_m(p);
    double farthest_m = 0.0;
    for (int j = 0; j <= 20000; ++j) {
      const double d_m = p.arc_point_O(p.start_rad + p.span_rad * j / 20000.0).norm();
      ASSERT_LE(d_m, reach_m + 1e-9) << "trial " << trial;
      farthest_m = std::max(farthest_m, d_m);
    }
    EXPECT_NEAR(farthest_m, reach_m, 1e-6 * (1.0 + reach_m)) << "trial " << trial;
  }
}

// The bound with diffuse face pieces (sensor_config ExtendedObjects) by hand, srr24's eq. (1):
// L0 26.5 dB, 0.75 dB/m, threshold 6 dB, no fluctuation: headroom = the 1-dB margin. One object:
// a 4-m face (chord (-2, 1) .. (2, 1), 1 cm sagitta) of ERCS 1, no points; reflection radius
// |(2, 1)| = sqrt(5) (its arc ends).
TEST(Culling, DiffusePiecesWidenTheBoundByHand) {
  const SensorConfig srr24 = builtin_sensor_config("srr24");
  std::vector<SceneObject> objects(1);
  objects[0].model.planes.push_back(plane_from_chord("face", {-2.0, 1.0}, {2.0, 1.0}, 0.01, 1.0));
  const Effects effects;
  const auto cull_m = [&](double diffuse) {
    SensorConfig config = srr24;
    config.extended_objects.diffuse_relative_ercs_per_sqrt_m = diffuse;
    const CullingBounds b = make_culling_bounds(config, effects, objects, true, true);
    EXPECT_NEAR(b.radius_m[0], std::sqrt(5.0), 1e-9);
    return b.cull_distance_m[0];
  };
  // Without pieces: (a) (26.5 - 6 + 1 + 20 log10 1) / 0.75 + 0.3 = 28.9667 m, (b) 28.6667 m:
  // 28.9667 + 2.2361 = 31.2027 m.
  EXPECT_NEAR(cull_m(0.0), 21.5 / 0.75 + 0.3 + std::sqrt(5.0), 1e-9);
  // r = 0.5: ERCS sum 1 + 0.5 x 1 x sqrt(16 x 4) = 5, echoes 1 + 16 = 17, the strongest single one
  // max(1, 0.5 sqrt(4)) = 1: (a) (21.5 + 13.9794) / 0.75 + 0.3 = 47.6059 m, (b) (21.5 + 20 log10 17)
  // / 0.75 = (21.5 + 24.6090) / 0.75 = 61.4786 m: 61.4786 + 2.2361 = 63.7147 m.
  EXPECT_NEAR(cull_m(0.5), (21.5 + 20.0 * std::log10(17.0)) / 0.75 + std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(cull_m(0.5), 63.7147, 1e-4);
  // r = 2: one piece of the whole chord is the strongest, 2 sqrt(4) = 4: (b) (21.5 + 20 log10(17 x 4))
  // / 0.75 = 77.5336 m (beyond (a): sum 1 + 2 x 8 = 17, 61.7786 m): 79.7696 m.
  EXPECT_NEAR(cull_m(2.0), (21.5 + 20.0 * std::log10(68.0)) / 0.75 + std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(cull_m(2.0), 79.7696, 1e-4);
}

// With diffuse face pieces the culling is still exact: the bundled scenes with srr24 plus an
// extended_objects block, and with the aimotive_lrr profile (radar equation with its fitted range
// exponent, Swerling 1, local maxima, occlusion as a loss, diffuse pieces) in the scenes' own
// mounting geometry.
TEST(Culling, DiffusePiecesByteIdentical) {
  int srr24_with_pieces = 0, lrr_with_pieces = 0;  // scenes whose ideal targets include pieces
  for (const char* file : {"front_approach.json", "perpendicular_crossing.json", "parking_area.json"}) {
    const Scene original = load_scene_file((fs::path(RCSIM_SOURCE_DIR) / "docs/examples" / file).string(), testing::library());
    Scene diffuse = original;
    for (auto& sensor : diffuse.sensors) sensor.config.extended_objects.diffuse_relative_ercs_per_sqrt_m = 0.5;
    srr24_with_pieces += target_lists(diffuse, ListLevel::ideal, true).find("#diffuse") != std::string::npos;
    expect_culling_invisible(diffuse, std::string(file) + " (srr24, diffuse 0.5)");
    Scene lrr = original;
    for (auto& sensor : lrr.sensors) sensor.config = builtin_sensor_config("aimotive_lrr");
    lrr.effects.occlusion = true;
    lrr_with_pieces += target_lists(lrr, ListLevel::ideal, true).find("#diffuse") != std::string::npos;
    expect_culling_invisible(lrr, std::string(file) + " (aimotive_lrr)");
  }
  EXPECT_EQ(srr24_with_pieces, 3);
  EXPECT_GE(lrr_with_pieces, 1);  // its +-17 deg view misses the car of front_approach (sensors at +-29 deg)
}

// Random traffic, where the range bound does cull (RandomTrafficByteIdentical), with strong
// pieces (r = 2) and a 400-m view range: the pieces' ERCS must be inside the bound.
TEST(Culling, DiffusePiecesInRandomTrafficByteIdentical) {
  const fs::path dir = fs::temp_directory_path() / ("rcsim_culling_diffuse_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path scene_path = dir / "traffic.json";
  ASSERT_EQ(testing::run_rcsim("traffic --layout highway --duration-s 6 --seed 2 -o " + scene_path.string()).exit_code, 0);
  Scene scene = load_scene_file(scene_path.string(), testing::library());
  fs::remove_all(dir);
  for (auto& sensor : scene.sensors) {
    sensor.config.extended_objects.diffuse_relative_ercs_per_sqrt_m = 2.0;
    sensor.config.fov.max_range_m = 400.0;
  }
  for (const ListLevel level : {ListLevel::detections, ListLevel::tracks}) {
    const std::string on = target_lists(scene, level, true);
    EXPECT_GT(on.size(), 0u);
    EXPECT_TRUE(on == target_lists(scene, level, false)) << "level " << static_cast<int>(level);
  }
  // The bound, wider with the pieces, still culls here: some present object lies beyond it.
  const int beyond = objects_beyond_cull_distance(scene);
  EXPECT_GT(beyond, 0);
}

}  // namespace
}  // namespace rcsim
