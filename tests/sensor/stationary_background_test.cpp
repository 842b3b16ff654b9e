// The `background` section of a sensor configuration (sensor/stationary_background.hpp): read
// strictly (weights normalised, azimuths in degrees), every bad field named, written back unchanged.
#include "sensor/stationary_background.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "test_support.hpp"

namespace rcsim::stationary_background_test {


StationaryBackground parsed(const nlohmann::ordered_json& doc) {
  const nlohmann::json plain = nlohmann::json::parse(doc.dump());
  return parse_stationary_background(JsonField(plain, "s.json", "background"));
}

std::string parse_error(const nlohmann::ordered_json& doc) {
  try {
    parsed(doc);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StationaryBackgroundSection, SectionRoundTripsAndBadFieldsAreNamed) {
  const StationaryBackground b = testing::hand_background();
  const nlohmann::ordered_json doc = stationary_background_to_json(b);
  const nlohmann::json plain = nlohmann::json::parse(doc.dump());
  const StationaryBackground back = parse_stationary_background(JsonField(plain, "s.json", "background"));
  EXPECT_EQ(back.targets_per_cycle, 20.0);
  EXPECT_EQ(back.range_edges_m, b.range_edges_m);
  ASSERT_EQ(back.azimuth_edges_rad.size(), 3u);
  EXPECT_NEAR(back.azimuth_edges_rad[2], 0.1, 1e-12);  // written in degrees, read back in radians
  EXPECT_EQ(back.weights, b.weights);
  EXPECT_EQ(back.amplitude_deciles_db, b.amplitude_deciles_db);

  auto bad = doc;
  bad["weights"][0][1] = -1.0;
  EXPECT_NE(parse_error(bad).find("background.weights"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["range_edges_m"] = {20.0, 10.0};
  EXPECT_NE(parse_error(bad).find("background.range_edges_m"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["amplitude_deciles_db"][0][3] = 0.0;  // falls below the decile before it
  EXPECT_NE(parse_error(bad).find("background.amplitude_deciles_db"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["weights"].push_back({0.5, 0.5});  // a row more than range bins
  EXPECT_NE(parse_error(bad).find("background.weights"), std::string::npos) << parse_error(bad);
  bad = doc;
  bad["targets_per_cycle"] = 1e9;
  EXPECT_NE(parse_error(bad).find("background.targets_per_cycle"), std::string::npos) << parse_error(bad);
}

TEST(StationaryBackgroundSection, WeightsAreNormalisedAndAzimuthsReadInDegreesByHand) {
  // Two range bins x two azimuth bins, weights 1 2 / 3 4 (sum 10): 0.1 0.2 0.3 0.4, row-major.
  nlohmann::ordered_json doc = {{"fitted_on", "drive_a"},
                                {"targets_per_cycle", 2.5},
                                {"range_edges_m", {0.0, 5.0, 50.0}},
                                {"azimuth_edges_deg", {-60.0, 0.0, 30.0}},
                                {"weights", {{1.0, 2.0}, {3.0, 4.0}}},
                                {"amplitude_deciles_db", nlohmann::ordered_json::array()}};
  for (int r = 0; r < 2; ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (int k = 0; k < kAmplitudeQuantiles; ++k) row.push_back(-5.0 + r + k);
    doc["amplitude_deciles_db"].push_back(row);
  }
  const StationaryBackground b = parsed(doc);
  EXPECT_EQ(b.fitted_on, "drive_a");
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.range_bins(), 2u);
  EXPECT_EQ(b.azimuth_bins(), 2u);
  ASSERT_EQ(b.weights.size(), 4u);
  EXPECT_NEAR(b.weights[0], 0.1, 1e-15);
  EXPECT_NEAR(b.weights[3], 0.4, 1e-15);
  EXPECT_NEAR(b.azimuth_edges_rad[0], -kPi / 3.0, 1e-15);  // -60 deg
  EXPECT_DOUBLE_EQ(b.amplitude_deciles_db[1][10], 6.0);    // -5 + 1 + 10
  // Written back: fitted_on first, azimuths in degrees, weights as normalised.
  const nlohmann::ordered_json out = stationary_background_to_json(b);
  EXPECT_EQ(out.begin().key(), "fitted_on");
  EXPECT_NEAR(out["azimuth_edges_deg"][2].get<double>(), 30.0, 1e-12);
  EXPECT_NEAR(out["weights"][1][0].get<double>(), 0.3, 1e-15);
  // No fitted_on: none written. Zero targets per cycle: an empty background.
  doc.erase("fitted_on");
  doc["targets_per_cycle"] = 0.0;
  const StationaryBackground none = parsed(doc);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(stationary_background_to_json(none).contains("fitted_on"));
}

TEST(StationaryBackgroundSection, EdgesAndRowsAreCheckedWithExactMessages) {
  const nlohmann::ordered_json good = stationary_background_to_json(testing::hand_background());
  auto bad = good;
  bad["azimuth_edges_deg"] = {-90.0, 0.0, 10.0};  // a sensor sees less than +-90 deg
  EXPECT_EQ(parse_error(bad), "s.json: background.azimuth_edges_deg: must lie within +-90 deg");
  bad = good;
  bad["range_edges_m"] = {-1.0, 20.0};
  EXPECT_EQ(parse_error(bad), "s.json: background.range_edges_m: must not be negative");
  bad = good;
  bad["range_edges_m"] = {10.0};
  EXPECT_EQ(parse_error(bad), "s.json: background.range_edges_m: must hold 2 to 1001 edges");
  bad = good;
  bad["range_edges_m"] = {10.0, "20"};
  EXPECT_EQ(parse_error(bad), "s.json: background.range_edges_m: must hold finite numbers");
  bad = good;
  bad["weights"] = {{0.0, 0.0}};
  EXPECT_EQ(parse_error(bad), "s.json: background.weights: must not all be 0");
  bad = good;
  bad["weights"] = {{1.0, 2.0, 3.0}};
  EXPECT_EQ(parse_error(bad), "s.json: background.weights: row 0 must hold 2 numbers");
  bad = good;
  bad["amplitude_deciles_db"][0][10] = 1001.0;
  EXPECT_EQ(parse_error(bad), "s.json: background.amplitude_deciles_db: row 0: amplitudes must be within +-1000 dB");
  bad = good;
  bad["targets_per_cycle"] = -1.0;
  EXPECT_EQ(parse_error(bad), "s.json: background.targets_per_cycle: must be in [0, 20000]");
  bad = good;
  bad["density"] = 1.0;
  EXPECT_EQ(parse_error(bad),
            "s.json: background.density: unknown field (expected one of: fitted_on, targets_per_cycle, range_edges_m, "
            "azimuth_edges_deg, weights, amplitude_deciles_db)");
}

}  // namespace rcsim::stationary_background_test
