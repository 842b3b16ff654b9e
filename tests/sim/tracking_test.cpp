// Paper III-E: Kalman tracking with 4-hit confirmation.
#include "sim/tracking.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

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

TEST(Tracking, ContestedDetectionGoesToTheNearerTrack) {
  // Two tracks 0.3 m apart, then a single detection 0.1 m from the second: the pair with the
  // smaller distance is taken first, the other track misses.
  Tracker tracker(TrackerConfig{}, 0.04);
  ReportedTargets reported;
  for (int k = 0; k < 3; ++k) tracker.step({detection(10.0), detection(10.3)}, reported);
  ASSERT_EQ(tracker.tracks().size(), 2u);
  tracker.step({detection(10.2)}, reported);
  ASSERT_EQ(tracker.tracks().size(), 2u);
  EXPECT_EQ(tracker.tracks()[0].misses, 1);
  EXPECT_EQ(tracker.tracks()[1].misses, 0);
  EXPECT_EQ(tracker.tracks()[1].hits, 4);
}

// The tracker the direct way (paper III-E): every (track, detection) pair through the gate, all
// candidates sorted by distance, greedy assignment; then initiation and deletion as in Tracker.
class TrackerByFullScan {
 public:
  TrackerByFullScan(const TrackerConfig& config, double cycle_time_s) : config_(config), model_(config, cycle_time_s) {}
  const std::vector<Track>& tracks() const { return tracks_; }

  void step(const Detections& detections) {
    for (auto& t : tracks_) {
      kalman_predict(model_, t);
      t.updated = false;
      ++t.age_cycles;
    }
    struct Candidate {
      double distance2;
      int track, detection;
    };
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      for (std::size_t j = 0; j < detections.size(); ++j) {
        const double d2 = mahalanobis2(model_, tracks_[i], innovation(tracks_[i], detections[j]));
        if (d2 <= config_.gate_chi2) candidates.push_back({d2, static_cast<int>(i), static_cast<int>(j)});
      }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      if (a.distance2 != b.distance2) return a.distance2 < b.distance2;
      if (a.track != b.track) return a.track < b.track;
      return a.detection < b.detection;
    });
    std::vector<bool> taken(detections.size(), false);
    for (const auto& c : candidates) {
      Track& t = tracks_[static_cast<std::size_t>(c.track)];
      if (t.updated || taken[static_cast<std::size_t>(c.detection)]) continue;
      kalman_update(model_, detections[static_cast<std::size_t>(c.detection)], t);
      t.updated = true;
      ++t.hits;
      t.misses = 0;
      if (t.hits >= config_.confirmation_hits) t.status = TrackStatus::Confirmed;
      taken[static_cast<std::size_t>(c.detection)] = true;
    }
    for (auto& t : tracks_) {
      if (!t.updated) ++t.misses;
    }
    for (std::size_t j = 0; j < detections.size(); ++j) {
      if (taken[j] || tracks_.size() >= static_cast<std::size_t>(config_.max_tracks)) continue;
      const Detection& d = detections[j];
      Track t;
      t.id = next_id_++;
      t.hits = 1;
      t.updated = true;
      t.x << d.range_m, d.range_rate_mps, d.azimuth_rad, d.amplitude_db;
      t.P = model_.R;
      tracks_.push_back(t);
    }
    std::erase_if(tracks_, [&](const Track& t) {
      return t.misses > (t.status == TrackStatus::Confirmed ? config_.max_misses_confirmed : config_.max_misses_tentative);
    });
  }

 private:
  TrackerConfig config_;
  KalmanModel model_;
  std::vector<Track> tracks_;
  int next_id_ = 1;
};

TEST(Tracking, RangeWindowGatingAssociatesLikeTheFullScan) {
  // Crowded scenes: targets 0.2..3 m apart in range with noisy measurements, dropouts and false
  // detections, so that gates overlap and detections are contested. Same tracks, bit for bit.
  TrackerConfig config;
  config.max_tracks = 48;
  Rng rng(17, 0);
  for (int scene = 0; scene < 20; ++scene) {
    Tracker tracker(config, 0.04);
    TrackerByFullScan reference(config, 0.04);
    ReportedTargets reported;
    const int targets = 5 + scene;
    std::vector<double> range_m(static_cast<std::size_t>(targets)), rate_mps(range_m.size());
    double r = 5.0;
    for (std::size_t i = 0; i < range_m.size(); ++i) {
      range_m[i] = (r += rng.uniform(0.2, 3.0));
      rate_mps[i] = rng.uniform(-2.0, 2.0);
    }
    for (int k = 0; k < 60; ++k) {
      Detections detections;
      for (std::size_t i = 0; i < range_m.size(); ++i) {
        range_m[i] += 0.04 * rate_mps[i];
        if (rng.uniform01() < 0.1) continue;  // dropout
        detections.push_back(detection(range_m[i] + 0.1 * rng.normal(), rate_mps[i] + 0.15 * rng.normal(),
                                       0.05 * rng.normal(), 15.0 + 2.0 * rng.normal()));
      }
      const int clutter = static_cast<int>(rng.uniform(0.0, 3.0));
      for (int c = 0; c < clutter; ++c) detections.push_back(detection(rng.uniform(5.0, 60.0), 0.0, 0.3, 8.0));
      // In random order, as the resolution cells come (strongest first).
      for (std::size_t j = detections.size(); j > 1; --j) {
        std::swap(detections[j - 1], detections[static_cast<std::size_t>(rng.uniform(0.0, static_cast<double>(j)))]);
      }
      tracker.step(detections, reported);
      reference.step(detections);
      ASSERT_EQ(tracker.tracks().size(), reference.tracks().size()) << "scene " << scene << " cycle " << k;
      for (std::size_t t = 0; t < tracker.tracks().size(); ++t) {
        const Track& a = tracker.tracks()[t];
        const Track& b = reference.tracks()[t];
        ASSERT_EQ(a.id, b.id);
        EXPECT_EQ(a.hits, b.hits);
        EXPECT_EQ(a.misses, b.misses);
        EXPECT_EQ(a.status, b.status);
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.P, b.P);
      }
    }
  }
}

}  // namespace
}  // namespace rcsim
