#pragma once
// MOBIL, "Minimizing Overall Braking Induced by Lane changes": A. Kesting, M. Treiber,
// D. Helbing, "General lane-changing model MOBIL for car-following models", Transportation
// Research Record 1999, 86-94 (2007). Both criteria are in terms of IDM accelerations:
//   safety:     a~_n >= -b_safe                                        (Kesting 2007 eq. 2)
//   incentive:  a~_c - a_c + p [(a~_n - a_n) + (a~_o - a_o)] > a_th + bias   (eq. 3, and the
//               asymmetric keep-right variant, eq. 5/6: bias = +a_bias to the left, -a_bias to the right)
// c: the changing vehicle, n: its new follower, o: its old follower; ~ after the change.

namespace rcsim::traffic {

// Typical values from Kesting 2007 and Treiber's MOBIL page (p in 0..0.5, b_safe 4 m/s^2,
// threshold 0.2 m/s^2 below every vehicle type's a, bias 0.2 m/s^2).
struct MobilParameters {
  double politeness = 0.3;               // p
  double threshold_mps2 = 0.2;           // a_th, damps ping-pong changes
  double safe_decel_mps2 = 4.0;          // b_safe, the most a change may force the new follower to brake
  double keep_right_bias_mps2 = 0.2;     // a_bias, European rule: prefer the right lane
};

// Accelerations of the three affected vehicles before (a) and after (a~) a candidate change.
// A vehicle that does not exist contributes 0 to both.
struct LaneChangeAccelerations {
  double changer_now_mps2 = 0.0;         // a_c
  double changer_after_mps2 = 0.0;       // a~_c
  double new_follower_now_mps2 = 0.0;    // a_n
  double new_follower_after_mps2 = 0.0;  // a~_n
  double old_follower_now_mps2 = 0.0;    // a_o
  double old_follower_after_mps2 = 0.0;  // a~_o
};

enum class LaneChangeDirection { Left, Right };

bool mobil_is_safe(const MobilParameters& p, const LaneChangeAccelerations& acc);
// The incentive's left-hand side minus its threshold (positive: the change pays off).
double mobil_advantage_mps2(const MobilParameters& p, const LaneChangeAccelerations& acc, LaneChangeDirection dir);

}  // namespace rcsim::traffic
