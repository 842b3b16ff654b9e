// Monopulse angle estimation (sim/monopulse.hpp, paper III-D, eqs. (6)-(8)) by hand: one
// reflector's angle comes back; two equal reflectors symmetric about the boresight in one cell
// give an angle near the middle, at neither reflector (the merge artefact of Fig. 10); two unequal ones land between them, nearer the
// stronger; the noise of eq. (8) is drawn from the generator and repeats with its seed.
#include "sim/monopulse.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/decibel.hpp"

namespace rcsim {
namespace {

const MonopulseAntenna kMonopulseTestAntenna{AntennaGeometry{}};

// One cell holding reflectors at the given azimuths with the given linear amplitudes.
ResolutionCells cell_of(const std::vector<std::pair<double, double>>& azimuth_amplitude) {
  ResolutionCellSum cell;
  cell.range_m = 10.0;
  cell.strongest_ideal_index = 0;
  for (const auto& [azimuth_rad, amplitude] : azimuth_amplitude) {
    const AntennaPointers h = kMonopulseTestAntenna.pattern(azimuth_rad);
    cell.sum_pointer += amplitude * h.sum;  // eq. (8): the cell's pointers are the members' sums
    cell.delta_pointer += amplitude * h.delta;
  }
  return {cell};
}

IdealTargets one_ideal(int object) {
  IdealTargets ideal(1);
  ideal[0].object_index = object;
  return ideal;
}

TEST(Monopulse, OneReflectorsAngleComesBack) {
  for (const double azimuth_rad : {-0.5, -0.1, 0.0, 0.2, 0.55}) {
    Detections out;
    estimate_monopulse_angles(kMonopulseTestAntenna, 0.0, cell_of({{azimuth_rad, 3.0}}), one_ideal(7), nullptr, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(out[0].azimuth_rad, azimuth_rad, 1e-9) << azimuth_rad;
    EXPECT_EQ(out[0].object_index, 7);
    EXPECT_NEAR(out[0].amplitude_db, amplitude_to_db(3.0 * kMonopulseTestAntenna.sum_magnitude(azimuth_rad)), 1e-9);
  }
}

TEST(Monopulse, TwoEqualReflectorsSymmetricAboutBoresightMergeNearTheMiddle) {
  Detections out;
  estimate_monopulse_angles(kMonopulseTestAntenna, 0.0, cell_of({{-0.15, 1.0}, {0.15, 1.0}}), one_ideal(0), nullptr, out);
  ASSERT_EQ(out.size(), 1u);
  // The pointers' sum and delta are real: the amplitude-sum ratio |delta| / |sum| = tan^2(psi/2)
  // (eq. (7)) gives a small angle whose sign the phase cannot tell; measured -0.036 rad.
  EXPECT_LT(std::abs(out[0].azimuth_rad), 0.05);
  Detections swapped;
  estimate_monopulse_angles(kMonopulseTestAntenna, 0.0, cell_of({{0.15, 1.0}, {-0.15, 1.0}}), one_ideal(0), nullptr, swapped);
  EXPECT_NEAR(swapped.at(0).azimuth_rad, out[0].azimuth_rad, 1e-12);  // the order of the members does not matter
}

TEST(Monopulse, TwoUnequalReflectorsLandBetweenNearerTheStronger) {
  Detections out;
  estimate_monopulse_angles(kMonopulseTestAntenna, 0.0, cell_of({{0.0, 1.0}, {0.2, 3.0}}), one_ideal(0), nullptr, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_GT(out[0].azimuth_rad, 0.1);
  EXPECT_LT(out[0].azimuth_rad, 0.2);
}

TEST(Monopulse, PointerNoiseRepeatsWithItsSeed) {
  const auto estimate = [](std::uint64_t seed) {
    Rng rng(seed);
    Detections out;
    estimate_monopulse_angles(kMonopulseTestAntenna, 0.1, cell_of({{0.1, 0.5}}), one_ideal(0), &rng, out);
    return out.at(0).azimuth_rad;
  };
  EXPECT_EQ(estimate(3), estimate(3));
  EXPECT_NE(estimate(3), estimate(4));
  EXPECT_NEAR(estimate(3), 0.1, 0.2);  // sigma 0.1 against a pointer of about 0.5
}

TEST(Monopulse, IdealAnglesTakeTheStrongestMembersAzimuth) {
  IdealTargets ideal = one_ideal(2);
  ideal[0].azimuth_rad = 0.3;
  Detections out;
  estimate_ideal_angles(0.0, cell_of({{0.3, 2.0}, {0.1, 1.0}}), ideal, nullptr, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].azimuth_rad, 0.3);
  EXPECT_EQ(out[0].object_index, 2);
}

}  // namespace
}  // namespace rcsim
