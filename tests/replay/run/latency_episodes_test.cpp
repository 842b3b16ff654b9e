// Latency episodes by hand: detection opens an episode, each side's first target of the object
// closes its latency, kEpisodeGapCycles cycles without detection end the episode.
#include "replay/run/latency_episodes.hpp"

#include <gtest/gtest.h>

namespace rcsim::replay {
namespace {

CycleComparison cycle_with(int recorded_object, int simulated_object) {
  CycleComparison c;
  if (recorded_object >= -1) c.recorded.push_back(ComparedTarget{.object = recorded_object});
  if (simulated_object >= -1) c.simulated.push_back(ComparedTarget{.object = simulated_object});
  return c;
}

TEST(LatencyEpisodes, EachSideIsTimedFromTheFirstDetection) {
  LatencyEpisodes episodes(1, 2);
  const std::vector<char> object0{1, 0};
  episodes.update_detected(0, object0, 1.00);
  episodes.note_first_targets(0, cycle_with(-1, -2), 1.00);  // a recorded target of no object
  episodes.update_detected(0, object0, 1.04);
  episodes.note_first_targets(0, cycle_with(-2, 0), 1.04);  // simulated first
  episodes.update_detected(0, object0, 1.08);
  episodes.note_first_targets(0, cycle_with(0, 0), 1.08);
  ReplaySummary summary;
  episodes.finish(summary);
  ASSERT_EQ(summary.latencies.size(), 1u);  // object 1 was never detectable: no episode
  EXPECT_DOUBLE_EQ(summary.latencies[0].detectable_from_s, 1.00);
  EXPECT_DOUBLE_EQ(summary.latencies[0].first_simulated_s, 1.04);
  EXPECT_DOUBLE_EQ(summary.latencies[0].first_recorded_s, 1.08);
  EXPECT_EQ(summary.latency_pairs, 1);
  EXPECT_NEAR(summary.latency_recorded_s, 0.08, 1e-12);
  EXPECT_NEAR(summary.latency_simulated_s, 0.04, 1e-12);
}

TEST(LatencyEpisodes, AGapOfTenUndetectedCyclesStartsANewEpisode) {
  LatencyEpisodes episodes(1, 1);
  const std::vector<char> seen{1}, unseen{0};
  double t_s = 0.0;
  episodes.update_detected(0, seen, t_s);
  for (int k = 0; k < LatencyEpisodes::kEpisodeGapCycles - 1; ++k) episodes.update_detected(0, unseen, t_s += 0.1);
  episodes.update_detected(0, seen, t_s += 0.1);  // 9 cycles: still the same episode
  for (int k = 0; k < LatencyEpisodes::kEpisodeGapCycles; ++k) episodes.update_detected(0, unseen, t_s += 0.1);
  episodes.update_detected(0, seen, t_s += 0.1);  // after 10: a second one
  ReplaySummary summary;
  episodes.finish(summary);
  ASSERT_EQ(summary.latencies.size(), 2u);
  EXPECT_EQ(summary.latencies[0].episode, 0);
  EXPECT_EQ(summary.latencies[1].episode, 1);
  EXPECT_DOUBLE_EQ(summary.latencies[0].detectable_from_s, 0.0);
  EXPECT_NEAR(summary.latencies[1].detectable_from_s, 2.1, 1e-9);  // 0 + 9 + 1 + 10 + 1 cycles of 0.1 s
  EXPECT_EQ(summary.latency_pairs, 0);  // nobody reported it
  EXPECT_EQ(summary.latency_recorded_s, -1.0);
}

}  // namespace
}  // namespace rcsim::replay
