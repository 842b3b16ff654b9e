// The amplitude stage of `rcsim profile derive` (replay/profile/amplitude_law.cpp, declared in
// derivation_stages.hpp): the reporting threshold from the amplitude histogram's start, and the
// radar equation's constant, range exponent and antenna pattern recovered from detections made
// to follow a known law; where the data cannot show the law, the base's, saying why.
#include "replay/profile/derivation_stages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/angles.hpp"
#include "common/decibel.hpp"
#include "sim/antenna.hpp"

namespace rcsim::replay::profile::amplitude_law_test {

// The pattern of eq. (6) in dB for a dipole length and spacing: two-way (exponent 2) or one-way (1).
double pattern_db(double azimuth_rad, double length_wavelengths, double spacing_wavelengths, double exponent = 2.0) {
  AntennaGeometry g;
  g.dipole_length_wavelengths = length_wavelengths, g.element_spacing_wavelengths = spacing_wavelengths;
  g.amplitude_pattern_exponent = exponent;
  return amplitude_to_db(std::pow(MonopulseAntenna(g).sum_magnitude(azimuth_rad), exponent));
}

// 1001 detections in one cycle: ranges 5 to 155 m, azimuths over +-12 deg (41 values, each in
// 0.025-rad bins of at least 10), RCS 0 to 9 dBsm, SNR = 70 - 10 x 2.5 log10 R + pattern + RCS.
DetectionPool known_law(double length_wavelengths, double spacing_wavelengths, double exponent = 2.0) {
  DetectionPool pool;
  pool.cycles.resize(1);
  for (int i = 0; i <= 1000; ++i) {
    PooledDetection d;
    d.range_m = 5.0 + 0.15 * i;
    d.azimuth_rad = deg_to_rad(-12.0 + 0.6 * (i % 41));
    d.rcs_dbsm = static_cast<double>(i % 10);
    d.amplitude_db = 70.0 - 25.0 * std::log10(d.range_m) + pattern_db(d.azimuth_rad, length_wavelengths, spacing_wavelengths, exponent) + d.rcs_dbsm;
    pool.cycles[0].detections.push_back(d);
  }
  pool.detections = 1001;
  return pool;
}

const nlohmann::json kBase = nlohmann::json::parse(R"({"antenna": {"amplitude_pattern_exponent": 2.0}})");

TEST(ProfileAmplitudeLaw, TheThresholdIsTheHistogramsStartToHalfADecibelBelow) {
  // Amplitudes 14.3 + 0.01 i dB on a radar's own scale: the 0.1 % quantile of 1001 is the 2nd,
  // 14.31 dB, floored to 14.0; within 1 dB above (<= 15.0): i <= 70, 71 of 1001 = 7.1 %.
  DetectionPool pool;
  pool.amplitude_unit = AmplitudeUnit::relative_db;
  pool.cycles.resize(1);
  for (int i = 0; i <= 1000; ++i) {
    PooledDetection d;
    d.range_m = 10.0 + i, d.amplitude_db = 14.3 + 0.01 * i;
    pool.cycles[0].detections.push_back(d);
  }
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_amplitude(pool, kBase, 16.0, figures);
  ASSERT_EQ(values.size(), 5u);
  EXPECT_EQ(values[0].field, "amplitude.detection_threshold_db");
  EXPECT_DOUBLE_EQ(values[0].value.get<double>(), 14.0);
  EXPECT_EQ(values[0].support, 1001);
  EXPECT_EQ(values[0].evidence,
            "the amplitude histogram starts abruptly: lowest 14.30 dB, 0.1 % quantile 14.31, 1 % 14.40; 7.1 % within 1 dB above");
  // A level on the radar's own scale cannot show the law: the law's two values are the base's; the
  // pattern would show in the amplitude's azimuth part, but every detection lies at one azimuth.
  for (std::size_t i = 1; i < values.size(); ++i) {
    EXPECT_EQ(values[i].source, ValueSource::base) << values[i].field;
    EXPECT_TRUE(values[i].value.is_null()) << values[i].field;
    EXPECT_NE(values[i].evidence.find(i < 3 ? "on the radar's own scale (relative_db)" : "too few azimuth bins with 200 detections (1)"),
              std::string::npos)
        << values[i].evidence;
  }
  EXPECT_EQ(values[1].field, "amplitude.snr_at_1m_for_1m2_db");
  EXPECT_EQ(values[4].field, "antenna.element_spacing_wavelengths");
  // One figure: amplitude against range with the threshold's line out to the farthest, 1010 m.
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_EQ(figures[0].series[1].points, (std::vector<std::pair<double, double>>{{0.0, 14.0}, {1010.0, 14.0}}));
}

TEST(ProfileAmplitudeLaw, AnSnrWithTooFewCrossSectionsBesideItLeavesTheLawToTheBase) {
  // 89.9 % of the detections with an RCS: fewer than 9 in 10.
  DetectionPool pool = known_law(0.8, 0.8);
  for (int i = 0; i < 102; ++i) pool.cycles[0].detections[static_cast<std::size_t>(i)].rcs_dbsm = RecordedTarget::kNoValue;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_amplitude(pool, kBase, 16.0, figures);
  ASSERT_EQ(values.size(), 5u);
  EXPECT_EQ(values[0].source, ValueSource::derived);
  EXPECT_EQ(values[2].field, "amplitude.range_exponent");
  EXPECT_EQ(values[2].source, ValueSource::base);
  EXPECT_NE(values[2].evidence.find("hold no rcs_dbsm beside the SNR"), std::string::npos) << values[2].evidence;
}

TEST(ProfileAmplitudeLaw, AKnownRangeLawAndPatternComeBack) {
  // Made with C = 70 dB, n = 2.5, dipole 0.8 and spacing 0.9 wavelengths (both on the search's
  // grid; the spacing within the invertible bound for 16 deg: floor(20 / (2 sin 16 deg)) / 20 =
  // 1.80), the pattern two-way and one-way: each comes back whatever the base's exponent (2).
  for (const double exponent : {2.0, 1.0}) {
    const DetectionPool pool = known_law(0.8, 0.9, exponent);
    std::vector<DerivationFigure> figures;
    const std::vector<DerivedValue> values = derive_amplitude(pool, kBase, 16.0, figures);
    ASSERT_EQ(values.size(), 6u);
    const auto value_of = [&](const char* field) {
      for (const DerivedValue& v : values) {
        if (v.field == field) {
          EXPECT_EQ(v.source, ValueSource::derived) << field;
          EXPECT_EQ(v.support, 1001) << field;
          return v.value.get<double>();
        }
      }
      ADD_FAILURE() << field << " missing";
      return 0.0;
    };
    EXPECT_NEAR(value_of("amplitude.snr_at_1m_for_1m2_db"), 70.0, 1e-9);
    EXPECT_NEAR(value_of("amplitude.range_exponent"), 2.5, 1e-9);
    EXPECT_EQ(value_of("antenna.amplitude_pattern_exponent"), exponent);
    EXPECT_NEAR(value_of("antenna.dipole_length_wavelengths"), 0.8, 1e-9);
    EXPECT_NEAR(value_of("antenna.element_spacing_wavelengths"), 0.9, 1e-9);
    // The law's evidence gives the residual: nil, the fit being exact.
    EXPECT_NE(values[1].evidence.find("C 70.00 dB, n 2.500, residual 0.00 dB"), std::string::npos) << values[1].evidence;
    EXPECT_NE(values[5].evidence.find("spacing 0.5-1.80 so that eq. (7) stays invertible"), std::string::npos) << values[5].evidence;
    // Figures: amplitude against range, SNR - RCS against range with the law, the residual against azimuth.
    ASSERT_EQ(figures.size(), 3u);
    EXPECT_EQ(figures[1].title, "SNR - RCS against range");
    EXPECT_EQ(figures[2].title, "The law's residual against azimuth");
  }
}

TEST(ProfileAmplitudeLaw, APatternOnTheRadarsOwnScaleComesBackFromTheAmplitudesAzimuthPart) {
  // A relative_db radar made with dipole 0.6 and spacing 0.4 wavelengths (exponent 2): at 8 ranges,
  // one to a 25-% range bin, and 40 azimuths at the centres of the 0.05-rad bins over +-1 rad, 40
  // detections each with cross-sections 0 to 19.5 dB: the 90 % quantile of each bin is the law at
  // its range, plus the pattern at its azimuth, plus 17.5 dB. The range and azimuth parts separate
  // exactly; the 20 folded bins of |azimuth| follow the pattern to rounding, and the search (spacing
  // up to floor(20 / (2 sin 65 deg)) / 20 = 0.55 for a view of +-65 deg) finds it.
  DetectionPool pool;
  pool.amplitude_unit = AmplitudeUnit::relative_db;
  pool.cycles.resize(1);
  const double ranges_m[] = {5.0, 7.0, 10.0, 14.0, 20.0, 28.0, 40.0, 56.0};
  for (const double range_m : ranges_m) {
    for (int k = -20; k < 20; ++k) {
      for (int i = 0; i < 40; ++i) {
        PooledDetection d;
        d.range_m = range_m, d.azimuth_rad = (k + 0.5) * 0.05;
        d.amplitude_db = 90.0 - 15.0 * std::log10(range_m) + pattern_db(d.azimuth_rad, 0.6, 0.4) + 0.5 * i;
        pool.cycles[0].detections.push_back(d);
      }
    }
  }
  pool.detections = static_cast<long long>(pool.cycles[0].detections.size());
  std::vector<DerivationFigure> figures;
  // An array's base (it resolves azimuth): the spacing searched from 0.1 wavelengths.
  const nlohmann::json array_base = nlohmann::json::parse(R"({"antenna": {"amplitude_pattern_exponent": 2.0}, "resolution": {"azimuth_cell_deg": 1.0}})");
  const std::vector<DerivedValue> values = derive_amplitude(pool, array_base, 65.0, figures);
  ASSERT_EQ(values.size(), 5u);
  EXPECT_EQ(values[2].source, ValueSource::base);  // the law: the base's
  EXPECT_EQ(values[3].field, "antenna.dipole_length_wavelengths");
  EXPECT_EQ(values[3].source, ValueSource::derived) << values[3].evidence;
  EXPECT_NEAR(values[3].value.get<double>(), 0.6, 1e-9) << values[3].evidence;
  EXPECT_NEAR(values[4].value.get<double>(), 0.4, 1e-9) << values[4].evidence;
  EXPECT_EQ(values[3].support, 12800);
  EXPECT_NE(values[3].evidence.find("(320 bins), its azimuth part over 20 bins of |azimuth| follows eq. (6)'s pattern within 0.00 dB RMS"),
            std::string::npos)
      << values[3].evidence;
  EXPECT_EQ(values[3].evidence.find("bound"), std::string::npos) << values[3].evidence;
  EXPECT_NE(values[4].evidence.find("0.1 to 0.55 (0.05 steps)"), std::string::npos) << values[4].evidence;
  ASSERT_EQ(figures.size(), 2u);
  EXPECT_EQ(figures[1].title, "The amplitude's azimuth part");
  // A monopulse base: its spacing sets eq. (7)'s slope too, so the search keeps to 0.5 and up, and
  // says that the best it found, 0.5, is its bound.
  std::vector<DerivationFigure> more;
  const std::vector<DerivedValue> monopulse = derive_amplitude(pool, kBase, 65.0, more);
  EXPECT_DOUBLE_EQ(monopulse[4].value.get<double>(), 0.5);
  EXPECT_NE(monopulse[4].evidence.find("0.5 to 0.55 (0.05 steps)"), std::string::npos) << monopulse[4].evidence;
  EXPECT_NE(monopulse[3].evidence.find("the narrowest spacing, 0.5"), std::string::npos) << monopulse[3].evidence;
}

}  // namespace rcsim::replay::profile::amplitude_law_test
