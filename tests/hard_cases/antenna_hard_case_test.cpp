// Hard cases of the antenna and monopulse stages (eqs. (6)-(8)): ASR at +-1, zero sum pointer,
// azimuth at and beyond +-90 deg.
#include <gtest/gtest.h>

#include <limits>

#include "hard_cases/hard_case_support.hpp"
#include "sim/monopulse.hpp"

namespace rcsim {
namespace {

MonopulseAntenna srr24_antenna() { return MonopulseAntenna(builtin_sensor_config("srr24").antenna); }

TEST(HardCaseAntenna, PatternFiniteEverywhere) {
  const MonopulseAntenna antenna = srr24_antenna();
  for (double az_deg = -270.0; az_deg <= 270.0; az_deg += 0.5) {
    const AntennaPointers h = antenna.pattern(az_deg * kPi / 180.0);
    EXPECT_TRUE(testing::finite(h.sum) && testing::finite(h.delta)) << az_deg;
    EXPECT_LE(magnitude(h.sum), 1.0 + 1e-12);  // |H_sum| <= 1: the culling bound relies on it
  }
  // At +-90 deg the element factor cos(phi) is zero: no sum signal.
  EXPECT_NEAR(antenna.sum_magnitude(0.5 * kPi), 0.0, 1e-15);
  EXPECT_NEAR(antenna.sum_magnitude(-0.5 * kPi), 0.0, 1e-15);
}

TEST(HardCaseAntenna, AdditiveSensingRatioLimits) {
  const MonopulseAntenna antenna = srr24_antenna();
  // Sum pointer zero, delta not: ASR = +1, |phi| = 90 deg at d = lambda/2.
  const AntennaPointers only_delta{{0.0, 0.0}, {0.0, -1.0}};
  EXPECT_DOUBLE_EQ(MonopulseAntenna::additive_sensing_ratio(only_delta), 1.0);
  EXPECT_NEAR(std::abs(antenna.estimate_azimuth(only_delta)), 0.5 * kPi, 1e-12);
  // Delta zero: ASR = -1, boresight.
  const AntennaPointers only_sum{{1.0, 0.0}, {0.0, 0.0}};
  EXPECT_DOUBLE_EQ(MonopulseAntenna::additive_sensing_ratio(only_sum), -1.0);
  EXPECT_DOUBLE_EQ(antenna.estimate_azimuth(only_sum), 0.0);
  // Nothing at all: boresight, finite.
  const AntennaPointers nothing{{0.0, 0.0}, {0.0, 0.0}};
  EXPECT_TRUE(std::isfinite(antenna.estimate_azimuth(nothing)));
  // Beyond the clamp and subnormal pointers.
  for (const double asr : {-2.0, -1.0, -1.0 + 1e-16, 1.0 - 1e-16, 1.0, 2.0}) {
    const double phi = antenna.absolute_azimuth_from_asr(asr);
    EXPECT_TRUE(std::isfinite(phi));
    EXPECT_GE(phi, 0.0);
    EXPECT_LE(phi, 0.5 * kPi);
  }
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_TRUE(std::isfinite(antenna.estimate_azimuth({{tiny, 0.0}, {0.0, tiny}})));
  // Every azimuth within +-90 deg is recovered from its own pattern (eq. (7) inverted).
  for (double az_deg = -89.5; az_deg <= 89.5; az_deg += 0.5) {
    EXPECT_NEAR(antenna.estimate_azimuth(antenna.pattern(az_deg * kPi / 180.0)), az_deg * kPi / 180.0, 1e-9) << az_deg;
  }
}

TEST(HardCaseAntenna, ZeroSumCellGivesFiniteDetection) {
  // A cell whose summed sum pointer cancels exactly (two reflectors of opposite phase).
  const MonopulseAntenna antenna = srr24_antenna();
  ResolutionCells cells(1);
  cells[0].range_m = 5.0;
  cells[0].amplitude_upper = 2.0;
  cells[0].sum_pointer = {0.0, 0.0};
  cells[0].delta_pointer = {0.3, -0.2};
  cells[0].strongest_ideal_index = 0;
  IdealTargets ideal(1);
  Detections out;
  estimate_monopulse_angles(antenna, 0.0, cells, ideal, nullptr, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(std::isfinite(out[0].azimuth_rad));
  EXPECT_TRUE(std::isfinite(out[0].amplitude_db));
  estimate_ideal_angles(0.01, cells, ideal, nullptr, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(std::isfinite(out[0].amplitude_db));
}

}  // namespace
}  // namespace rcsim
