// The scene a traffic run writes (traffic/scene_writer.hpp): its fields as the text gives them,
// the same text for the same seed, and the loader's interpolation of it following the simulated
// motion.
#include "traffic/scene_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "model/model_library.hpp"
#include "scene/scene.hpp"
#include "scratch_dir.hpp"
#include "traffic/traffic_sim.hpp"
#include "traffic/traffic_fixtures.hpp"

namespace rcsim::scene_writer_test {

using namespace rcsim::traffic;

using testing::small_highway;

TEST(TrafficScene, SameSeedSameTextOtherSeedDifferent) {
  TrafficConfig c = small_highway(11);
  c.record_steps = false;
  c.duration_s = 10.0;
  const auto text = [&](std::uint64_t seed) {
    TrafficConfig cs = c;
    cs.seed = seed;
    Rng rng(seed);
    TrafficSimulation sim(cs, rng);
    sim.run(rng);
    return scene_json(sim);
  };
  const std::string a = text(11);
  EXPECT_EQ(a, text(11));
  EXPECT_NE(a, text(12));
}

TEST(TrafficScene, LoaderInterpolationFollowsTheSimulatedMotion) {
  // Samples every 0.5 s; the loader's cubic Hermite must reproduce the 0.1 s simulation steps,
  // lane changes included, to within centimetres.
  TrafficConfig c = small_highway(13);
  c.sample_interval_s = 0.5;
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  const std::filesystem::path dir = rcsim::testing::fresh_scratch_dir("scene_writer");
  const std::filesystem::path path = dir / "traffic.json";
  write_scene(path.string(), sim);
  const Scene scene = load_scene_file(path.string(), ModelLibrary::builtin());
  std::filesystem::remove_all(dir);
  ASSERT_GT(scene.objects.size(), 50u);
  double worst_m = 0.0, worst_yaw_rad = 0.0;
  for (const StepSnapshot& step : sim.snapshots()) {
    if (step.t_s < 0.0) continue;
    for (const VehicleSnapshot& s : step.vehicles) {
      const Vehicle& v = sim.vehicles()[s.vehicle];
      const Trajectory* trajectory = &scene.ego;
      if (!v.is_ego) {
        const auto it = std::find_if(scene.objects.begin(), scene.objects.end(), [&](const SceneObject& o) { return o.id == v.id; });
        ASSERT_NE(it, scene.objects.end()) << v.id;
        if (!it->present_at(step.t_s)) continue;
        trajectory = &it->trajectory;
      }
      const BodyState b = trajectory->state_at(step.t_s);
      worst_m = std::max(worst_m, std::hypot(b.X_WB.x_m - s.motion.x_m, b.X_WB.y_m - s.motion.y_m));
      worst_yaw_rad = std::max(worst_yaw_rad, std::abs(angle_difference_rad(b.X_WB.yaw_rad, s.motion.yaw_rad)));
    }
  }
  EXPECT_LT(worst_m, 0.05);
  EXPECT_LT(worst_yaw_rad, 0.005);
  EXPECT_GT(sim.lane_changes().size(), 0u);
}

// A short run written and read back as JSON: the header fields, the ego's sensors (ids escaped),
// every non-ego track once with its presence window, and samples at fixed decimals.
TEST(TrafficScene, FieldsAsTheRunGivesThem) {
  TrafficConfig c;
  c.lanes = 2;
  c.duration_s = 6.0;
  c.warmup_s = 0.0;
  c.density_vpkm = 15.0;
  c.seed = 4;
  c.cycle_time_s = 0.05;
  c.sensors = {{"front \"a\"", "srr24", 3.7, 0.5, 0.25}};
  c = resolve_traffic_config(c, ".");
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  const std::string text = scene_json(sim);
  EXPECT_EQ(text.rfind("{\n  \"format\": \"rcsim-scene\", \"version\": 1,\n", 0), 0u) << text.substr(0, 80);
  const nlohmann::json scene = nlohmann::json::parse(text);
  EXPECT_EQ(scene.at("name"), "traffic highway seed 4");
  EXPECT_EQ(scene.at("duration_s"), 6.0);
  EXPECT_EQ(scene.at("cycle_time_s"), 0.05);
  ASSERT_EQ(scene.at("ego").at("sensors").size(), 1u);
  const nlohmann::json& sensor = scene.at("ego").at("sensors")[0];
  EXPECT_EQ(sensor.at("id"), "front \"a\"");
  EXPECT_EQ(sensor.at("type"), "srr24");
  EXPECT_EQ(sensor.at("x_m"), 3.7);
  EXPECT_EQ(sensor.at("yaw_rad"), 0.25);
  // Objects: the non-ego tracks with samples, in order, each with its own samples rounded to 1 mm.
  std::size_t k = 0;
  for (const VehicleTrack& track : sim.tracks()) {
    if (track.is_ego) {
      const nlohmann::json& ego = scene.at("ego").at("trajectory");
      ASSERT_EQ(ego.size(), track.samples.size());
      EXPECT_EQ(ego[0].at("t_s"), 0.0);
      continue;
    }
    if (track.samples.empty()) continue;
    ASSERT_LT(k, scene.at("objects").size());
    const nlohmann::json& object = scene.at("objects")[k++];
    EXPECT_EQ(object.at("id"), track.id);
    EXPECT_EQ(object.at("model"), track.model);
    EXPECT_EQ(object.contains("present_from_s"), track.present_from_s.has_value()) << track.id;
    EXPECT_EQ(object.contains("present_until_s"), track.present_until_s.has_value()) << track.id;
    ASSERT_EQ(object.at("trajectory").size(), track.samples.size()) << track.id;
    for (std::size_t i = 0; i < track.samples.size(); ++i) {
      const nlohmann::json& s = object.at("trajectory")[i];
      EXPECT_NEAR(s.at("x_m").get<double>(), track.samples[i].x_m, 0.0005 + 1e-9) << track.id;
      EXPECT_NEAR(s.at("yaw_rad").get<double>(), track.samples[i].yaw_rad, 0.000005 + 1e-12) << track.id;
    }
  }
  EXPECT_EQ(k, scene.at("objects").size());
  EXPECT_GT(k, 5u);

  // Without a cycle time of its own the scene leaves the field out (the sensors' default).
  c.cycle_time_s = 0.0;
  Rng rng_again(c.seed);
  TrafficSimulation again(c, rng_again);
  again.run(rng_again);
  EXPECT_FALSE(nlohmann::json::parse(scene_json(again)).contains("cycle_time_s"));
}

class TrafficSceneFile : public rcsim::testing::ScratchDirTest {
 protected:
  TrafficSceneFile() : ScratchDirTest("scene_writer_file") {}
};

TEST_F(TrafficSceneFile, WritesTheTextOrNothing) {
  TrafficConfig c = small_highway(2);
  c.record_steps = false;
  c.duration_s = 2.0;
  c.warmup_s = 0.0;
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  const std::filesystem::path path = dir_ / "scene.json";
  write_scene(path.string(), sim);
  std::ifstream in(path, std::ios::binary);
  std::stringstream written;
  written << in.rdbuf();
  EXPECT_EQ(written.str(), scene_json(sim));
  // Into a directory that does not exist: refused naming the file, nothing left behind.
  const std::filesystem::path missing = dir_ / "no_such_dir" / "scene.json";
  try {
    write_scene(missing.string(), sim);
    FAIL() << "written into a missing directory";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), missing.string());
    EXPECT_NE(std::string(e.what()).find("cannot create output file"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "no_such_dir"));
}

}  // namespace rcsim::scene_writer_test
