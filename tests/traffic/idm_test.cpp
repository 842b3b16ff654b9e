// The Intelligent Driver Model of traffic/idm.hpp: the desired gap, the clipped and raw
// accelerations and the equilibrium (fundamental diagram) by hand (Treiber 2000, Table I values).
#include "traffic/idm.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::idm_test {

using traffic::FundamentalDiagramPoint;
using traffic::IdmParameters;
using traffic::idm_acceleration_mps2;
using traffic::idm_capacity;
using traffic::idm_desired_gap_m;
using traffic::idm_equilibrium_at_density;
using traffic::idm_equilibrium_gap_m;
using traffic::idm_equilibrium_speed_mps;
using traffic::idm_free_acceleration_mps2;
using traffic::idm_jam_density_vpkm;
using traffic::idm_raw_acceleration_mps2;

TEST(TrafficIdm, EquilibriumGapGivesZeroAcceleration) {
  const IdmParameters p;  // Treiber 2000 Table I
  for (const double v : {5.0, 15.0, 25.0, 30.0}) {
    EXPECT_NEAR(idm_raw_acceleration_mps2(p, v, idm_equilibrium_gap_m(p, v), 0.0), 0.0, 1e-9) << v;
    EXPECT_NEAR(idm_equilibrium_speed_mps(p, idm_equilibrium_gap_m(p, v)), v, 1e-6);
  }
  EXPECT_NEAR(idm_jam_density_vpkm(p, 5.0), 1000.0 / 7.0, 1e-9);
  // Hand check of eq. (1) and (2): v = 20, s = 50, dv = 2: s* = 2 + 32 + 40/(2 sqrt(0.73 * 1.67)).
  const double s_star = 2.0 + 32.0 + 40.0 / (2.0 * std::sqrt(0.73 * 1.67));
  EXPECT_NEAR(idm_raw_acceleration_mps2(p, 20.0, 50.0, 2.0),
              0.73 * (1.0 - std::pow(20.0 / 33.33, 4.0) - (s_star / 50.0) * (s_star / 50.0)), 1e-12);
}

TEST(TrafficIdm, DesiredGapNeverBelowTheJamDistance) {
  const IdmParameters p;
  // Same speed as the leader: s0 + v T = 2 + 20 * 1.6 = 34 m.
  EXPECT_DOUBLE_EQ(idm_desired_gap_m(p, 20.0, 0.0), 34.0);
  // Standing: s0 whatever the approach rate.
  EXPECT_DOUBLE_EQ(idm_desired_gap_m(p, 0.0, 5.0), 2.0);
  // Leader pulling away fast: v = 10, dv = -10: 16 - 100 / (2 sqrt(0.73 * 1.67)) = 16 - 45.3 < 0,
  // so the dynamic part is cut at 0 and s* = s0.
  EXPECT_DOUBLE_EQ(idm_desired_gap_m(p, 10.0, -10.0), 2.0);
}

TEST(TrafficIdm, FreeRoadTermAndEmergencyClip) {
  const IdmParameters p;
  EXPECT_DOUBLE_EQ(idm_free_acceleration_mps2(p, 0.0), 0.73);
  EXPECT_NEAR(idm_free_acceleration_mps2(p, 33.33), 0.0, 1e-12);
  // Half the desired speed: a (1 - 0.5^4) = 0.73 * 15/16.
  EXPECT_NEAR(idm_free_acceleration_mps2(p, 33.33 / 2.0), 0.73 * 15.0 / 16.0, 1e-12);
  // A negative speed counts as standing (no NaN from the power).
  EXPECT_DOUBLE_EQ(idm_free_acceleration_mps2(p, -1.0), 0.73);
  // Non-positive (and tiny) gaps give -b_max; a gap of 1 m at 20 m/s clips at -b_max too.
  EXPECT_DOUBLE_EQ(idm_acceleration_mps2(p, 10.0, 0.0, 0.0), -9.0);
  EXPECT_DOUBLE_EQ(idm_acceleration_mps2(p, 10.0, -3.0, 0.0), -9.0);
  EXPECT_DOUBLE_EQ(idm_acceleration_mps2(p, 10.0, 1e-3, 0.0), -9.0);
  EXPECT_LT(idm_raw_acceleration_mps2(p, 20.0, 1.0, 0.0), -9.0);
  EXPECT_DOUBLE_EQ(idm_acceleration_mps2(p, 20.0, 1.0, 0.0), -9.0);
  // Above the clip the applied and the raw acceleration are the same.
  EXPECT_DOUBLE_EQ(idm_acceleration_mps2(p, 20.0, 50.0, 2.0), idm_raw_acceleration_mps2(p, 20.0, 50.0, 2.0));
}

TEST(TrafficIdm, FundamentalDiagramPointsAndCapacity) {
  const IdmParameters p;
  const double length_m = 5.0;
  // Gaps at or below s0 stand still; so does the jam density (spacing s0 + l = 7 m).
  EXPECT_EQ(idm_equilibrium_speed_mps(p, 2.0), 0.0);
  EXPECT_EQ(idm_equilibrium_speed_mps(p, 1.0), 0.0);
  const FundamentalDiagramPoint jam = idm_equilibrium_at_density(p, length_m, 1000.0 / 7.0);
  EXPECT_EQ(jam.speed_mps, 0.0);
  EXPECT_EQ(jam.flow_vph, 0.0);
  // 20 /km: spacing 50 m, gap 45 m; Q = rho v 3.6 (km/h).
  const FundamentalDiagramPoint free_flow = idm_equilibrium_at_density(p, length_m, 20.0);
  EXPECT_NEAR(idm_equilibrium_gap_m(p, free_flow.speed_mps), 45.0, 1e-6);
  EXPECT_DOUBLE_EQ(free_flow.density_vpkm, 20.0);
  EXPECT_NEAR(free_flow.flow_vph, 20.0 * free_flow.speed_mps * 3.6, 1e-9);
  // The capacity is the largest flow: no density on a grid gives more, and its density is
  // 1000 / (s_e(v) + l) at its speed.
  const FundamentalDiagramPoint cap = idm_capacity(p, length_m);
  EXPECT_NEAR(cap.density_vpkm, 1000.0 / (idm_equilibrium_gap_m(p, cap.speed_mps) + length_m), 1e-9);
  EXPECT_NEAR(cap.flow_vph, cap.density_vpkm * cap.speed_mps * 3.6, 1e-6);
  for (double density_vpkm = 5.0; density_vpkm < 140.0; density_vpkm += 2.5) {
    EXPECT_LE(idm_equilibrium_at_density(p, length_m, density_vpkm).flow_vph, cap.flow_vph + 1e-6) << density_vpkm;
  }
  EXPECT_GT(cap.speed_mps, 0.0);
  EXPECT_LT(cap.speed_mps, p.desired_speed_mps);
}

}  // namespace rcsim::idm_test
