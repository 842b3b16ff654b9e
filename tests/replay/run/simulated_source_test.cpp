// The two simulated sources a recording is compared with (replay/run/simulated_source.hpp): the
// model at the tracks level, and the signal-level reference; both mark a pole 10 m ahead as
// detected (the model before its tracker confirms it) and report it near 10 m.
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

// The pole's box as the sensor (at the world origin, looking along +x) sees it.
std::vector<metrics::BoxInSensor> pole_box() {
  BodyState ego, pole;
  pole.X_WB = {10.0, 0.0, 0.0};
  return {metrics::box_in_sensor(0, Pose2{}, ego, pole, 0.2, 0.2)};
}

TEST(SimulatedSource, ModelOptionsCompareTracksWithTheGivenSeed) {
  const SimulationOptions options = model_options(42, Fidelity::points_only);
  EXPECT_EQ(options.level, OutputLevel::tracks);
  EXPECT_EQ(options.seed, 42u);
  EXPECT_EQ(options.fidelity, Fidelity::points_only);
}

TEST(SimulatedSource, TheModelDetectsAtOnceAndReportsAfterConfirmation) {
  const Scene scene = pole_ahead();
  ModelSource source(scene, model_options(1, Fidelity::full));
  std::vector<char> detected(1, 0);
  source.run_at(0.0);
  source.mark_detected_objects(0, pole_box(), 1.0, detected);
  EXPECT_EQ(detected[0], 1);  // a detection in the first cycle
  std::vector<ComparedTarget> targets;
  source.append_targets(0, targets);
  EXPECT_TRUE(targets.empty());  // tentative: nothing reported yet (4-hit confirmation, paper III-E)
  for (int k = 1; k <= 3; ++k) source.run_at(k * scene.cycle_time_s);
  source.append_targets(0, targets);
  ASSERT_EQ(targets.size(), 1u);
  EXPECT_NEAR(targets[0].range_m, 10.0, 0.3);
  EXPECT_GE(targets[0].track_id, 0);
}

TEST(SimulatedSource, TheReferenceDetectsThePoleByTheNearestBox) {
  const Scene scene = pole_ahead();
  ReferenceSource source(scene, 5);
  std::vector<char> detected(1, 0);
  source.run_at(0.0);
  source.mark_detected_objects(0, pole_box(), 1.0, detected);
  EXPECT_EQ(detected[0], 1);
  std::vector<char> none(1, 0);
  source.mark_detected_objects(0, {}, 1.0, none);  // no box to belong to
  EXPECT_EQ(none[0], 0);
}

}  // namespace
}  // namespace rcsim::replay
