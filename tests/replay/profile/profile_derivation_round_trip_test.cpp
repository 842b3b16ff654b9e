// rcsim profile derive (issue 30) given back the profile that made the data: a drive simulated by
// the reflection-center model with aimotive_lrr and written as that radar would report it
// (replay/run/model_recording.hpp: its detections, the cross-section estimate beside each SNR).
// Every value `profile derive` reads must come back within the tolerances: view +-1 deg,
// maximum range +-5 m, threshold +-0.5 dB, range exponent +-0.2, cells +-20 %, noise +-30 %; and
// the cycle time and the fluctuation model as the profile says.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "common/angles.hpp"
#include "replay/profile/profile_derivation.hpp"
#include "replay/run/model_recording.hpp"
#include "common/json_reader.hpp"
#include "sensor/sensor_config.hpp"
#include "test_support.hpp"

namespace rcsim::replay::profile {
namespace {

// 8 s at 20 m/s on a road lined with poles 1 to 6 m apart (a fixed draw), 3.5 to 14 m either side:
// pairs of stationary returns at every distance, so that the cells' gaps show; traffic ahead and
// oncoming at every range up to beyond the radar's reach.
Scene lined_road(const std::string& sensor) {
  constexpr double kDuration_s = 8.0, kSpeed_mps = 20.0;
  Scene scene = testing::single_sensor_scene(kDuration_s);
  scene.sensors[0].config = builtin_sensor_config(sensor);
  scene.sensors[0].X_VS = {3.6, 0.0, 0.0};
  scene.cycle_time_s = scene.sensors[0].config.cycle_time_s;
  scene.ego = Trajectory({testing::sample(0.0, 0.0, 0.0, 0.0, kSpeed_mps),
                          testing::sample(kDuration_s, kSpeed_mps * kDuration_s, 0.0, 0.0, kSpeed_mps)});
  int n = 0;
  const auto id = [&](const char* kind) { return std::string(kind) + std::to_string(n++); };
  std::mt19937 draw(30);
  std::uniform_real_distribution<double> spacing_m(1.0, 6.0);
  for (const double y_m : {-14.0, -8.0, -3.5, 3.5, 8.0, 14.0}) {
    for (double x_m = 5.0; x_m < 400.0; x_m += spacing_m(draw)) {
      testing::add_object(scene, id("pole"), "pole", {testing::sample(0.0, x_m, y_m, 0.0, 0.0)});
    }
  }
  // Vehicles: (start ahead, lateral, speed); a negative speed drives towards the ego.
  struct Vehicle {
    double x_m, y_m, speed_mps;
    const char* model;
  };
  const Vehicle vehicles[] = {{15.0, 3.5, 20.0, "passenger_car"},  {40.0, -3.5, 22.0, "passenger_car"},
                              {70.0, 0.0, 25.0, "truck_trailer"},  {110.0, 3.5, 27.0, "passenger_car"},
                              {150.0, -3.5, 24.0, "truck_trailer"}, {200.0, 0.0, 21.0, "truck_trailer"},
                              {260.0, -7.0, -20.0, "truck_trailer"}, {330.0, -7.0, -22.0, "passenger_car"},
                              {25.0, 7.0, 18.0, "passenger_car"},  {90.0, 7.0, 16.0, "passenger_car"}};
  for (const Vehicle& v : vehicles) {
    const double yaw_rad = v.speed_mps < 0.0 ? kPi : 0.0;
    const double end_x_m = v.x_m + v.speed_mps * kDuration_s;
    testing::add_object(scene, id("vehicle"), v.model,
                        {testing::sample(0.0, v.x_m, v.y_m, yaw_rad, std::abs(v.speed_mps)),
                         testing::sample(kDuration_s, end_x_m, v.y_m, yaw_rad, std::abs(v.speed_mps))});
  }
  return scene;
}

TEST(ProfileDeriveRoundTrip, AimotiveLrrComesBackFromItsOwnModel) {
  const Scene scene = lined_road("aimotive_lrr");
  const Recording recording = model_recording(scene, "lined_road", 7);
  // The base is the paper's srr24 (its law eq. (1), its pattern one-way): nothing of aimotive_lrr
  // comes from it.
  const ProfileDerivation d = derive_profile({&recording}, {.base = "srr24", .name = "round_trip"});
  std::map<std::string, DerivedValue> values;
  for (const DerivedValue& v : d.values) values[v.field] = v;
  const auto expect_near = [&](const std::string& field, double truth, double tolerance) {
    ASSERT_TRUE(values.count(field)) << field;
    EXPECT_EQ(values.at(field).source, ValueSource::derived) << field << ": " << values.at(field).evidence;
    EXPECT_NEAR(values.at(field).value.get<double>(), truth, tolerance) << field << ": " << values.at(field).evidence;
  };
  const SensorConfig lrr = builtin_sensor_config("aimotive_lrr");
  const MeasurementNoise& noise = lrr.noise;
  // Measured (seed 7): 17.0 deg, 180 m, 14.0 dB; the law exact (C 70.50 dB, n 2.530, residual
  // 0.00 dB: the cross-sections are the radar's own estimate), the pattern 2, 0.7, 1.5; cells
  // 1.28 m and 0.187 m/s; noise 0.042 / 0.013 m/s and 0.09 / 0.045 m; cycle 55.6 ms; Swerling 1.
  expect_near("field_of_view.azimuth_half_deg", rad_to_deg(lrr.fov.azimuth_half_rad), 1.0);
  expect_near("field_of_view.max_range_m", lrr.fov.max_range_m, 5.0);
  expect_near("amplitude.detection_threshold_db", lrr.amplitude.detection_threshold_db, 0.5);
  expect_near("amplitude.range_exponent", lrr.amplitude.range_exponent, 0.2);
  expect_near("amplitude.snr_at_1m_for_1m2_db", lrr.amplitude.snr_at_1m_for_1m2_db, 0.5);
  expect_near("antenna.amplitude_pattern_exponent", lrr.antenna.amplitude_pattern_exponent, 0.0);
  expect_near("antenna.dipole_length_wavelengths", lrr.antenna.dipole_length_wavelengths, 0.051);
  expect_near("antenna.element_spacing_wavelengths", lrr.antenna.element_spacing_wavelengths, 0.051);
  expect_near("resolution.range_cell_m", lrr.resolution.range_cell_m, 0.2 * lrr.resolution.range_cell_m);
  expect_near("resolution.range_rate_cell_mps", lrr.resolution.range_rate_cell_mps, 0.2 * lrr.resolution.range_rate_cell_mps);
  expect_near("measurement_noise.range_rate_sigma_at_threshold_mps", noise.range_rate_sigma_at_threshold_mps,
              0.3 * noise.range_rate_sigma_at_threshold_mps);
  expect_near("measurement_noise.range_rate_sigma_min_mps", noise.range_rate_sigma_min_mps, 0.3 * noise.range_rate_sigma_min_mps);
  expect_near("measurement_noise.range_sigma_at_threshold_m", noise.range_sigma_at_threshold_m, 0.3 * noise.range_sigma_at_threshold_m);
  expect_near("measurement_noise.range_sigma_min_m", noise.range_sigma_min_m, 0.3 * noise.range_sigma_min_m);
  expect_near("cycle_time_s", lrr.cycle_time_s, 0.002);
  EXPECT_EQ(values.at("detection.fluctuation").value, "swerling1") << values.at("detection.fluctuation").evidence;
  EXPECT_EQ(values.at("resolution.spectral_window").value, "none") << values.at("resolution.spectral_window").evidence;
  // The derived law replaces the base's eq. (1): the profile written is the radar equation's.
  EXPECT_EQ(values.at("amplitude.law").value, "radar_equation");
  EXPECT_EQ(d.profile.at("amplitude").value("law", ""), "radar_equation");
  EXPECT_FALSE(d.profile.at("amplitude").contains("reference_slope_db_per_m"));
  const SensorConfig derived = parse_sensor_config(JsonField(d.profile, "round_trip", ""));
  EXPECT_EQ(derived.amplitude.kind, AmplitudeLawKind::radar_equation);
}

}  // namespace
}  // namespace rcsim::replay::profile
