// Latency episodes by hand (replay/run/latency_episodes.hpp): the scene's detectability opens an
// episode; each side confirms the object when targets of it came in 3 of the last 4 cycles; one
// stray target confirms nothing, one missed cycle resets nothing; an episode a side never
// confirms is kept and counted; kEpisodeGapCycles undetectable cycles end an episode.
#include "replay/run/latency_episodes.hpp"

#include <gtest/gtest.h>

namespace rcsim::replay {
namespace {

ComparedTarget of_object(int object) {
  ComparedTarget t;
  t.object = object;
  t.target_class = object >= 0 ? metrics::TargetClass::object : metrics::TargetClass::other;
  return t;
}

// A cycle whose lists hold one target of the given objects (-1: a target of no object).
CycleComparison cycle_with(std::vector<int> recorded, std::vector<int> simulated) {
  CycleComparison c;
  for (const int o : recorded) c.recorded.push_back(of_object(o));
  for (const int o : simulated) c.simulated.push_back(of_object(o));
  return c;
}

// Runs cycles 0.04 s apart from t = 1.00 with object 0 detectable throughout.
ReplaySummary run(const std::vector<CycleComparison>& cycles, std::size_t objects = 1) {
  LatencyEpisodes episodes(1, objects);
  std::vector<char> detectable(objects, 1);
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    const double t_s = 1.00 + 0.04 * static_cast<double>(k);
    episodes.update_detectable(0, detectable, t_s);
    episodes.note_targets(0, cycles[k], t_s);
  }
  ReplaySummary summary;
  episodes.finish(summary);
  return summary;
}

TEST(LatencyEpisodes, ConfirmedAtTheThirdOfFourCyclesEachSideAlike) {
  // Simulated every cycle from the start: confirmed at the third (1.08); recorded from the second
  // cycle on: confirmed at the fourth (1.12).
  const ReplaySummary s = run({cycle_with({}, {0}), cycle_with({0}, {0}), cycle_with({0}, {0}), cycle_with({0}, {0}),
                               cycle_with({0}, {0})});
  ASSERT_EQ(s.latencies.size(), 1u);
  EXPECT_DOUBLE_EQ(s.latencies[0].detectable_from_s, 1.00);
  EXPECT_DOUBLE_EQ(s.latencies[0].first_simulated_s, 1.08);
  EXPECT_DOUBLE_EQ(s.latencies[0].first_recorded_s, 1.12);
  EXPECT_EQ(s.latency_pairs, 1);
  EXPECT_NEAR(s.latency_recorded_s, 0.12, 1e-12);
  EXPECT_NEAR(s.latency_simulated_s, 0.08, 1e-12);
  EXPECT_NEAR(s.latency_difference_mean_s, -0.04, 1e-12);
}

TEST(LatencyEpisodes, OneStrayTargetConfirmsNothingAndOneMissedCycleResetsNothing) {
  // Recorded: one stray target of the object at the first cycle, then nothing for four cycles:
  // not confirmed there. Then hits, a miss, a hit: 3 of 4 at the ninth cycle (1.32).
  const ReplaySummary s = run({cycle_with({0}, {}), cycle_with({}, {}), cycle_with({}, {}), cycle_with({}, {}),
                               cycle_with({}, {}), cycle_with({0}, {}), cycle_with({0}, {}), cycle_with({}, {}),
                               cycle_with({0}, {})});
  ASSERT_EQ(s.latencies.size(), 1u);
  EXPECT_NEAR(s.latencies[0].first_recorded_s, 1.32, 1e-12);
  EXPECT_EQ(s.latencies[0].first_simulated_s, -1.0);
}

TEST(LatencyEpisodes, AnEpisodeNeverConfirmedIsKeptCensoredAndCounted) {
  // Two objects detectable; the recording confirms object 0 only, the simulation neither;
  // targets of no object (merge artefacts, background) never count.
  std::vector<CycleComparison> cycles(4, cycle_with({0, -1}, {-1, -1}));
  const ReplaySummary s = run(cycles, 2);
  ASSERT_EQ(s.latencies.size(), 2u);
  EXPECT_EQ(s.latency_episodes, 2);
  EXPECT_EQ(s.latency_unconfirmed_recorded, 1);
  EXPECT_EQ(s.latency_unconfirmed_simulated, 2);
  EXPECT_EQ(s.latency_pairs, 0);
  EXPECT_NEAR(s.latency_recorded_s, 0.08, 1e-12);
  EXPECT_EQ(s.latency_simulated_s, -1.0);
}

TEST(LatencyEpisodes, AGapOfTenUndetectableCyclesStartsANewEpisode) {
  LatencyEpisodes episodes(1, 1);
  const std::vector<char> seen{1}, unseen{0};
  double t_s = 0.0;
  episodes.update_detectable(0, seen, t_s);
  for (int k = 0; k < LatencyEpisodes::kEpisodeGapCycles - 1; ++k) episodes.update_detectable(0, unseen, t_s += 0.1);
  episodes.update_detectable(0, seen, t_s += 0.1);  // 9 cycles: still the same episode
  for (int k = 0; k < LatencyEpisodes::kEpisodeGapCycles; ++k) episodes.update_detectable(0, unseen, t_s += 0.1);
  episodes.update_detectable(0, seen, t_s += 0.1);  // after 10: a second one
  ReplaySummary summary;
  episodes.finish(summary);
  ASSERT_EQ(summary.latencies.size(), 2u);
  EXPECT_EQ(summary.latencies[0].episode, 0);
  EXPECT_EQ(summary.latencies[1].episode, 1);
  EXPECT_DOUBLE_EQ(summary.latencies[0].detectable_from_s, 0.0);
  EXPECT_NEAR(summary.latencies[1].detectable_from_s, 2.1, 1e-9);  // 0 + 9 + 1 + 10 + 1 cycles of 0.1 s
  EXPECT_EQ(summary.latency_pairs, 0);  // nobody reported it
  EXPECT_EQ(summary.latency_unconfirmed_recorded, 2);
  EXPECT_EQ(summary.latency_recorded_s, -1.0);
}

}  // namespace
}  // namespace rcsim::replay
