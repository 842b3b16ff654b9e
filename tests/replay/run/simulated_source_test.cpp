// The two simulated sources a recording is compared with (replay/run/simulated_source.hpp): the
// model at the tracks level, and the signal-level reference; both report a pole 10 m ahead near
// 10 m, the model once its tracker confirms it.
#include "replay/run/simulated_source.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace rcsim::replay {
namespace {

Scene pole_ahead() {
  Scene scene = testing::single_sensor_scene(1.0);
  testing::add_object(scene, "pole", "pole", {testing::sample(0.0, 10.0, 0.0, 0.0, 0.0)});
  return scene;
}

TEST(SimulatedSource, ModelOptionsCompareTracksWithTheGivenSeed) {
  const SimulationOptions options = model_options(42, Fidelity::points_only);
  EXPECT_EQ(options.level, ListLevel::tracks);
  EXPECT_EQ(options.seed, 42u);
  EXPECT_EQ(options.fidelity, Fidelity::points_only);
}

TEST(SimulatedSource, TheModelReportsAfterConfirmation) {
  const Scene scene = pole_ahead();
  ModelSource source(scene, model_options(1, Fidelity::full));
  source.run_at(0.0, -1);
  std::vector<ComparedTarget> targets;
  source.append_targets(0, targets);
  EXPECT_TRUE(targets.empty());  // tentative: nothing reported yet (4-hit confirmation, paper III-E)
  for (int k = 1; k <= 3; ++k) source.run_at(k * scene.cycle_time_s, -1);
  source.append_targets(0, targets);
  ASSERT_EQ(targets.size(), 1u);
  EXPECT_NEAR(targets[0].range_m, 10.0, 0.3);
  EXPECT_GE(targets[0].track_id, 0);
}

TEST(SimulatedSource, TheReferenceReportsThePole) {
  const Scene scene = pole_ahead();
  ReferenceSource source(scene, 5);
  std::vector<ComparedTarget> targets;
  for (int k = 0; k <= 4; ++k) source.run_at(k * scene.cycle_time_s, -1);
  source.append_targets(0, targets);
  ASSERT_FALSE(targets.empty());
  EXPECT_NEAR(targets[0].range_m, 10.0, 0.5);
}

}  // namespace
}  // namespace rcsim::replay
