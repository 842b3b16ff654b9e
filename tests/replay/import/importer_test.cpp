#include "replay/import/importer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

TEST(Importer, AnnotationNoiseDoesNotTurnIntoYawRatesOrSpeeds) {
  // A car driving straight at 4 m/s, annotated with 5 cm and 1° of noise.
  const Scene scene = testing::two_cars_scene(6.0);
  const Recording rec = testing::model_recording(scene, 1, 0.05, 0.01745);
  const ImportedScene imported = import_recording(rec, testing::library(), ImportOptions{});
  ASSERT_EQ(imported.objects.size(), 2u);
  double yaw_rate_sq = 0.0, position_sq = 0.0;
  const auto& samples = imported.objects[0].trajectory;
  for (const auto& s : samples) {
    yaw_rate_sq += std::pow(*s.yaw_rate_radps, 2);
    const BodyState truth = scene.objects[0].trajectory.state_at(s.t_s);
    position_sq += (Vec2(s.x_m, s.y_m) - truth.X_WB.translation()).squaredNorm();
  }
  const double n = static_cast<double>(samples.size());
  EXPECT_LT(std::sqrt(yaw_rate_sq / n), 0.05);
  EXPECT_LT(std::sqrt(position_sq / n), 0.05);  // less than the 7 cm of the raw 2-D noise
  EXPECT_DOUBLE_EQ(imported.objects[0].length_m, scene.objects[0].model.length_m);
  ASSERT_EQ(imported.objects[0].presence.size(), 1u);
  EXPECT_NEAR(imported.objects[0].presence[0].from_s, -0.02, 1e-12);
}

TEST(Importer, BuildsASceneWithScaledModelsAndShiftedTimes) {
  Scene scene = testing::two_cars_scene(1.0);
  Recording rec = testing::model_recording(scene, 1);
  rec.objects[0].length_m = 5.0;
  for (auto& e : rec.ego) e.t_s += 100.0;
  for (auto& b : rec.boxes) for (auto& box : b) box.t_s += 100.0;
  const ImportedScene imported = import_recording(rec, testing::library(), ImportOptions{});
  EXPECT_DOUBLE_EQ(imported.time_offset_s, 100.0);
  EXPECT_NEAR(imported.objects[0].trajectory.front().t_s, 0.0, 1e-9);
  const Scene built = build_scene(imported, testing::library(), "");
  EXPECT_DOUBLE_EQ(built.objects[0].model.length_m, 5.0);
  EXPECT_EQ(built.sensors.size(), 2u);
  EXPECT_TRUE(built.objects[0].present_at(0.5));
  EXPECT_FALSE(built.objects[0].present_at(1.5));
}

TEST(Importer, WrittenSceneLoadsBack) {
  const Scene scene = testing::two_cars_scene(1.0);
  const ImportedScene imported = import_recording(testing::model_recording(scene, 1), testing::library(), {});
  const fs::path path = fs::temp_directory_path() / ("rcsim_import_" + std::to_string(::getpid()) + ".json");
  write_scene_file(path.string(), imported);
  const Scene loaded = load_scene_file(path.string(), testing::library());
  fs::remove(path);
  EXPECT_EQ(loaded.objects.size(), 2u);
  EXPECT_EQ(loaded.cycle_count(), scene.cycle_count());
  ASSERT_EQ(loaded.objects[1].presence.size(), 1u);
  EXPECT_NEAR(loaded.objects[1].presence[0].until_s, imported.objects[1].presence[0].until_s, 1e-12);
}

TEST(Importer, AWrongTypedSourceEffectsIsRefusedByField) {
  Recording rec = testing::model_recording(testing::two_cars_scene(1.0), 1);
  rec.dir = "rec";
  for (const auto& [effects, field] : {std::pair{nlohmann::json("all"), "source.effects"},
                                       std::pair{nlohmann::json{{"clutter", "yes"}}, "source.effects.clutter"},
                                       std::pair{nlohmann::json{{"glare", true}}, "source.effects.glare"}}) {
    rec.source["effects"] = effects;
    try {
      import_recording(rec, testing::library(), {});
      ADD_FAILURE() << effects.dump() << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("recording.json: ") + field + ":"), std::string::npos) << e.what();
    }
  }
  rec.source["effects"] = {{"clutter", false}, {"occlusion", true}};
  EXPECT_FALSE(import_recording(rec, testing::library(), {}).effects.clutter);
}

TEST(Importer, RefusesUnknownClassesAndSplitsLongGaps) {
  const Scene scene = testing::two_cars_scene(2.0);
  Recording rec = testing::model_recording(scene, 1);
  rec.dir = "rec";
  Recording unknown = rec;
  unknown.objects[1].object_class = "spaceship";
  try {
    import_recording(unknown, testing::library(), {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[1].class"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("spaceship"), std::string::npos);
  }
  Recording gap = rec;
  auto& boxes = gap.boxes[0];
  boxes.erase(boxes.begin() + 10, boxes.begin() + 30);  // 0.8 s without annotation: out of sight
  const ImportedScene split = import_recording(gap, testing::library(), {});
  ASSERT_EQ(split.warnings.size(), 1u);
  EXPECT_NE(split.warnings[0].find("absent"), std::string::npos);
  const Scene scene_split = build_scene(split, testing::library(), "");
  ASSERT_EQ(scene_split.objects[0].presence.size(), 2u);
  EXPECT_TRUE(scene_split.objects[0].present_at(0.36));
  EXPECT_FALSE(scene_split.objects[0].present_at(0.8));
  EXPECT_TRUE(scene_split.objects[0].present_at(1.2));
  ImportOptions lenient;
  lenient.max_gap_s = 1.0;
  const ImportedScene bridged = import_recording(gap, testing::library(), lenient);
  ASSERT_EQ(bridged.warnings.size(), 1u);
  EXPECT_NE(bridged.warnings[0].find("interpolated"), std::string::npos);
  EXPECT_EQ(bridged.objects[0].presence.size(), 1u);
}

}  // namespace
}  // namespace rcsim::replay
