// rcsim profile derive (issue 30) on a recording `rcsim synth` made from a known profile. The
// signal-level reference takes from aimotive_lrr only what the profile says of the radar itself
// (docs/synth.md, "One radar per profile") and is otherwise its own radar: a Hann-windowed FFT
// whose peaks lie at least two bins apart, and only its 40 strongest detections per cycle (so
// the view field's edge, where the antenna pattern is 20 dB down, does not show). What must come
// back: the maximum range, and the cells as that radar resolves them, two FFT bins.
#include <gtest/gtest.h>

#include <map>

#include "replay/profile/derivation_checks.hpp"
#include "replay/profile/profile_derivation.hpp"
#include "sensor/sensor_config.hpp"
#include "synth/reference_simulator.hpp"
#include "test_support.hpp"

namespace rcsim::replay::profile {
namespace {

// 3 s at 20 m/s through a field of poles every 4 m, 3 to 14 m either side; two cars drive ahead
// at the ego's speed, 120 m and 172 m away.
Scene pole_field() {
  Scene scene = testing::single_sensor_scene(3.0);
  scene.sensors[0].config = builtin_sensor_config("aimotive_lrr");
  scene.sensors[0].X_VS = {3.6, 0.0, 0.0};
  scene.cycle_time_s = scene.sensors[0].config.cycle_time_s;
  scene.ego = Trajectory({testing::sample(0.0, 0.0, 0.0, 0.0, 20.0), testing::sample(3.0, 60.0, 0.0, 0.0, 20.0)});
  int n = 0;
  for (double x_m = 10.0; x_m < 250.0; x_m += 4.0) {
    for (const double y_m : {-14.0, -8.0, -3.0, 3.0, 8.0, 14.0}) {
      testing::add_object(scene, "pole" + std::to_string(n++), "pole", {testing::sample(0.0, x_m, y_m, 0.0, 0.0)});
    }
  }
  for (const double ahead_m : {120.0, 172.0}) {
    testing::add_object(scene, "ahead" + std::to_string(n++), "passenger_car",
                        {testing::sample(0.0, ahead_m, 0.0, 0.0, 20.0), testing::sample(3.0, ahead_m + 60.0, 0.0, 0.0, 20.0)});
  }
  return scene;
}

TEST(ProfileDeriveSynthetic, ASynthesisedAimotiveLrrGivesItsRadarBack) {
  const Scene scene = pole_field();
  const Recording recording = synth::make_recording(scene, synth::SynthConfig{}, 3, {"lined_road", "", "test"});
  const ProfileDerivation d = derive_profile({&recording}, {.base = "aimotive_lrr", .name = "synthesised_lrr"});
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  const auto expect_near = [&](const std::string& field, double truth, double tolerance) {
    testing::expect_derived_near(values, field, truth, tolerance);
  };
  const SensorConfig lrr = builtin_sensor_config("aimotive_lrr");
  // Measured: 179 m; 2.86 m (the bins 1.40 m).
  expect_near("field_of_view.max_range_m", lrr.fov.max_range_m, 5.0);
  expect_near("resolution.range_cell_m", 2.0 * lrr.resolution.range_cell_m, 0.2 * 2.0 * lrr.resolution.range_cell_m);
  // Its amplitude is an SNR with no cross-section beside it: the law is the base's, said so.
  EXPECT_EQ(values.at("amplitude.range_exponent").source, ValueSource::base);
}

}  // namespace
}  // namespace rcsim::replay::profile
