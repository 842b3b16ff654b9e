// rcsim profile derive (issue 30) given back the profile that made the data: docs/examples/
// round_trip/lined_road.json (8 s at 20 m/s, poles 1 to 6 m apart either side, ten vehicles out to
// beyond 180 m) simulated by the reflection-center model with aimotive_lrr and written as that
// radar would report it (replay/run/model_recording.hpp: its detections, the cross-section
// estimate beside each SNR), as `rcsim simulate --format recording` writes it.
// Every value `profile derive` reads must come back within the tolerances: view +-1 deg,
// maximum range +-5 m, threshold +-0.5 dB, range exponent +-0.2, cells +-20 %, noise +-30 %; and
// the cycle time and the fluctuation model as the profile says.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "common/angles.hpp"
#include "scene/scene.hpp"
#include "replay/profile/derivation_checks.hpp"
#include "replay/profile/profile_derivation.hpp"
#include "replay/run/model_recording.hpp"
#include "common/json_reader.hpp"
#include "sensor/sensor_config.hpp"
#include "test_support.hpp"

namespace rcsim::replay::profile {
namespace {

TEST(ProfileDeriveRoundTrip, AimotiveLrrComesBackFromItsOwnModel) {
  const Scene scene = load_scene_file(std::string(RCSIM_SOURCE_DIR) + "/docs/examples/round_trip/lined_road.json", testing::library());
  ASSERT_EQ(scene.sensors.at(0).config.name, "aimotive_lrr");
  const Recording recording = model_recording(scene, "lined_road", 7);
  // The base is the paper's srr24 (its law eq. (1), its pattern one-way): nothing of aimotive_lrr
  // comes from it.
  const ProfileDerivation d = derive_profile({&recording}, {.base = "srr24", .name = "round_trip"});
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  const auto expect_near = [&](const std::string& field, double truth, double tolerance) {
    testing::expect_derived_near(values, field, truth, tolerance);
  };
  const SensorConfig lrr = builtin_sensor_config("aimotive_lrr");
  const MeasurementNoise& noise = lrr.noise;
  // Measured (seed 7): 17.0 deg, 180 m, 14.0 dB; the law exact (C 70.50 dB, n 2.530, residual
  // 0.00 dB: the cross-sections are the radar's own estimate), the pattern 2, 0.7, 1.5; cells
  // 1.32 m and 0.168 m/s; noise 0.047 / 0.011 m/s and 0.105 / 0.045 m; cycle 55.7 ms; Swerling 1.
  // Seeds 0 to 3: cells 1.34-1.39 m and 0.176-0.205 m/s, noise 0.038-0.045 / 0.012-0.013 m/s and
  // 0.08-0.10 / 0.045 m, view 16.5-17 deg; the rest as seed 7.
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
