#include "traffic/idm.hpp"

#include <algorithm>
#include <cmath>

namespace rcsim::traffic {

double idm_desired_gap_m(const IdmParameters& p, double speed_mps, double approach_rate_mps) {
  const double dynamic_m =
      speed_mps * p.time_headway_s +
      speed_mps * approach_rate_mps / (2.0 * std::sqrt(p.max_accel_mps2 * p.comfortable_decel_mps2));
  return p.min_gap_m + std::max(0.0, dynamic_m);
}

double idm_free_acceleration_mps2(const IdmParameters& p, double speed_mps) {
  return p.max_accel_mps2 * (1.0 - std::pow(std::max(speed_mps, 0.0) / p.desired_speed_mps, p.accel_exponent));
}

double idm_raw_acceleration_mps2(const IdmParameters& p, double speed_mps, double gap_m, double approach_rate_mps) {
  const double ratio = idm_desired_gap_m(p, speed_mps, approach_rate_mps) / gap_m;
  return idm_free_acceleration_mps2(p, speed_mps) - p.max_accel_mps2 * ratio * ratio;
}

double idm_acceleration_mps2(const IdmParameters& p, double speed_mps, double gap_m, double approach_rate_mps) {
  if (gap_m <= 1e-3) return -p.emergency_decel_mps2;
  return std::max(-p.emergency_decel_mps2, idm_raw_acceleration_mps2(p, speed_mps, gap_m, approach_rate_mps));
}

double idm_equilibrium_gap_m(const IdmParameters& p, double speed_mps) {
  return (p.min_gap_m + speed_mps * p.time_headway_s) /
         std::sqrt(1.0 - std::pow(speed_mps / p.desired_speed_mps, p.accel_exponent));
}

double idm_equilibrium_speed_mps(const IdmParameters& p, double gap_m) {
  if (gap_m <= p.min_gap_m) return 0.0;
  double lo = 0.0;
  double hi = p.desired_speed_mps;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (idm_equilibrium_gap_m(p, mid) < gap_m ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

FundamentalDiagramPoint idm_equilibrium_at_density(const IdmParameters& p, double vehicle_length_m,
                                                   double density_vpkm) {
  const double spacing_m = 1000.0 / density_vpkm;
  const double speed_mps = idm_equilibrium_speed_mps(p, spacing_m - vehicle_length_m);
  return {density_vpkm, density_vpkm * speed_mps * 3.6, speed_mps};
}

FundamentalDiagramPoint idm_capacity(const IdmParameters& p, double vehicle_length_m) {
  // Q(v) = v / (s_e(v) + l) is unimodal on (0, v0).
  const auto flow_vph = [&](double v) { return 3600.0 * v / (idm_equilibrium_gap_m(p, v) + vehicle_length_m); };
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = 0.0;
  double hi = p.desired_speed_mps * (1.0 - 1e-9);
  for (int i = 0; i < 200; ++i) {
    const double m1 = hi - golden * (hi - lo);
    const double m2 = lo + golden * (hi - lo);
    (flow_vph(m1) < flow_vph(m2) ? lo : hi) = (flow_vph(m1) < flow_vph(m2) ? m1 : m2);
  }
  const double v = 0.5 * (lo + hi);
  const double density_vpkm = 1000.0 / (idm_equilibrium_gap_m(p, v) + vehicle_length_m);
  return {density_vpkm, flow_vph(v), v};
}

double idm_jam_density_vpkm(const IdmParameters& p, double vehicle_length_m) {
  return 1000.0 / (p.min_gap_m + vehicle_length_m);
}

}  // namespace rcsim::traffic
