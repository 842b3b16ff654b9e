// The reference sensor's tracker (synth/synth_tracker.hpp): confirmation and deletion, one
// alpha-beta update and prediction by hand, gating, greedy association and the track limit.
#include "synth/synth_tracker.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rcsim::synth::synth_tracker_test {


Detection detection(double range_m, double range_rate_mps, double azimuth_rad, double amplitude_db) {
  Detection d;
  d.range_m = range_m;
  d.range_rate_mps = range_rate_mps;
  d.azimuth_rad = azimuth_rad;
  d.amplitude_db = amplitude_db;
  return d;
}

TEST(SynthTracker, ConfirmsAfterFourHitsAndDropsAfterMisses) {
  TrackerConfig config;
  SynthTracker tracker(config, 0.04);
  Detection d;
  d.range_m = 10.0;
  d.range_rate_mps = -2.0;
  d.azimuth_rad = 0.1;
  d.amplitude_db = 15.0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(tracker.step({d}).empty()) << k;
    d.range_m += d.range_rate_mps * 0.04;
  }
  const auto reported = tracker.step({d});
  ASSERT_EQ(reported.size(), 1u);
  EXPECT_NEAR(reported[0].range_m, d.range_m, 0.05);
  EXPECT_NEAR(reported[0].range_rate_mps, -2.0, 0.1);
  // Missed: not reported while coasting, deleted after max_misses_confirmed + 1 misses.
  EXPECT_TRUE(tracker.step({}).empty());
  EXPECT_EQ(tracker.tracks().size(), 1u);
  for (int k = 0; k < config.max_misses_confirmed; ++k) tracker.step({});
  EXPECT_TRUE(tracker.tracks().empty());
  // A false detection that never repeats never reaches the target list.
  SynthTracker other(config, 0.04);
  d.range_m = 20.0;
  EXPECT_TRUE(other.step({d}).empty());
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(other.step({}).empty());
}

TEST(SynthTracker, OneAlphaBetaUpdateAndPredictionByHand) {
  const TrackerConfig config;  // alpha_r 0.5, beta_r 0.3, alpha_rr 0.6, alpha_az 0.35, beta_az 0.1, alpha_amp 0.5
  SynthTracker tracker(config, 0.1);
  tracker.step({detection(10.0, 0.0, 0.0, 10.0)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks()[0].hits, 1);
  EXPECT_EQ(tracker.tracks()[0].status, TrackStatus::tentative);
  // Predicted at 10 m (no rate yet); measured 10.4 m, +1 m/s, 0.1 rad, 20 dB (inside the gates
  // 0.7 m, 1.2 m/s, 0.2 rad). Range: 10 + 0.5 x 0.4 = 10.2; rate from range 0.3 x 0.4 / 0.1 = 1.2,
  // blended 0.4 x 1.2 + 0.6 x 1.0 = 1.08; azimuth 0.35 x 0.1 = 0.035, its rate 0.1 x 0.1 / 0.1 =
  // 0.1; amplitude 10 + 0.5 x 10 = 15.
  tracker.step({detection(10.4, 1.0, 0.1, 20.0)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  const SynthTrack updated = tracker.tracks()[0];
  EXPECT_NEAR(updated.range_m, 10.2, 1e-12);
  EXPECT_NEAR(updated.range_rate_mps, 1.08, 1e-12);
  EXPECT_NEAR(updated.azimuth_rad, 0.035, 1e-12);
  EXPECT_NEAR(updated.azimuth_rate_radps, 0.1, 1e-12);
  EXPECT_NEAR(updated.amplitude_db, 15.0, 1e-12);
  EXPECT_EQ(updated.hits, 2);
  EXPECT_EQ(updated.misses, 0);
  // Missed once: predicted to 10.2 + 1.08 x 0.1 = 10.308 m and 0.035 + 0.1 x 0.1 = 0.045 rad;
  // a tentative track survives one miss, not two.
  tracker.step({});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NEAR(tracker.tracks()[0].range_m, 10.308, 1e-12);
  EXPECT_NEAR(tracker.tracks()[0].azimuth_rad, 0.045, 1e-12);
  EXPECT_EQ(tracker.tracks()[0].misses, 1);
  EXPECT_FALSE(tracker.tracks()[0].updated);
  tracker.step({});
  EXPECT_TRUE(tracker.tracks().empty());
}

TEST(SynthTracker, GatesGreedyAssociationAndTheTrackLimit) {
  TrackerConfig config;
  config.confirmation_hits = 1;  // reported at once: the association shows in the ids
  SynthTracker tracker(config, 0.05);
  const auto first = tracker.step({detection(20.0, 0.0, 0.0, 30.0), detection(10.0, 0.0, 0.0, 20.0)});
  // Reported sorted by range, ids in order of the detections (strongest first).
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].id, 1);
  EXPECT_DOUBLE_EQ(first[0].range_m, 10.0);
  EXPECT_EQ(first[1].id, 0);
  // 20.3 m fits track 0 (0.3 m off); 10.8 m is 0.8 m off track 1, outside the 0.7 m gate: track 1
  // is missed and a new track 2 starts.
  const auto second = tracker.step({detection(20.3, 0.0, 0.0, 30.0), detection(10.8, 0.0, 0.0, 20.0)});
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(second[0].id, 2);
  EXPECT_DOUBLE_EQ(second[0].range_m, 10.8);
  EXPECT_EQ(second[1].id, 0);
  EXPECT_EQ(tracker.tracks().size(), 3u);  // track 1 coasts (confirmed: two misses allowed)
  // Two detections in one track's gate: the nearer one wins, the other starts a track.
  SynthTracker greedy(config, 0.05);
  greedy.step({detection(15.0, 0.0, 0.0, 20.0)});
  greedy.step({detection(15.5, 0.0, 0.0, 25.0), detection(15.1, 0.0, 0.0, 20.0)});
  ASSERT_EQ(greedy.tracks().size(), 2u);
  EXPECT_EQ(greedy.tracks()[0].id, 0);
  EXPECT_NEAR(greedy.tracks()[0].range_m, 15.05, 1e-12);  // 15 + 0.5 x 0.1
  EXPECT_EQ(greedy.tracks()[1].id, 1);
  EXPECT_DOUBLE_EQ(greedy.tracks()[1].range_m, 15.5);
  // At most max_tracks: the third detection starts nothing.
  config.max_tracks = 2;
  SynthTracker limited(config, 0.05);
  limited.step({detection(5.0, 0.0, 0.0, 30.0), detection(10.0, 0.0, 0.0, 25.0), detection(15.0, 0.0, 0.0, 20.0)});
  ASSERT_EQ(limited.tracks().size(), 2u);
  EXPECT_DOUBLE_EQ(limited.tracks()[1].range_m, 10.0);
}

}  // namespace rcsim::synth::synth_tracker_test
