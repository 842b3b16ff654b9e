#include "traffic/mobil.hpp"

namespace rcsim::traffic {

bool mobil_is_safe(const MobilParameters& p, const LaneChangeAccelerations& acc) {
  // Kesting 2007 eq. (2): a~_n >= -b_safe. We also ask it of the changer itself, so that no
  // change leads straight into an emergency stop behind the new leader.
  return acc.new_follower_after_mps2 >= -p.safe_decel_mps2 && acc.changer_after_mps2 >= -p.safe_decel_mps2;
}

double mobil_advantage_mps2(const MobilParameters& p, const LaneChangeAccelerations& acc, LaneChangeDirection dir) {
  // Kesting 2007 eq. (3) with the keep-right bias of eq. (5)/(6).
  const double own_mps2 = acc.changer_after_mps2 - acc.changer_now_mps2;
  const double others_mps2 = (acc.new_follower_after_mps2 - acc.new_follower_now_mps2) +
                             (acc.old_follower_after_mps2 - acc.old_follower_now_mps2);
  const double bias_mps2 = dir == LaneChangeDirection::Left ? p.keep_right_bias_mps2 : -p.keep_right_bias_mps2;
  return own_mps2 + p.politeness * others_mps2 - (p.threshold_mps2 + bias_mps2);
}

}  // namespace rcsim::traffic
