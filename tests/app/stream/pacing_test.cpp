// Absolute deadlines against an injected clock: no drift, slow cycles do not shift later ones,
// late cycles are reported, pause/resume/step/seek re-anchor.
#include "stream/pacing.hpp"

#include <gtest/gtest.h>

namespace rcsim::stream {
namespace {

using namespace std::chrono_literals;

TimePoint at_ms(double ms) { return TimePoint{} + std::chrono::nanoseconds(static_cast<std::int64_t>(ms * 1e6)); }

TEST(StreamPacing, DeadlinesComeFromTheAnchorNotFromTheLastSend) {
  Pacer pacer({1.0, 2ms, false});
  // First cycle: sent at once and anchors the schedule at wall 1000 ms = scene 0 s.
  EXPECT_EQ(pacer.decide(at_ms(1000), 0.0).action, Pacer::Action::send);
  pacer.on_sent(at_ms(1000), 0.0);
  // Every send 0.7 ms late: with sleep-after-send this would add up to 70 ms over 100 cycles.
  for (int k = 1; k <= 100; ++k) {
    const double t_s = 0.04 * k;
    const auto d = pacer.decide(at_ms(1000 + 40.0 * k - 5), t_s);
    ASSERT_EQ(d.action, Pacer::Action::wait);
    EXPECT_EQ(d.at, at_ms(1000 + 40.0 * k)) << k;
    const auto record = pacer.on_sent(d.at + 700us, t_s);
    EXPECT_TRUE(record.paced);
    EXPECT_EQ(record.lateness, 700us);
    EXPECT_FALSE(record.late);
  }
}

TEST(StreamPacing, SpeedScalesTheSchedule) {
  Pacer pacer({10.0, 2ms, false});
  pacer.decide(at_ms(0), 5.0);
  pacer.on_sent(at_ms(0), 5.0);
  EXPECT_EQ(pacer.deadline(6.0), at_ms(100));  // 1 scene second in 100 ms
  EXPECT_EQ(pacer.deadline(5.04), at_ms(4));
}

TEST(StreamPacing, ASlowCycleIsLateButLaterCyclesKeepTheirDeadlines) {
  Pacer pacer({1.0, 2ms, false});
  LatenessStats stats;
  pacer.decide(at_ms(0), 0.0);
  stats.add(pacer.on_sent(at_ms(0), 0.0));
  // Cycle 1 (due at 40 ms) was ready only at 130 ms: sent then, late by 90 ms.
  ASSERT_EQ(pacer.decide(at_ms(130), 0.04).action, Pacer::Action::send);
  const auto late = pacer.on_sent(at_ms(130), 0.04);
  stats.add(late);
  EXPECT_TRUE(late.late);
  EXPECT_EQ(late.lateness, 90ms);
  // Cycle 2 was due at 80 ms: also late, sent at once; cycle 3 and 4 are not moved.
  ASSERT_EQ(pacer.decide(at_ms(130.1), 0.08).action, Pacer::Action::send);
  stats.add(pacer.on_sent(at_ms(130.1), 0.08));
  ASSERT_EQ(pacer.decide(at_ms(130.2), 0.12).action, Pacer::Action::send);
  stats.add(pacer.on_sent(at_ms(130.2), 0.12));  // due at 120: 10.2 ms late
  const auto d4 = pacer.decide(at_ms(130.3), 0.16);
  ASSERT_EQ(d4.action, Pacer::Action::wait);
  EXPECT_EQ(d4.at, at_ms(160));
  stats.add(pacer.on_sent(at_ms(160.5), 0.16));
  EXPECT_EQ(stats.paced(), 5u);
  EXPECT_EQ(stats.late(), 3u);
  EXPECT_NEAR(stats.quantile_ms(0.5), 10.2, 1e-3);
  EXPECT_NEAR(stats.max_ms(), 90.0, 1e-3);
  EXPECT_NEAR(stats.quantile_ms(0.0), 0.0, 1e-3);
}

TEST(StreamPacing, PauseHoldsAndResumeReanchorsAtTheNextCycle) {
  Pacer pacer({1.0, 2ms, false});
  pacer.decide(at_ms(0), 0.0);
  pacer.on_sent(at_ms(0), 0.0);
  pacer.pause();
  EXPECT_EQ(pacer.decide(at_ms(500), 0.04).action, Pacer::Action::hold);
  pacer.resume();
  // Resumed 5 s later: the next cycle leaves at once, the one after 40 ms later.
  EXPECT_EQ(pacer.decide(at_ms(5000), 0.04).action, Pacer::Action::send);
  EXPECT_FALSE(pacer.on_sent(at_ms(5000), 0.04).late);
  const auto d = pacer.decide(at_ms(5001), 0.08);
  EXPECT_EQ(d.action, Pacer::Action::wait);
  EXPECT_EQ(d.at, at_ms(5040));
}

TEST(StreamPacing, SteppedModeSendsExactlyTheStepsAsked) {
  Pacer pacer({1.0, 2ms, true});
  EXPECT_EQ(pacer.decide(at_ms(0), 0.0).action, Pacer::Action::hold);
  pacer.step(2);
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(pacer.decide(at_ms(1), 0.04 * k).action, Pacer::Action::send);
    EXPECT_FALSE(pacer.on_sent(at_ms(1), 0.04 * k).paced);  // no deadline, no lateness
  }
  EXPECT_EQ(pacer.decide(at_ms(2), 0.08).action, Pacer::Action::hold);
  EXPECT_EQ(pacer.step_credits(), 0u);
}

TEST(StreamPacing, MaxSpeedNeverWaits) {
  Pacer pacer({0.0, 2ms, false});
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(pacer.decide(at_ms(0), 100.0 * k).action, Pacer::Action::send);
    EXPECT_FALSE(pacer.on_sent(at_ms(0), 100.0 * k).paced);
  }
}

TEST(StreamPacing, SeekReanchors) {
  Pacer pacer({1.0, 2ms, false});
  pacer.decide(at_ms(0), 0.0);
  pacer.on_sent(at_ms(0), 0.0);
  pacer.reanchor();
  EXPECT_EQ(pacer.decide(at_ms(10), 3.0).action, Pacer::Action::send);  // not 3 s late
  EXPECT_FALSE(pacer.on_sent(at_ms(10), 3.0).late);
  EXPECT_EQ(pacer.decide(at_ms(11), 3.04).at, at_ms(50));
}

}  // namespace
}  // namespace rcsim::stream
