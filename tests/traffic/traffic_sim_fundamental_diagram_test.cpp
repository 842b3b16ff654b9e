// Macroscopic check against the IDM literature: the flow-density relation of a single-lane ring
// road of identical Treiber-2000 cars must match the IDM's equilibrium fundamental diagram
// Q(rho) = rho v_e(rho), with s_e(v) = (s0 + v T) / sqrt(1 - (v/v0)^delta), in capacity and
// critical density (docs/traffic.md shows the curve).
#include <gtest/gtest.h>

#include <cstdio>

#include "traffic/idm.hpp"
#include "traffic/traffic_sim.hpp"

namespace rcsim::traffic {
namespace {

// Mean flow (vehicles/h) of a ring at the density after warming up: Q = rho * mean speed.
double ring_flow_vph(double density_vpkm, std::uint64_t seed) {
  TrafficConfig c;
  c.layout = Layout::Ring;
  c.lanes = 1;
  c.length_m = 2000.0;
  c.density_vpkm = density_vpkm;
  c.truck_share = 0.0;
  c.warmup_s = 0.0;
  c.duration_s = 1.0;
  c.classes = default_vehicle_classes(Layout::Highway);
  c.classes[0].desired_speed_sigma_mps = 0.0;  // identical vehicles, as the theory assumes
  c.classes[0].length_m = 5.0;                 // Treiber 2000: l = 5 m
  c.seed = seed;
  c = resolve_traffic_config(c, ".");
  Rng rng(seed);
  TrafficSimulation sim(c, rng);
  for (int k = 0; k < 1500; ++k) sim.step(rng);  // 150 s to settle from the jittered start
  double speed_sum_mps = 0.0;
  int count = 0;
  for (int k = 0; k < 1000; ++k) {
    sim.step(rng);
    for (const Vehicle& v : sim.vehicles()) speed_sum_mps += v.speed_mps, ++count;
  }
  const double actual_density_vpkm = 1000.0 * static_cast<double>(sim.vehicles().size()) / c.length_m;
  return actual_density_vpkm * 3.6 * speed_sum_mps / count;
}

TEST(TrafficFundamentalDiagram, RingRoadMatchesIdmCapacityAndCriticalDensity) {
  const IdmParameters p = default_vehicle_classes(Layout::Highway)[0].idm;
  const FundamentalDiagramPoint theory = idm_capacity(p, 5.0);
  double best_flow_vph = 0.0, best_density_vpkm = 0.0;
  for (double density_vpkm = 10.0; density_vpkm <= 60.0; density_vpkm += 2.5) {
    const double flow_vph = ring_flow_vph(density_vpkm, 1);
    const double theory_vph = idm_equilibrium_at_density(p, 5.0, density_vpkm).flow_vph;
    std::printf("  density %5.1f /km: simulated %6.0f /h, theory %6.0f /h\n", density_vpkm, flow_vph, theory_vph);
    if (flow_vph > best_flow_vph) best_flow_vph = flow_vph, best_density_vpkm = density_vpkm;
    // The free branch and the congested branch both follow the equilibrium curve (5 %).
    EXPECT_NEAR(flow_vph, theory_vph, 0.05 * theory_vph) << density_vpkm;
  }
  std::printf("  capacity: simulated %.0f /h at %.1f /km; theory %.0f /h at %.1f /km\n", best_flow_vph,
              best_density_vpkm, theory.flow_vph, theory.density_vpkm);
  EXPECT_NEAR(best_flow_vph, theory.flow_vph, 0.03 * theory.flow_vph);
  EXPECT_NEAR(best_density_vpkm, theory.density_vpkm, 2.5);  // the density grid's spacing
}

}  // namespace
}  // namespace rcsim::traffic
