// Recordings made by the model itself (replay/run/model_recording.hpp): the true boxes are the
// annotation, the simulated tracks are the targets, annotation noise and range are as asked,
// and the same seed gives the same recording.
#include "replay/run/model_recording.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synth/reference_simulator.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace {

Scene two_poles_ahead(double duration_s = 1.0) {
  Scene scene = testing::single_sensor_scene(duration_s);
  testing::add_object(scene, "pole", "pole", {testing::sample(0.0, 10.0, 0.0, 0.0, 0.0)});
  testing::add_object(scene, "far", "pole", {testing::sample(0.0, 40.0, 5.0, 0.0, 0.0)});
  return scene;
}

TEST(ModelRecording, TrueBoxesAndTheModelsTracks) {
  const Scene scene = two_poles_ahead();
  const Recording rec = model_recording(scene, "poles", 3);
  EXPECT_EQ(rec.name, "poles");
  EXPECT_EQ(rec.cycle_count(), static_cast<int>(std::lround(scene.duration_s / scene.cycle_time_s)) + 1);
  ASSERT_EQ(rec.boxes.size(), 2u);
  ASSERT_EQ(rec.boxes[0].size(), static_cast<std::size_t>(rec.cycle_count()));
  EXPECT_DOUBLE_EQ(rec.boxes[0][5].x_m, 10.0);  // no noise: the true box
  EXPECT_DOUBLE_EQ(rec.boxes[0][5].y_m, 0.0);
  ASSERT_FALSE(rec.targets.empty());
  // The pole 10 m ahead is confirmed after 4 hits (paper III-E) and then reported near 10 m.
  EXPECT_GE(rec.targets.front().cycle, 3);
  EXPECT_NEAR(rec.targets.back().range_m, 10.0, 0.5);
  for (std::size_t i = 1; i < rec.targets.size(); ++i) EXPECT_LE(rec.targets[i - 1].cycle, rec.targets[i].cycle);
}

TEST(ModelRecording, NoiseAndAnnotationRangeAsAsked) {
  const Scene scene = two_poles_ahead(2.0);
  const Recording noisy = model_recording(scene, "poles", 3, {0.05, 0.0, 20.0});
  // The far pole is never within 20 m: it is not in the recording at all.
  ASSERT_EQ(noisy.boxes.size(), 1u);
  ASSERT_EQ(noisy.objects.size(), 1u);
  EXPECT_EQ(noisy.objects[0].id, "pole");
  double sum_sq = 0.0;
  for (const AnnotatedBox& b : noisy.boxes[0]) sum_sq += std::pow(b.x_m - 10.0, 2) + std::pow(b.y_m, 2);
  const double sigma_m = std::sqrt(sum_sq / (2.0 * static_cast<double>(noisy.boxes[0].size())));
  EXPECT_GT(sigma_m, 0.03);
  EXPECT_LT(sigma_m, 0.07);
  const Recording again = model_recording(scene, "poles", 3, {0.05, 0.0, 20.0});
  EXPECT_EQ(again.boxes[0][7].x_m, noisy.boxes[0][7].x_m);  // same seed, same draws
  EXPECT_EQ(again.targets.size(), noisy.targets.size());
}

}  // namespace
}  // namespace rcsim::replay

namespace rcsim::replay {
namespace {

// Both writers of a recording from a scene (the model's, rcsim synth's) give ego.csv's speed as
// the signed speed along the heading: a reversing ego drives at -2 m/s in both.
TEST(ModelRecording, TheEgoSpeedIsSignedAsSynthWritesIt) {
  Scene scene = two_poles_ahead(0.5);
  scene.ego = Trajectory({testing::sample(0.0, 10.0, 0.0, 0.0, -2.0), testing::sample(0.5, 9.0, 0.0, 0.0, -2.0)});
  const Recording model = model_recording(scene, "reversing", 1);
  const Recording synth = synth::make_recording(scene, synth::SynthConfig{}, 1, {"reversing", "", "test"});
  ASSERT_EQ(model.ego.size(), synth.ego.size());
  for (std::size_t k = 0; k < model.ego.size(); ++k) {
    EXPECT_NEAR(model.ego[k].speed_mps, -2.0, 1e-9) << k;
    EXPECT_EQ(model.ego[k].speed_mps, synth.ego[k].speed_mps) << k;
    EXPECT_EQ(model.ego[k].yaw_rad, synth.ego[k].yaw_rad) << k;
  }
}

}  // namespace
}  // namespace rcsim::replay
