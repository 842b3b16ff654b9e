// A user's ego log for a dataset importer (replay/import/ego_log.hpp): interpolated by hand,
// the yaw along the shorter arc through +-pi, nothing extrapolated; the Doppler cross-check.
#include "replay/import/ego_log.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.hpp"

namespace rcsim::replay {
namespace {

const std::vector<EgoSample> kLog = {{0.0, 0.0, 0.0, 3.1, 10.0, 0.1}, {1.0, 10.0, 2.0, -3.1, 20.0, 0.3}};

TEST(EgoLog, LinearBetweenSamplesAndTheYawAcrossPi) {
  const auto ego = ego_at_times(kLog, {0.0, 0.25, 0.5, 1.0}, "log.csv");
  ASSERT_EQ(ego.size(), 4u);
  EXPECT_DOUBLE_EQ(ego[0].speed_mps, 10.0);  // a sample's own time gives the sample
  EXPECT_DOUBLE_EQ(ego[1].t_s, 0.25);
  EXPECT_NEAR(ego[1].x_m, 2.5, 1e-12);
  EXPECT_NEAR(ego[1].y_m, 0.5, 1e-12);
  EXPECT_NEAR(ego[1].speed_mps, 12.5, 1e-12);
  EXPECT_NEAR(ego[1].yaw_rate_radps, 0.15, 1e-12);
  // 3.1 to -3.1 is 0.0832 rad through pi, not 6.2 rad the other way: halfway is pi itself.
  EXPECT_NEAR(std::cos(ego[2].yaw_rad), -1.0, 1e-9);
  EXPECT_NEAR(std::abs(ego[2].yaw_rad), M_PI, 1e-9);
  EXPECT_NEAR(ego[1].yaw_rad, 3.1 + 0.25 * (2.0 * M_PI - 6.2), 1e-12);
  EXPECT_DOUBLE_EQ(ego[3].yaw_rad, -3.1);
}

TEST(EgoLog, ATimeOutsideTheLogIsRefusedNamingTheFile) {
  for (const double t : {-0.01, 1.01}) {
    try {
      ego_at_times(kLog, {t}, "drive/ego_log.csv");
      ADD_FAILURE() << "extrapolated to " << t;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("drive/ego_log.csv"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("covers 0 to 1 s"), std::string::npos) << e.what();
    }
  }
}

TEST(EgoLog, DopplerCheckIsEstimateMinusLog) {
  std::vector<EgoSample> estimate = kLog;
  estimate[0].speed_mps += 1.0;
  estimate[1].speed_mps -= 1.0;
  estimate[1].yaw_rate_radps += 0.02;
  const auto r = ego_difference_report(kLog, estimate);
  EXPECT_EQ(r.at("cycles").get<int>(), 2);
  EXPECT_NEAR(r.at("speed_difference_mean_mps").get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(r.at("speed_difference_rms_mps").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(r.at("yaw_rate_difference_mean_radps").get<double>(), 0.01, 1e-12);
}

}  // namespace
}  // namespace rcsim::replay
