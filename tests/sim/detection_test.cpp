// The detection decision as a detection-probability curve (III-B with eq. (8)'s pointer noise and
// Swerling fluctuation): the closed forms by hand, and the simulated stages against them.
#include "sim/detection.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/decibel.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/amplitude.hpp"
#include "sim/antenna.hpp"
#include "sim/monopulse.hpp"
#include "sensor_json.hpp"

namespace rcsim {
namespace {

TEST(Detection, SwerlingOneByHand) {
  // S = 9, T = 10, noise power 1: exp(-10 / (1 + 9)) = e^-1
  EXPECT_NEAR(detection_probability(Fluctuation::swerling1, power_to_db(9.0), 10.0, 1.0), std::exp(-1.0), 1e-12);
  // No signal: the false-alarm probability exp(-T) = e^-10
  EXPECT_NEAR(detection_probability(Fluctuation::swerling1, -300.0, 10.0, 1.0), std::exp(-10.0), 1e-15);
  // No noise: P(S x >= T) for exponential x: exp(-T / S) = exp(-10 / 9)
  EXPECT_NEAR(detection_probability(Fluctuation::swerling1, power_to_db(9.0), 10.0, 0.0), std::exp(-10.0 / 9.0), 1e-12);
}

TEST(Detection, SwerlingThreeByHand) {
  // S = 8, T = 10, noise 1: S/2 = 4, spread 5: e^-2 (1 + 4 * 10 / 25) = 2.6 e^-2 = 0.351871
  EXPECT_NEAR(detection_probability(Fluctuation::swerling3, power_to_db(8.0), 10.0, 1.0), 2.6 * std::exp(-2.0), 1e-12);
  EXPECT_NEAR(detection_probability(Fluctuation::swerling3, -300.0, 10.0, 1.0), std::exp(-10.0), 1e-15);
  // No noise: P(S (E1 + E2) / 2 >= T) = exp(-2T/S) (1 + 2T/S); S = 10, T = 10: 3 e^-2
  EXPECT_NEAR(detection_probability(Fluctuation::swerling3, 10.0, 10.0, 0.0), 3.0 * std::exp(-2.0), 1e-12);
}

TEST(Detection, SteadyTargetIsMarcumQ) {
  // S = T = 2, noise 1: a = b = 2, Q1(a, a) = (1 + e^{-a^2} I0(a^2)) / 2 with I0(4) = 11.3019219521
  EXPECT_NEAR(detection_probability(Fluctuation::none, power_to_db(2.0), power_to_db(2.0), 1.0),
              0.5 * (1.0 + std::exp(-4.0) * 11.3019219521), 1e-9);
  // Without a signal the Rice law is the noise's: exp(-T / s2); T = 10, s2 = 4: e^-2.5
  EXPECT_NEAR(detection_probability(Fluctuation::none, -300.0, 10.0, 2.0), std::exp(-2.5), 1e-9);
  // Without noise: the paper's hard threshold.
  EXPECT_EQ(detection_probability(Fluctuation::none, 6.0, 6.0, 0.0), 1.0);
  EXPECT_EQ(detection_probability(Fluctuation::none, 5.999, 6.0, 0.0), 0.0);
}

TEST(Detection, CurvesRiseWithTheMeanLevel) {
  for (const Fluctuation f : {Fluctuation::none, Fluctuation::swerling1, Fluctuation::swerling3}) {
    double previous = 0.0;
    for (double level_db = -10.0; level_db <= 40.0; level_db += 1.0) {
      const double pd = detection_probability(f, level_db, 14.0, 1.0);
      EXPECT_GE(pd, previous) << static_cast<int>(f) << " at " << level_db;
      EXPECT_LE(pd, 1.0);
      previous = pd;
    }
  }
  // At a 10 dB margin a steady target is almost sure, a Swerling 1 target not (its deep fades):
  EXPECT_GT(detection_probability(Fluctuation::none, 24.0, 14.0, 1.0), 0.999);
  EXPECT_NEAR(detection_probability(Fluctuation::swerling1, 24.0, 14.0, 1.0), std::exp(-db_to_power(14.0) / (1.0 + db_to_power(24.0))), 1e-12);
}

TEST(Detection, FloorIsTheThresholdWithoutFluctuationElseWherePdIsNegligible) {
  SensorConfig config;
  config.amplitude.detection_threshold_db = 14.0;
  config.pointer_noise_sigma = 1.0;
  EXPECT_EQ(detection_floor_db(config), 14.0);
  config.detection.fluctuation = Fluctuation::swerling1;
  const double floor_db = detection_floor_db(config);
  EXPECT_LT(floor_db, 14.0);
  // exp(-T / (1 + S)) = 1e-6  =>  S = T / ln(1e6) - 1 = 25.12 / 13.82 - 1 = 0.818 (-0.87 dB)
  EXPECT_NEAR(floor_db, power_to_db(db_to_power(14.0) / std::log(1e6) - 1.0), 1e-6);
}

// Cells of one mean level, fluctuated and measured with pointer noise exactly as the sensor cycle
// does (apply_fluctuation, estimate_monopulse_angles, apply_detection_threshold): the fraction
// detected is the closed form's.
double simulated_detection_fraction(Fluctuation f, double mean_level_db, double threshold_db, double noise_sigma,
                                    int cells_n) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  const auto h = antenna.pattern(0.1);
  const double scale = db_to_amplitude(mean_level_db) / std::abs(h.sum);
  IdealTargets ideal(1);
  ResolutionCells cells(static_cast<std::size_t>(cells_n));
  for (auto& c : cells) {
    c.sum_pointer = scale * h.sum;
    c.delta_pointer = scale * h.delta;
    c.strongest_ideal_index = 0;
  }
  Rng rng(42, 1);
  apply_fluctuation(f, rng, cells);
  Detections detections;
  estimate_monopulse_angles(antenna, noise_sigma, cells, ideal, &rng, detections);
  apply_detection_threshold(threshold_db, detections);
  return static_cast<double>(detections.size()) / cells_n;
}

TEST(Detection, SimulatedStagesFollowTheCurves) {
  constexpr int kCells = 40000;  // binomial sigma <= 0.0025
  for (const Fluctuation f : {Fluctuation::none, Fluctuation::swerling1, Fluctuation::swerling3}) {
    for (const double level_db : {10.0, 14.0, 18.0}) {
      const double expected = detection_probability(f, level_db, 14.0, 1.0);
      EXPECT_NEAR(simulated_detection_fraction(f, level_db, 14.0, 1.0, kCells), expected, 0.0125)
          << static_cast<int>(f) << " at " << level_db << " dB";
    }
  }
}

TEST(Detection, FluctuationKeepsTheMonopulseAngle) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  const auto h = antenna.pattern(0.2);
  IdealTargets ideal(1);
  ResolutionCells cells(50);
  for (auto& c : cells) {
    c.sum_pointer = 100.0 * h.sum;
    c.delta_pointer = 100.0 * h.delta;
    c.strongest_ideal_index = 0;
  }
  Rng rng(3, 0);
  apply_fluctuation(Fluctuation::swerling1, rng, cells);
  Detections detections;
  estimate_monopulse_angles(antenna, 0.0, cells, ideal, nullptr, detections);
  double spread_db = 0.0;
  for (const auto& d : detections) {
    EXPECT_NEAR(d.azimuth_rad, 0.2, 1e-9);
    spread_db = std::max(spread_db, std::abs(d.amplitude_db - 40.0));
  }
  EXPECT_GT(spread_db, 3.0);  // the amplitudes did fluctuate
}

TEST(Detection, FluctuationIsReadAndUnknownNamesRefused) {
  EXPECT_EQ(builtin_sensor_config("srr24").detection.fluctuation, Fluctuation::none);  // the paper's
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(doc.is_null());
  doc["detection"] = {{"fluctuation", "swerling3"}};
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).detection.fluctuation, Fluctuation::swerling3);
  doc["detection"] = {{"fluctuation", "swerling5"}};
  try {
    parse_sensor_config(JsonField(doc, "s.json", ""));
    FAIL() << "swerling5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("detection.fluctuation"), std::string::npos) << e.what();
  }
}


// keep_local_maxima: detections of a range/range-rate map with 1-m x 0.5-m/s cells (cell k centred
// on k cells: range cell round(R / 1 m), range-rate cell round(v / 0.5 m/s)); a detection's
// neighbours are those in its own cell or the eight around it. object_index tells them apart.
Detection at(double range_m, double range_rate_mps, double amplitude_db, int id) {
  Detection d;
  d.range_m = range_m;
  d.range_rate_mps = range_rate_mps;
  d.amplitude_db = amplitude_db;
  d.object_index = id;
  return d;
}

std::vector<int> ids_after_local_maxima(Detections detections) {
  LocalMaximaBuffers buffers;
  keep_local_maxima(ResolutionCell{1.0, 0.5}, detections, buffers);
  std::vector<int> ids;
  for (const auto& d : detections) ids.push_back(d.object_index);
  return ids;
}

TEST(LocalMaxima, ThreeInARowOneCellApartKeepTheStrongest) {
  // 10, 11, 12 m at 0 m/s: 20, 30, 25 dB, in range cells 10, 11, 12: the 30-dB one is stronger than
  // both neighbours: only the middle one stays; cells 10 and 12 are not neighbours.
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(11.0, 0.0, 30.0, 1), at(12.0, 0.0, 25.0, 2)}),
            (std::vector<int>{1}));
  // The same in any input order.
  EXPECT_EQ(ids_after_local_maxima({at(12.0, 0.0, 25.0, 2), at(10.0, 0.0, 20.0, 0), at(11.0, 0.0, 30.0, 1)}),
            (std::vector<int>{1}));
  // A strongest one at the end: 10 m 20 dB < 11 m 25 dB < 12 m 30 dB: 12 hides 11, 11 hides 10.
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(11.0, 0.0, 25.0, 1), at(12.0, 0.0, 30.0, 2)}),
            (std::vector<int>{2}));
}

TEST(LocalMaxima, TwoRangeRateCellsApartAllStay) {
  // Range rates 0, 1, 2 m/s: range-rate cells 0, 2, 4, none neighbours: all peaks.
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(11.0, 1.0, 30.0, 1), at(12.0, 2.0, 25.0, 2)}),
            (std::vector<int>{0, 1, 2}));
  // Neighbours in range rate (0.7 m/s: cell 1) but not in range (11.6 m: cell 12): both stay;
  // neighbours in both (11.4 m: cell 11): the weaker goes.
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(11.6, 0.7, 30.0, 1)}), (std::vector<int>{0, 1}));
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(11.4, 0.7, 30.0, 1)}), (std::vector<int>{1}));
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(10.0, -0.7, 30.0, 1)}), (std::vector<int>{1}));
  EXPECT_EQ(ids_after_local_maxima({at(10.0, 0.0, 20.0, 0), at(10.0, -0.8, 30.0, 1)}), (std::vector<int>{0, 1}));
  // The cells, not the distance, decide, as a peak search over the FFT's bins: 1.2 m apart in cells
  // 10 and 12 both stay; 0.8 m apart in one cell (10.6 and 11.4 m: 11) the weaker goes.
  EXPECT_EQ(ids_after_local_maxima({at(10.4, 0.0, 20.0, 0), at(11.6, 0.0, 30.0, 1)}), (std::vector<int>{0, 1}));
  EXPECT_EQ(ids_after_local_maxima({at(10.6, 0.0, 20.0, 0), at(11.4, 0.0, 30.0, 1)}), (std::vector<int>{1}));
}

TEST(LocalMaxima, EqualAmplitudesKeepTheEarlier) {
  // 25 dB both, 1 m apart: the one first in the list stays, whichever is nearer.
  EXPECT_EQ(ids_after_local_maxima({at(12.0, 0.0, 25.0, 0), at(11.0, 0.0, 25.0, 1)}), (std::vector<int>{0}));
  EXPECT_EQ(ids_after_local_maxima({at(11.0, 0.0, 25.0, 0), at(12.0, 0.0, 25.0, 1)}), (std::vector<int>{0}));
}

TEST(LocalMaxima, SurvivorsKeepTheirOrder) {
  // Two peaks far apart (30 m, 10 m) and one at another range rate (5 m, 3 m/s); 10.5 m 15 dB lies
  // in the 10-m peak's window and goes. The others stay in the order they came, not by range.
  EXPECT_EQ(ids_after_local_maxima({at(30.0, 0.0, 20.0, 0), at(10.0, 0.0, 25.0, 1), at(10.5, 0.2, 15.0, 2),
                                    at(5.0, 3.0, 18.0, 3)}),
            (std::vector<int>{0, 1, 3}));
  EXPECT_TRUE(ids_after_local_maxima({}).empty());
  EXPECT_EQ(ids_after_local_maxima({at(7.0, 1.0, 9.0, 4)}), (std::vector<int>{4}));
}

TEST(LocalMaxima, OptionIsReadAndOffByDefault) {
  EXPECT_FALSE(builtin_sensor_config("srr24").detection.local_maxima_only);
  EXPECT_TRUE(builtin_sensor_config("aimotive_lrr").detection.local_maxima_only);
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(doc.is_null());
  doc["detection"] = {{"fluctuation", "none"}};
  EXPECT_FALSE(parse_sensor_config(JsonField(doc, "s.json", "")).detection.local_maxima_only);
  doc["detection"]["local_maxima_only"] = true;
  EXPECT_TRUE(parse_sensor_config(JsonField(doc, "s.json", "")).detection.local_maxima_only);
  doc["detection"]["local_maxima_only"] = "yes";
  try {
    parse_sensor_config(JsonField(doc, "s.json", ""));
    FAIL() << "a string accepted as a boolean";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("detection.local_maxima_only"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsim
