// Paper III-E: Kalman tracking with 4-hit confirmation.
#include "sim/tracking.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "common/rng.hpp"

namespace rcsim {
namespace {

Detection detection(double range_m, double rate_mps = 0.0, double azimuth_rad = 0.1, double amplitude_db = 15.0) {
  Detection d;
  d.range_m = range_m;
  d.range_rate_mps = rate_mps;
  d.azimuth_rad = azimuth_rad;
  d.amplitude_db = amplitude_db;
  d.object_index = 0;
  return d;
}

TEST(Tracking, FirstReportOnTheFourthMeasurement) {
  Tracker tracker(TrackerConfig{}, 0.04);
  ReportedTargets reported;
  for (int k = 0; k < 6; ++k) {
    tracker.step({detection(10.0 - 0.04 * k, -1.0)}, reported);
    ASSERT_EQ(tracker.tracks().size(), 1u);
    EXPECT_EQ(tracker.tracks()[0].hits, k + 1);
    if (k < 3) {
      EXPECT_TRUE(reported.empty()) << "cycle " << k;
      EXPECT_EQ(tracker.tracks()[0].status, TrackStatus::Tentative);
    } else {
      ASSERT_EQ(reported.size(), 1u) << "cycle " << k;
      EXPECT_EQ(tracker.tracks()[0].status, TrackStatus::Confirmed);
      EXPECT_NEAR(reported[0].range_m, 10.0 - 0.04 * k, 1e-9);  // noise-free constant rate: exact
      EXPECT_NEAR(reported[0].range_rate_mps, -1.0, 1e-9);
    }
  }
}

TEST(Tracking, TentativeTrackWithGapsNeedsFourHitsNotFourCycles) {
  Tracker tracker(TrackerConfig{}, 0.04);
  ReportedTargets reported;
  const bool present[] = {true, false, true, true, false, true};
  for (int k = 0; k < 6; ++k) {
    Detections d;
    if (present[k]) d.push_back(detection(10.0));
    tracker.step(d, reported);
    EXPECT_EQ(reported.size(), k == 5 ? 1u : 0u) << "cycle " << k;
  }
}

TEST(Tracking, DeletionAfterMisses) {
  TrackerConfig config;  // tentative: 1 miss allowed; confirmed: 2
  Tracker tracker(config, 0.04);
  ReportedTargets reported;
  tracker.step({detection(10.0)}, reported);
  tracker.step({}, reported);
  EXPECT_EQ(tracker.tracks().size(), 1u);
  tracker.step({}, reported);
  EXPECT_TRUE(tracker.tracks().empty());
  for (int k = 0; k < 4; ++k) tracker.step({detection(10.0)}, reported);
  tracker.step({}, reported);
  tracker.step({}, reported);
  EXPECT_EQ(tracker.tracks().size(), 1u);
  EXPECT_TRUE(reported.empty());  // coasting tracks are not reported
  tracker.step({}, reported);
  EXPECT_TRUE(tracker.tracks().empty());
}

TEST(Tracking, GateSeparatesDistantTargets) {
  Tracker tracker(TrackerConfig{}, 0.04);
  ReportedTargets reported;
  tracker.step({detection(10.0)}, reported);
  tracker.step({detection(15.0)}, reported);  // far outside the gate: a new track
  EXPECT_EQ(tracker.tracks().size(), 2u);
}

TEST(Tracking, AzimuthInnovationIsWrapped) {
  Tracker tracker(TrackerConfig{}, 0.04);
  ReportedTargets reported;
  for (int k = 0; k < 4; ++k) tracker.step({detection(10.0, 0.0, k % 2 ? 3.14 : -3.14)}, reported);
  ASSERT_EQ(tracker.tracks().size(), 1u);  // +-3.14 are 0.0032 rad apart, not 6.28
  EXPECT_GT(std::abs(tracker.tracks()[0].x(2)), 3.1);
}

TEST(Tracking, CovarianceStaysSymmetricPositiveDefinite) {
  TrackerConfig config;
  Tracker tracker(config, 0.04);
  Rng rng(3);
  ReportedTargets reported;
  for (int k = 0; k < 20000; ++k) {
    tracker.step({detection(10.0 + 0.1 * rng.normal(), 0.15 * rng.normal(), 0.2 + 0.05 * rng.normal(),
                            15.0 + 2 * rng.normal())},
                 reported);
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  const auto& P = tracker.tracks()[0].P;
  EXPECT_EQ((P - P.transpose()).norm(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(P);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  EXPECT_LT(P(0, 0), 0.1 * 0.1);  // filtered below the measurement variance
}

TEST(Tracking, BlockwiseUpdateEqualsTheFull4x4JosephForm) {
  const KalmanModel model(TrackerConfig{}, 0.04);
  Track track;
  track.x << 12.0, -1.5, 0.3, 14.0;
  track.P.setZero();
  track.P.topLeftCorner<2, 2>() << 0.04, 0.01, 0.01, 0.09;
  track.P(2, 2) = 0.003;
  track.P(3, 3) = 5.0;
  const Detection d = detection(12.2, -1.1, 0.25, 16.0);
  // The textbook filter with H = I on the full matrices.
  Track full = track;
  full.x = model.F * full.x;
  full.P = model.F * full.P * model.F.transpose() + model.Q;
  const Eigen::Matrix4d K = full.P * (full.P + model.R).inverse();
  const Eigen::Vector4d nu(d.range_m - full.x(0), d.range_rate_mps - full.x(1), d.azimuth_rad - full.x(2),
                           d.amplitude_db - full.x(3));
  const double d2_full = nu.dot((full.P + model.R).inverse() * nu);
  full.x += K * nu;
  const Eigen::Matrix4d I_K = Eigen::Matrix4d::Identity() - K;
  full.P = I_K * full.P * I_K.transpose() + K * model.R * K.transpose();

  kalman_predict(model, track);
  EXPECT_NEAR(mahalanobis2(model, track, innovation(track, d)), d2_full, 1e-9);
  kalman_update(model, d, track);
  EXPECT_LT((track.x - full.x).norm(), 1e-12);
  EXPECT_LT((track.P - full.P).norm(), 1e-12);
}

}  // namespace
}  // namespace rcsim
