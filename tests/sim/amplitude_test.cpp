// Paper eqs. (1)-(3).
#include "sim/amplitude.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "sensor/sensor_config.hpp"
#include "sensor_json.hpp"

namespace rcsim {
namespace {

TEST(Amplitude, ReferenceLawByHand) {
  const AmplitudeLaw law;
  // eq. (1): 26.5 - 0.75 * 10 = 19 dB
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 10.0)), 19.0, 1e-12);
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 0.0)), 26.5, 1e-12);
  // Threshold crossing: 26.5 - 0.75 R = 6  =>  R = 27.333 m
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 82.0 / 3.0)), 6.0, 1e-12);
}

TEST(Amplitude, EchoOfReferenceReflectorAtBoresight) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  IdealTargets ideal(1);
  ideal[0].range_m = 10.0;
  ideal[0].set_azimuth(0.0);
  ideal[0].ercs = 1.0;
  Echoes echoes;
  compute_echoes(AmplitudeLaw{}, antenna, ideal, echoes);
  ASSERT_EQ(echoes.size(), 1u);
  EXPECT_NEAR(amplitude_to_db(echoes[0].amplitude), 19.0, 1e-12);
}

TEST(Amplitude, EchoScalesWithErcsAndAntennaPattern) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  IdealTargets ideal(1);
  ideal[0].range_m = 10.0;
  ideal[0].set_azimuth(deg_to_rad(30.0));
  ideal[0].ercs = 2.0;
  Echoes echoes;
  compute_echoes(AmplitudeLaw{}, antenna, ideal, echoes);
  // eq. (3): 19 dB + 20 log10(2) + 20 log10(0.551329) = 19 + 6.0206 - 5.1718 = 19.8488 dB
  EXPECT_NEAR(amplitude_to_db(echoes[0].amplitude), 19.0 + 20 * std::log10(2.0) + 20 * std::log10(0.5513288954), 1e-8);
  // eq. (8) weights the pointers by A_ref^R(R) ERCS only: |delta| / |sum| is the pattern ratio
  const auto h = antenna.pattern(deg_to_rad(30.0));
  EXPECT_NEAR(std::abs(echoes[0].delta_pointer) / std::abs(echoes[0].sum_pointer), std::abs(h.delta) / std::abs(h.sum),
              1e-12);
}

TEST(Amplitude, PatternExponentTwoSquaresTheAntennaFactorAndKeepsTheAngle) {
  AntennaGeometry geometry;
  geometry.amplitude_pattern_exponent = 2.0;
  const MonopulseAntenna antenna{geometry};
  const MonopulseAntenna paper{AntennaGeometry{}};
  IdealTargets ideal(2);
  ideal[0].range_m = ideal[1].range_m = 10.0;
  ideal[0].set_azimuth(deg_to_rad(30.0));
  ideal[1].set_azimuth(deg_to_rad(90.0));  // |H_sum| = 0: stays 0, no NaN
  ideal[0].ercs = ideal[1].ercs = 1.0;
  Echoes echoes;
  compute_echoes(AmplitudeLaw{}, antenna, ideal, echoes);
  // A^phi = |H_sum(30 deg)|^2: 19 dB + 2 * 20 log10(0.551329) = 19 - 10.3436 = 8.6564 dB
  EXPECT_NEAR(amplitude_to_db(echoes[0].amplitude), 19.0 + 40 * std::log10(0.5513288954), 1e-8);
  EXPECT_TRUE(std::isfinite(echoes[1].amplitude));
  EXPECT_NEAR(echoes[1].amplitude, 0.0, 1e-15);  // cos(pi/2) in doubles is 6e-17, squared
  // The monopulse ratio, eq. (7), and so the estimated angle are those of the paper's pattern.
  const auto h = paper.pattern(deg_to_rad(30.0));
  const AntennaPointers pointers{echoes[0].sum_pointer, echoes[0].delta_pointer};
  EXPECT_NEAR(MonopulseAntenna::additive_sensing_ratio(pointers), MonopulseAntenna::additive_sensing_ratio(h), 1e-12);
  EXPECT_NEAR(antenna.estimate_azimuth(pointers), deg_to_rad(30.0), 1e-12);
}

TEST(Amplitude, PatternExponentIsOptionalAndRefusedOutsideOneToFour) {
  nlohmann::json srr24 = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(srr24.is_null());
  EXPECT_EQ(parse_sensor_config(JsonField(srr24, "srr24.json", "")).antenna.amplitude_pattern_exponent, 1.0);
  srr24["antenna"]["amplitude_pattern_exponent"] = 1.7;
  EXPECT_EQ(parse_sensor_config(JsonField(srr24, "srr24.json", "")).antenna.amplitude_pattern_exponent, 1.7);
  srr24["antenna"]["amplitude_pattern_exponent"] = 0.5;
  try {
    parse_sensor_config(JsonField(srr24, "srr24.json", ""));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("antenna.amplitude_pattern_exponent"), std::string::npos) << e.what();
  }
}

// The level of one reflector's echo on boresight (eqs. (2)-(3) with the paper's antenna).
double boresight_echo_db(const AmplitudeLaw& law, double range_m, double ercs) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  IdealTargets ideal(1);
  ideal[0].range_m = range_m;
  ideal[0].set_azimuth(0.0);
  ideal[0].ercs = ercs;
  Echoes echoes;
  compute_echoes(law, antenna, ideal, echoes);
  return amplitude_to_db(echoes[0].amplitude);
}

AmplitudeLaw radar_equation_law() {
  AmplitudeLaw law;
  law.kind = AmplitudeLawKind::radar_equation;
  law.snr_at_1m_for_1m2_db = 90.0;
  law.reference_rcs_dbsm = 10.0;
  law.detection_threshold_db = 14.0;
  return law;
}

TEST(Amplitude, RadarEquationByHand) {
  const AmplitudeLaw law = radar_equation_law();
  // SNR = K + sigma_ref - 40 log10 R: 90 + 10 - 80 = 20 dB at 100 m, 100 dB at 1 m, 88 dB at 2 m
  EXPECT_NEAR(reference_range_level_db(law, 100.0), 20.0, 1e-12);
  EXPECT_NEAR(reference_range_level_db(law, 1.0), 100.0, 1e-12);
  EXPECT_NEAR(reference_range_level_db(law, 2.0), 100.0 - 40.0 * std::log10(2.0), 1e-12);
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 100.0)), 20.0, 1e-12);
  // An ERCS of 2 stands for sigma = 10 + 20 log10 2 = 16.02 dBsm: its echo 6.02 dB stronger.
  EXPECT_NEAR(boresight_echo_db(law, 100.0, 2.0), 20.0 + 20.0 * std::log10(2.0), 1e-9);
  // The range at which the reference reflector falls to the 14 dB threshold: 100 - 40 log10 R = 14,
  // R = 10^(86/40) = 141.25 m; an ERCS of 10 (+20 dB) reaches 10^(106/40) = 446.7 m.
  EXPECT_TRUE(has_detection_range_bound(law));
  EXPECT_NEAR(detection_range_bound_m(law, 1.0), std::pow(10.0, 86.0 / 40.0), 1e-9);
  EXPECT_NEAR(detection_range_bound_m(law, 10.0), std::pow(10.0, 106.0 / 40.0), 1e-9);
  EXPECT_NEAR(reference_range_level_db(law, detection_range_bound_m(law, 1.0)), 14.0, 1e-9);
  // The paper's law without a slope never falls: no bound.
  AmplitudeLaw flat;
  flat.reference_slope_db_per_m = 0.0;
  EXPECT_FALSE(has_detection_range_bound(flat));
  EXPECT_TRUE(has_detection_range_bound(AmplitudeLaw{}));
}

TEST(Amplitude, ARangeCompensatedAmplitudeDoesNotFallWithRange) {
  // The Astyx HiRes's Mag: range exponent 0, the level is the same at every range.
  AmplitudeLaw law;
  law.kind = AmplitudeLawKind::radar_equation;
  law.snr_at_1m_for_1m2_db = 55.0;
  law.reference_rcs_dbsm = -3.0;
  law.range_exponent = 0.0;
  law.detection_threshold_db = 45.0;
  EXPECT_DOUBLE_EQ(reference_range_level_db(law, 1.0), 52.0);
  EXPECT_DOUBLE_EQ(reference_range_level_db(law, 90.0), 52.0);
  EXPECT_FALSE(has_detection_range_bound(law));
  EXPECT_TRUE(std::isinf(detection_range_bound_m(law, 1.0)));
  // Exponent 1.25: 12.5 dB per decade.
  law.range_exponent = 1.25;
  EXPECT_NEAR(reference_range_level_db(law, 100.0), 52.0 - 25.0, 1e-12);
  EXPECT_NEAR(detection_range_bound_m(law, 1.0), std::pow(10.0, 7.0 / 12.5), 1e-9);  // 52 - 12.5 log10 R = 45
}

TEST(Amplitude, RadarEquationAtZeroRangeStaysFinite) {
  const AmplitudeLaw law = radar_equation_law();
  EXPECT_TRUE(std::isfinite(reference_range_level_db(law, 0.0)));
  EXPECT_NEAR(reference_range_level_db(law, 0.0), 100.0 + 120.0, 1e-9);  // taken at 1 mm
}

TEST(Amplitude, LawIsReadFromTheSensorConfigurationAndCheckedField) {
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(doc.is_null());
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).amplitude.kind, AmplitudeLawKind::paper_eq1);
  doc["amplitude"] = {{"law", "radar_equation"}, {"snr_at_1m_for_1m2_db", 90.0}, {"reference_rcs_dbsm", 10.0},
                      {"detection_threshold_db", 14.0}};
  const SensorConfig radar = parse_sensor_config(JsonField(doc, "s.json", ""));
  EXPECT_EQ(radar.amplitude.kind, AmplitudeLawKind::radar_equation);
  EXPECT_EQ(radar.amplitude.snr_at_1m_for_1m2_db, 90.0);
  EXPECT_EQ(radar.amplitude.reference_rcs_dbsm, 10.0);
  // The other law's fields are refused, not ignored; so are unknown laws and absurd levels.
  doc["amplitude"]["reference_slope_db_per_m"] = 0.75;
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.reference_slope_db_per_m"), std::string::npos) << testing::sensor_config_error(doc);
  doc["amplitude"].erase("reference_slope_db_per_m");
  doc["amplitude"]["law"] = "radar_eq";
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.law"), std::string::npos) << testing::sensor_config_error(doc);
  doc["amplitude"]["law"] = "radar_equation";
  doc["amplitude"]["reference_rcs_dbsm"] = 1e308;
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.reference_rcs_dbsm"), std::string::npos) << testing::sensor_config_error(doc);
}


TEST(Amplitude, RangeExponentByHand) {
  AmplitudeLaw law = radar_equation_law();
  law.range_exponent = 2.5;
  // SNR = K + sigma_ref - 10 n log10 R = 90 + 10 - 25 * 2 = 50 dB at 100 m; 100 - 25 = 75 dB at 10 m
  EXPECT_NEAR(reference_range_level_db(law, 100.0), 50.0, 1e-12);
  EXPECT_NEAR(reference_range_level_db(law, 10.0), 75.0, 1e-12);
  EXPECT_NEAR(reference_range_level_db(law, 1.0), 100.0, 1e-12);  // n does not move the 1-m level
  // Threshold 14 dB: 100 - 25 log10 R = 14  =>  R = 10^(86/25) = 10^3.44 = 2754.23 m;
  // ERCS 10 (+20 dB): 10^(106/25) = 10^4.24 = 17378.0 m; 3 dB headroom: 10^(89/25) = 3630.78 m.
  EXPECT_NEAR(detection_range_bound_m(law, 1.0), std::pow(10.0, 3.44), 1e-9 * 2754.23);
  EXPECT_NEAR(detection_range_bound_m(law, 1.0), 2754.2287, 1e-3);
  EXPECT_NEAR(detection_range_bound_m(law, 10.0), std::pow(10.0, 4.24), 1e-9 * 17378.0);
  EXPECT_NEAR(detection_range_bound_m(law, 1.0, 3.0), std::pow(10.0, 89.0 / 25.0), 1e-9 * 3630.78);
  EXPECT_NEAR(reference_range_level_db(law, detection_range_bound_m(law, 1.0)), 14.0, 1e-9);
  // The echo at 100 m of an ERCS of 2 on boresight: 50 + 20 log10 2 = 56.02 dB.
  EXPECT_NEAR(boresight_echo_db(law, 100.0, 2.0), 50.0 + 20.0 * std::log10(2.0), 1e-9);
}

TEST(Amplitude, RangeExponentIsOptionalAndRefusedOutsideZeroToSix) {
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(doc.is_null());
  doc["amplitude"] = {{"law", "radar_equation"}, {"snr_at_1m_for_1m2_db", 90.0}, {"reference_rcs_dbsm", 10.0},
                      {"detection_threshold_db", 14.0}};
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).amplitude.range_exponent, 4.0);  // absent: 1/R^4
  for (const double n : {0.0, 0.5, 1.0, 2.53, 6.0}) {  // 0: a range-compensated amplitude
    doc["amplitude"]["range_exponent"] = n;
    EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).amplitude.range_exponent, n);
  }
  for (const double n : {-0.5, 7.0, -4.0}) {
    doc["amplitude"]["range_exponent"] = n;
    EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.range_exponent"), std::string::npos) << n << ": " << testing::sensor_config_error(doc);
  }
  // Only the radar equation has a range exponent: the paper's law refuses it.
  doc["amplitude"] = {{"reference_level_db", 26.5}, {"reference_slope_db_per_m", 0.75}, {"detection_threshold_db", 6.0},
                      {"range_exponent", 4.0}};
  EXPECT_NE(testing::sensor_config_error(doc).find("amplitude.range_exponent"), std::string::npos) << testing::sensor_config_error(doc);
  // The built-in aimotive_lrr gives its fitted n (docs/sensor-profiles.md), not the default 4.
  const nlohmann::json lrr = testing::builtin_sensor_json("aimotive_lrr");
  ASSERT_TRUE(lrr["amplitude"].contains("range_exponent"));
  EXPECT_EQ(builtin_sensor_config("aimotive_lrr").amplitude.range_exponent, lrr["amplitude"]["range_exponent"].get<double>());
  EXPECT_NE(builtin_sensor_config("aimotive_lrr").amplitude.range_exponent, 4.0);
}

}  // namespace
}  // namespace rcsim
