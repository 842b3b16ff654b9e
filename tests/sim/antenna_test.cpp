// Paper eq. (6) and (7): patterns, the additive sensing ratio and its exact inverse.
#include "sim/antenna.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "common/angles.hpp"

namespace rcsim {
namespace {

const MonopulseAntenna kAntenna{AntennaGeometry{}};

TEST(Antenna, SumPatternIsOneAtBoresight) {
  const auto h = kAntenna.pattern(0.0);
  EXPECT_DOUBLE_EQ(std::abs(h.sum), 1.0);
  EXPECT_DOUBLE_EQ(std::abs(h.delta), 0.0);
}

TEST(Antenna, SumPatternAt30DegreesByHand) {
  // si(pi/2 * 0.5) cos 30 deg |cos(pi/4)| = (sin(pi/4)/(pi/4)) * 0.866025 * 0.707107 = 0.551329
  const double expected = (std::sin(kPi / 4) / (kPi / 4)) * std::cos(deg_to_rad(30)) * std::cos(kPi / 4);
  EXPECT_NEAR(kAntenna.sum_magnitude(deg_to_rad(30)), expected, 1e-15);
  EXPECT_NEAR(kAntenna.sum_magnitude(deg_to_rad(30)), 0.551329, 1e-6);
  EXPECT_NEAR(kAntenna.sum_magnitude(deg_to_rad(-30)), expected, 1e-15);
}

TEST(Antenna, AdditiveSensingRatioAtKeyAngles) {
  // ASR = tan(|u| - pi/4), u = pi/2 sin(phi): -1 at boresight, 0 at 30 deg, 1 at 90 deg.
  EXPECT_DOUBLE_EQ(MonopulseAntenna::additive_sensing_ratio(kAntenna.pattern(0.0)), -1.0);
  EXPECT_NEAR(MonopulseAntenna::additive_sensing_ratio(kAntenna.pattern(deg_to_rad(30))), 0.0, 1e-15);
  EXPECT_NEAR(MonopulseAntenna::additive_sensing_ratio(kAntenna.pattern(deg_to_rad(-30))), 0.0, 1e-15);
  EXPECT_NEAR(MonopulseAntenna::additive_sensing_ratio(kAntenna.pattern(deg_to_rad(89.999))), 1.0, 1e-6);
}

TEST(Antenna, AsrIsMonotoneInAbsoluteAngle) {
  double previous = -2.0;
  for (int i = 0; i <= 899; ++i) {
    const double asr = MonopulseAntenna::additive_sensing_ratio(kAntenna.pattern(deg_to_rad(i * 0.1)));
    EXPECT_GT(asr, previous) << "at " << i * 0.1 << " deg";
    previous = asr;
  }
}

TEST(Antenna, InverseRoundTripIsExactAcrossTheHalfPlane) {
  for (double deg = -89.5; deg <= 89.5; deg += 0.5) {
    const double phi = deg_to_rad(deg);
    EXPECT_NEAR(kAntenna.estimate_azimuth(kAntenna.pattern(phi)), phi, 1e-12) << deg << " deg";
  }
}

TEST(Antenna, SignFollowsPhaseBetweenDeltaAndSum) {
  const auto left = kAntenna.pattern(deg_to_rad(20));
  const auto right = kAntenna.pattern(deg_to_rad(-20));
  EXPECT_LT((left.delta * std::conj(left.sum)).imag(), 0.0);
  EXPECT_GT((right.delta * std::conj(right.sum)).imag(), 0.0);
  EXPECT_GT(kAntenna.estimate_azimuth(left), 0.0);
  EXPECT_LT(kAntenna.estimate_azimuth(right), 0.0);
}

TEST(Antenna, PatternEqualsEquation6WrittenWithComplexExponentials) {
  // eq. (6) as printed, for the srr24 (L = d = lambda/2: one sine serves both factors) and for a
  // geometry with L != d; the sensor cycle passes sin and cos of the azimuth from the line of sight.
  AntennaGeometry other;
  other.dipole_length_wavelengths = 0.7;
  other.element_spacing_wavelengths = 0.45;
  for (const auto& geometry : {AntennaGeometry{}, other}) {
    const MonopulseAntenna antenna{geometry};
    for (double deg = -89.0; deg <= 89.0; deg += 0.5) {
      const double phi = deg_to_rad(deg);
      const double x = kPi * geometry.dipole_length_wavelengths * std::sin(phi);
      const double si = x == 0.0 ? 1.0 : std::sin(x) / x;
      const std::complex<double> turn = std::exp(std::complex<double>(0.0, 2.0 * kPi * geometry.element_spacing_wavelengths * std::sin(phi)));
      const std::complex<double> sum = si * std::cos(phi) * 0.5 * (1.0 + turn);
      const std::complex<double> delta = si * std::cos(phi) * 0.5 * (1.0 - turn);
      const auto h = antenna.pattern(std::sin(phi), std::cos(phi));
      EXPECT_NEAR(std::abs(h.sum - sum), 0.0, 1e-15) << deg;
      EXPECT_NEAR(std::abs(h.delta - delta), 0.0, 1e-15) << deg;
      const auto by_angle = antenna.pattern(phi);
      EXPECT_EQ(by_angle.sum, h.sum);
      EXPECT_EQ(by_angle.delta, h.delta);
    }
  }
}

TEST(Antenna, NoSignalGivesBoresightNotNaN) {
  EXPECT_DOUBLE_EQ(kAntenna.estimate_azimuth({}), 0.0);
}

}  // namespace
}  // namespace rcsim
