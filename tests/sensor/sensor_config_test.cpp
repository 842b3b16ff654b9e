// The imaging-radar fields of an rcsim-sensor file (schemas/sensor-config.md): read, and refused
// where they contradict each other, naming the field.
#include "sensor/sensor_config.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "sensor_json.hpp"

namespace rcsim {
namespace {

TEST(SensorConfigImaging, TheAstyxProfileIsAnArrayThatResolvesAzimuth) {
  const SensorConfig c = builtin_sensor_config("astyx_hires");
  EXPECT_TRUE(c.resolution.resolves_azimuth());
  EXPECT_NEAR(c.resolution.azimuth_cell_rad, std::numbers::pi / 180.0, 1e-15);
  EXPECT_TRUE(c.resolution.aliases_range_rate());
  EXPECT_DOUBLE_EQ(c.resolution.unambiguous_min_mps, -5.2374);
  EXPECT_DOUBLE_EQ(c.resolution.unambiguous_max_mps, 5.1562);
  EXPECT_TRUE(c.detection.strongest_beam_per_cell);
  EXPECT_EQ(c.amplitude.unit, AmplitudeUnit::relative_db);
  EXPECT_EQ(c.extended_objects.max_pieces_per_face, 128);
  EXPECT_EQ(c.extended_objects.surface, ExtendedObjects::Surface::box);
  EXPECT_DOUBLE_EQ(c.extended_objects.box_side_inset_m, 0.3);
  EXPECT_EQ(c.resolution.window, SpectralWindow::hann);
  EXPECT_GT(c.background.targets_per_cycle, 1000.0);  // more than the Knuth Poisson draw held
  // The paper's sensor is none of that.
  const SensorConfig srr24 = builtin_sensor_config("srr24");
  EXPECT_FALSE(srr24.resolution.resolves_azimuth());
  EXPECT_FALSE(srr24.resolution.aliases_range_rate());
  EXPECT_EQ(srr24.amplitude.unit, AmplitudeUnit::snr_db);
  EXPECT_EQ(srr24.extended_objects.max_pieces_per_face, 16);
  EXPECT_EQ(srr24.extended_objects.surface, ExtendedObjects::Surface::model_faces);
  EXPECT_EQ(srr24.resolution.window, SpectralWindow::none);
}

TEST(SensorConfigImaging, ContradictionsAreRefusedNamingTheField) {
  const nlohmann::json astyx = testing::builtin_sensor_json("astyx_hires");
  ASSERT_FALSE(astyx.is_null());
  EXPECT_EQ(testing::sensor_config_error(astyx), "");

  auto doc = astyx;
  doc["resolution"].erase("azimuth_cell_deg");  // beams reported without beams
  EXPECT_NE(testing::sensor_config_error(doc).find("detection.reported_beams"), std::string::npos);
  doc = astyx;
  doc["monopulse"] = {{"pointer_noise_sigma", 0.1}};  // an array has no monopulse
  EXPECT_NE(testing::sensor_config_error(doc).find("monopulse"), std::string::npos);
  doc = astyx;
  doc.erase("array");
  EXPECT_NE(testing::sensor_config_error(doc).find("array"), std::string::npos);
  doc = astyx;
  doc["resolution"]["unambiguous_range_rate_mps"] = {1.0, 5.0};  // 0 must lie inside
  EXPECT_NE(testing::sensor_config_error(doc).find("resolution.unambiguous_range_rate_mps"), std::string::npos);
  doc["resolution"]["unambiguous_range_rate_mps"] = {-5.0};
  EXPECT_NE(testing::sensor_config_error(doc).find("two numbers"), std::string::npos);
  doc = astyx;
  doc["resolution"]["spectral_window"] = "hamming";  // not one we model
  EXPECT_NE(testing::sensor_config_error(doc).find("resolution.spectral_window"), std::string::npos);
  doc = astyx;
  doc["amplitude"]["range_exponent"] = -0.5;
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.range_exponent"), std::string::npos);
  doc = astyx;
  doc["amplitude"]["unit"] = "mag";
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.unit"), std::string::npos);
  doc = astyx;
  doc["extended_objects"]["max_pieces_per_face"] = 1000;
  EXPECT_NE(testing::sensor_config_error(doc).find("extended_objects.max_pieces_per_face"), std::string::npos);
  doc = astyx;
  doc["extended_objects"]["diffuse_surface"] = "boxes";
  EXPECT_NE(testing::sensor_config_error(doc).find("extended_objects.diffuse_surface"), std::string::npos);
  doc = astyx;
  doc["extended_objects"]["box_side_inset_m"] = 1.5;
  EXPECT_NE(testing::sensor_config_error(doc).find("extended_objects.box_side_inset_m"), std::string::npos);
  doc["extended_objects"]["box_side_inset_m"] = 0.2;
  doc["extended_objects"].erase("diffuse_surface");  // an inset of the model's own faces means nothing
  EXPECT_NE(testing::sensor_config_error(doc).find("extended_objects.box_side_inset_m"), std::string::npos);

  auto srr24 = testing::builtin_sensor_json("srr24");
  srr24["array"] = {{"azimuth_sigma_deg", 0.1}};  // an array section without beams
  EXPECT_NE(testing::sensor_config_error(srr24).find("array"), std::string::npos);
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

// A relative amplitude scale names where its noise lies (amplitude.noise_floor_db): a threshold at
// or below it would detect every cell on the pointer noise of eq. (8), and is refused by name.
TEST(SensorConfigNoiseFloor, ARelativeScaleNamesItsNoiseFloor) {
  nlohmann::json rcs = testing::builtin_sensor_json("astyx_hires");
  rcs["amplitude"]["snr_at_1m_for_1m2_db"] = -27.0;  // an RCS-like scale: the threshold -55
  rcs["amplitude"]["detection_threshold_db"] = -55.0;
  const std::string refused = testing::sensor_config_error(rcs);
  EXPECT_NE(refused.find("amplitude.detection_threshold_db"), std::string::npos) << refused;
  EXPECT_NE(refused.find("noise floor"), std::string::npos) << refused;
  rcs["amplitude"]["noise_floor_db"] = -100.0;
  EXPECT_EQ(testing::sensor_config_error(rcs), "");
  const SensorConfig c = parse_sensor_config(JsonField(rcs, "s.json", ""));
  EXPECT_EQ(c.amplitude.noise_floor_db, -100.0);
  EXPECT_NEAR(pointer_noise_amplitude(c), c.pointer_noise_sigma * 1e-5, 1e-20);  // -100 dB: 10^(-5) in amplitude
  // The SNR scale's floor is 0 dB by definition: naming one there is refused, and the default is 1 x sigma.
  nlohmann::json srr24 = testing::builtin_sensor_json("srr24");
  EXPECT_EQ(pointer_noise_amplitude(builtin_sensor_config("srr24")), builtin_sensor_config("srr24").pointer_noise_sigma);
  srr24["amplitude"]["noise_floor_db"] = -10.0;
  EXPECT_NE(testing::sensor_config_error(srr24).find("amplitude.noise_floor_db"), std::string::npos);
}

}  // namespace
}  // namespace rcsim
