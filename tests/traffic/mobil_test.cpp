// MOBIL's two criteria of traffic/mobil.hpp by hand: the safety limit on the new follower's and
// the changer's braking, and the incentive with politeness, threshold and keep-right bias.
#include "traffic/mobil.hpp"

#include <gtest/gtest.h>

namespace rcsim::mobil_test {

using traffic::LaneChangeAccelerations;
using traffic::LaneChangeDirection;
using traffic::MobilParameters;
using traffic::mobil_advantage_mps2;
using traffic::mobil_is_safe;

TEST(TrafficMobil, SafeUpToTheSafeDecelerationInclusive) {
  const MobilParameters p;  // b_safe = 4 m/s^2
  LaneChangeAccelerations acc;
  EXPECT_TRUE(mobil_is_safe(p, acc));
  acc.new_follower_after_mps2 = -4.0;  // exactly -b_safe: Kesting eq. (2) holds with equality
  EXPECT_TRUE(mobil_is_safe(p, acc));
  acc.new_follower_after_mps2 = -4.01;
  EXPECT_FALSE(mobil_is_safe(p, acc));
  // The changer itself must not have to brake harder than b_safe either.
  acc.new_follower_after_mps2 = 0.0;
  acc.changer_after_mps2 = -4.5;
  EXPECT_FALSE(mobil_is_safe(p, acc));
  // The old follower's braking does not enter the safety criterion.
  acc.changer_after_mps2 = 0.0;
  acc.old_follower_after_mps2 = -8.0;
  EXPECT_TRUE(mobil_is_safe(p, acc));
}

TEST(TrafficMobil, IncentiveWithPolitenessThresholdAndBias) {
  const MobilParameters p;  // p = 0.3, a_th = 0.2, a_bias = 0.2
  LaneChangeAccelerations acc;
  acc.changer_now_mps2 = 0.1;
  acc.changer_after_mps2 = 0.9;         // own gain 0.8
  acc.new_follower_now_mps2 = 0.0;
  acc.new_follower_after_mps2 = -1.0;   // -1.0
  acc.old_follower_now_mps2 = -0.5;
  acc.old_follower_after_mps2 = 0.3;    // +0.8; others: -0.2, times p: -0.06
  // Left: 0.8 - 0.06 - (0.2 + 0.2) = 0.34; right: 0.8 - 0.06 - (0.2 - 0.2) = 0.74.
  EXPECT_NEAR(mobil_advantage_mps2(p, acc, LaneChangeDirection::Left), 0.34, 1e-12);
  EXPECT_NEAR(mobil_advantage_mps2(p, acc, LaneChangeDirection::Right), 0.74, 1e-12);
  // Egoistic driver (p = 0): the others do not count: 0.8 - 0.4 = 0.4 to the left.
  MobilParameters egoistic = p;
  egoistic.politeness = 0.0;
  EXPECT_NEAR(mobil_advantage_mps2(egoistic, acc, LaneChangeDirection::Left), 0.4, 1e-12);
  // Altruistic (p = 1): 0.8 - 0.2 - 0.4 = 0.2.
  MobilParameters altruistic = p;
  altruistic.politeness = 1.0;
  EXPECT_NEAR(mobil_advantage_mps2(altruistic, acc, LaneChangeDirection::Left), 0.2, 1e-12);
}

TEST(TrafficMobil, NothingToGainStaysUnlessKeepingRight) {
  const MobilParameters p;
  const LaneChangeAccelerations nothing;  // every acceleration the same before and after
  // Left: -(a_th + a_bias) = -0.4; right: the bias cancels the threshold, exactly 0, which is not
  // "positive": no change for nothing either way.
  EXPECT_NEAR(mobil_advantage_mps2(p, nothing, LaneChangeDirection::Left), -0.4, 1e-12);
  EXPECT_NEAR(mobil_advantage_mps2(p, nothing, LaneChangeDirection::Right), 0.0, 1e-12);
  // A small own gain of 0.1 pays off to the right (keep right) but not to the left.
  LaneChangeAccelerations small;
  small.changer_after_mps2 = 0.1;
  EXPECT_GT(mobil_advantage_mps2(p, small, LaneChangeDirection::Right), 0.0);
  EXPECT_LT(mobil_advantage_mps2(p, small, LaneChangeDirection::Left), 0.0);
}

}  // namespace rcsim::mobil_test
