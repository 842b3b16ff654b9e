// The traffic simulation of traffic/traffic_sim.hpp on small highway and intersection runs: no
// overlaps, accelerations and speeds within the IDM's bounds, lane changes only into gaps MOBIL
// accepts, and the intersection's conflict area held by one road at a time.
#include "traffic/traffic_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "common/angles.hpp"
#include "traffic/idm.hpp"
#include "traffic/traffic_fixtures.hpp"

namespace rcsim::traffic_sim_test {

using namespace rcsim::traffic;

using testing::small_highway;

TrafficConfig small_intersection(std::uint64_t seed) {
  TrafficConfig c;
  c.layout = Layout::Intersection;
  c.lanes = 1;
  c.duration_s = 60.0;
  c.warmup_s = 10.0;
  c.density_vpkm = 15.0;
  c.inflow_vph = 600.0;
  c.seed = seed;
  c.record_steps = true;
  return resolve_traffic_config(c, ".");
}

// Oriented boxes overlap: separating axis test on the four edge normals.
bool boxes_overlap(const WorldMotion& a, double la, double wa, const WorldMotion& b, double lb, double wb) {
  const auto corners = [](const WorldMotion& m, double l, double w) {
    std::array<Vec2, 4> c;
    const double hx[4] = {0.5 * l, 0.5 * l, -0.5 * l, -0.5 * l};
    const double hy[4] = {0.5 * w, -0.5 * w, -0.5 * w, 0.5 * w};
    for (int k = 0; k < 4; ++k) c[k] = Vec2(m.x_m, m.y_m) + rotate(m.yaw_rad, Vec2(hx[k], hy[k]));
    return c;
  };
  const auto ca = corners(a, la, wa);
  const auto cb = corners(b, lb, wb);
  for (const double yaw : {a.yaw_rad, a.yaw_rad + 0.5 * kPi, b.yaw_rad, b.yaw_rad + 0.5 * kPi}) {
    const Vec2 axis(std::cos(yaw), std::sin(yaw));
    double amin = 1e18, amax = -1e18, bmin = 1e18, bmax = -1e18;
    for (const Vec2& p : ca) amin = std::min(amin, p.dot(axis)), amax = std::max(amax, p.dot(axis));
    for (const Vec2& p : cb) bmin = std::min(bmin, p.dot(axis)), bmax = std::max(bmax, p.dot(axis));
    if (amax < bmin || bmax < amin) return false;
  }
  return true;
}

void expect_no_overlaps(const TrafficSimulation& sim) {
  const auto& vehicles = sim.vehicles();
  int pairs_checked = 0;
  for (const StepSnapshot& step : sim.snapshots()) {
    for (std::size_t i = 0; i < step.vehicles.size(); ++i) {
      for (std::size_t j = i + 1; j < step.vehicles.size(); ++j) {
        const VehicleSnapshot& a = step.vehicles[i];
        const VehicleSnapshot& b = step.vehicles[j];
        if (std::hypot(a.motion.x_m - b.motion.x_m, a.motion.y_m - b.motion.y_m) > 25.0) continue;
        ++pairs_checked;
        const Vehicle& va = vehicles[a.vehicle];
        const Vehicle& vb = vehicles[b.vehicle];
        ASSERT_FALSE(boxes_overlap(a.motion, va.length_m, va.width_m, b.motion, vb.length_m, vb.width_m))
            << va.id << " and " << vb.id << " overlap at t = " << step.t_s << " s";
      }
    }
  }
  EXPECT_GT(pairs_checked, 100);  // the check saw close neighbours, side by side and in line
}

TEST(TrafficHighway, NoOverlapBoundedAccelerationAndSpeed) {
  TrafficConfig c = small_highway(3);
  c.curve_radius_m = 600.0;  // winding, so the lane-change yaw and the curvature both act
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  expect_no_overlaps(sim);
  const MobilParameters mobil;
  int hard_braking_steps = 0, steps = 0;
  for (const StepSnapshot& step : sim.snapshots()) {
    for (const VehicleSnapshot& s : step.vehicles) {
      const Vehicle& v = sim.vehicles()[s.vehicle];
      ++steps;
      // IDM: a <= a_max always; braking clipped at the emergency limit b_max.
      ASSERT_LE(s.accel_mps2, v.idm.max_accel_mps2 + 1e-12) << v.id;
      ASSERT_GE(s.accel_mps2, -v.idm.emergency_decel_mps2 - 1e-12) << v.id;
      if (s.accel_mps2 < -mobil.safe_decel_mps2) ++hard_braking_steps;
      // The free-road term 1 - (v/v0)^delta is negative above v0: never faster than desired.
      ASSERT_LE(s.speed_mps, v.idm.desired_speed_mps + 1e-9) << v.id;
      ASSERT_GE(s.speed_mps, 0.0);
    }
  }
  EXPECT_LT(hard_braking_steps, steps / 1000 + 1) << "braking beyond b_safe should be rare";
}

TEST(TrafficHighway, LaneChangesOnlyIntoGapsMobilAccepts) {
  const TrafficConfig c = small_highway(5);
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  ASSERT_GT(sim.lane_changes().size(), 5u);
  const MobilParameters mobil;
  for (const LaneChangeEvent& e : sim.lane_changes()) {
    EXPECT_EQ(std::abs(e.to_lane - e.from_lane), 1);
    EXPECT_GT(e.advantage_mps2, 0.0);
    EXPECT_GE(e.changer_after_mps2, -mobil.safe_decel_mps2);
    if (!e.has_new_follower) continue;
    // Recomputed from the raw IDM (Kesting 2007 eq. 2: a~_n >= -b_safe).
    EXPECT_GT(e.new_follower_gap_m, 0.0);
    EXPECT_GE(idm_raw_acceleration_mps2(e.new_follower_idm, e.new_follower_speed_mps, e.new_follower_gap_m,
                                        e.new_follower_approach_mps),
              -mobil.safe_decel_mps2)
        << e.vehicle << " at " << e.t_s;
  }
}

TEST(TrafficIntersection, ConflictAreaHoldsOneRoadAtATimeAndNoOverlap) {
  const TrafficConfig c = small_intersection(7);
  Rng rng(c.seed);
  TrafficSimulation sim(c, rng);
  sim.run(rng);
  int crossings_seen = 0;
  std::array<bool, 2> used{false, false};
  for (const StepSnapshot& step : sim.snapshots()) {
    std::array<int, 2> inside{0, 0};
    for (const VehicleSnapshot& s : step.vehicles) {
      if (s.inside_conflict_area) ++inside[crossing_group(sim.vehicles()[s.vehicle].road)];
    }
    ASSERT_FALSE(inside[0] > 0 && inside[1] > 0) << "crossing vehicles both inside at t = " << step.t_s;
    for (int g = 0; g < 2; ++g) used[g] = used[g] || inside[g] > 0;
    crossings_seen += inside[0] + inside[1];
  }
  EXPECT_TRUE(used[0] && used[1]) << "both roads got through";
  EXPECT_GT(crossings_seen, 50);
  expect_no_overlaps(sim);
}

}  // namespace rcsim::traffic_sim_test
