#pragma once
// The Intelligent Driver Model (IDM): M. Treiber, A. Hennecke, D. Helbing, "Congested traffic
// states in empirical observations and microscopic simulations", Phys. Rev. E 62, 1805 (2000).
// Car following: acceleration from own speed, gap to the leader and approach rate; and the
// model's equilibrium (fundamental diagram) derived from it.
#include <vector>

namespace rcsim::traffic {

struct IdmParameters {
  double desired_speed_mps = 33.33;       // v0
  double time_headway_s = 1.6;            // T, safe time headway
  double min_gap_m = 2.0;                 // s0, jam distance
  double max_accel_mps2 = 0.73;           // a
  double comfortable_decel_mps2 = 1.67;   // b
  double accel_exponent = 4.0;            // delta
  double emergency_decel_mps2 = 9.0;      // b_max: physical limit the applied deceleration is clipped to
};

// Treiber 2000 eq. (2): s*(v, dv) = s0 + max(0, v T + v dv / (2 sqrt(a b))).
double idm_desired_gap_m(const IdmParameters& p, double speed_mps, double approach_rate_mps);

// Treiber 2000 eq. (1): dv/dt = a [1 - (v/v0)^delta - (s*(v, dv)/s)^2]; without the clip.
// approach_rate_mps = v - v_leader (positive when closing in). gap_m > 0.
double idm_raw_acceleration_mps2(const IdmParameters& p, double speed_mps, double gap_m, double approach_rate_mps);

// The free-road term a [1 - (v/v0)^delta] (no leader).
double idm_free_acceleration_mps2(const IdmParameters& p, double speed_mps);

// eq. (1) clipped below at -b_max (the emergency limit); non-positive gaps give -b_max.
double idm_acceleration_mps2(const IdmParameters& p, double speed_mps, double gap_m, double approach_rate_mps);

// Equilibrium (dv/dt = 0, dv = 0): s_e(v) = (s0 + v T) / sqrt(1 - (v/v0)^delta), v < v0.
double idm_equilibrium_gap_m(const IdmParameters& p, double speed_mps);
// Inverse: the equilibrium speed for a gap (bisection on the monotone s_e(v)); 0 for gap <= s0.
double idm_equilibrium_speed_mps(const IdmParameters& p, double gap_m);

// One point of the fundamental diagram of identical vehicles of length vehicle_length_m:
// density rho = 1 / (s_e + l), flow Q = rho v.
struct FundamentalDiagramPoint {
  double density_vpkm = 0.0;  // vehicles per km and lane
  double flow_vph = 0.0;      // vehicles per hour and lane
  double speed_mps = 0.0;
};
FundamentalDiagramPoint idm_equilibrium_at_density(const IdmParameters& p, double vehicle_length_m, double density_vpkm);
// The capacity (maximum equilibrium flow) and the critical density where it is reached,
// by golden-section search on Q(v).
FundamentalDiagramPoint idm_capacity(const IdmParameters& p, double vehicle_length_m);
// Jam density 1 / (s0 + l) in vehicles per km and lane.
double idm_jam_density_vpkm(const IdmParameters& p, double vehicle_length_m);

}  // namespace rcsim::traffic
