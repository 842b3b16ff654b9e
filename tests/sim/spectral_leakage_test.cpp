// Spectral leakage (docs/imaging-radar.md): a strong return spills into the cells beside its own
// at the Hann window's response, computed here by hand.
#include "sim/spectral_leakage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rcsim {
namespace spectral_leakage_test {
namespace {

TEST(SpectralLeakage, TheHannWindowsResponseByHand) {
  EXPECT_DOUBLE_EQ(hann_response(0.0), 1.0);
  // sinc(0.5) = 2/pi, / (1 - 0.25): the scalloping loss, -1.42 dB.
  EXPECT_NEAR(hann_response(0.5), (2.0 / std::numbers::pi) / 0.75, 1e-12);
  EXPECT_NEAR(hann_response(-0.5), 0.848826, 1e-6);
  EXPECT_DOUBLE_EQ(hann_response(1.0), 0.5);  // the limit at the removable singularity, -6.02 dB
  EXPECT_NEAR(hann_response(1.0 + 1e-6), 0.5, 1e-6);
  EXPECT_NEAR(hann_response(1.5), (2.0 / (3.0 * std::numbers::pi)) / 1.25, 1e-12);  // 0.1698
  EXPECT_NEAR(hann_response(2.0), 0.0, 1e-15);                                      // the first null
  EXPECT_NEAR(hann_response(2.5), (2.0 / (5.0 * std::numbers::pi)) / 5.25, 1e-12);  // 0.0243, -32.3 dB
}

ResolutionCell hann_cells() {
  ResolutionCell cell;
  cell.range_cell_m = 0.5;
  cell.range_rate_cell_mps = 0.25;
  cell.window = SpectralWindow::hann;
  return cell;
}

Detection return_at(double range_m, double range_rate_mps, double amplitude_db) {
  Detection d;
  d.range_m = range_m, d.range_rate_mps = range_rate_mps, d.amplitude_db = amplitude_db;
  d.azimuth_rad = 0.3, d.object_index = 7;
  return d;
}

TEST(SpectralLeakage, AReturnAtItsCellsCentreLeaksSixDecibelsDownIntoItsFourNeighbours) {
  // 10.25 m and 0.125 m/s are the centre of their cells (20.5 and 0.5 cells from 0). 10 dB over the
  // threshold: the neighbours in range and in range rate at W(1) = -6.02 dB pass, the diagonals at
  // W(1)^2 = -12.04 dB do not, two cells away lies the null.
  Detections d{return_at(10.25, 0.125, 60.0)};
  add_spectral_leakage(hann_cells(), 50.0, d);
  ASSERT_EQ(d.size(), 5u);
  const double expected_db = 60.0 + 20.0 * std::log10(0.5);
  const double ranges_m[] = {9.75, 10.25, 10.25, 10.75}, rates_mps[] = {0.125, -0.125, 0.375, 0.125};
  for (int k = 0; k < 4; ++k) {
    const Detection& leak = d[static_cast<std::size_t>(k) + 1];
    EXPECT_NEAR(leak.range_m, ranges_m[k], 1e-12) << k;
    EXPECT_NEAR(leak.range_rate_mps, rates_mps[k], 1e-12) << k;
    EXPECT_NEAR(leak.amplitude_db, expected_db, 1e-9) << k;
    EXPECT_EQ(leak.azimuth_rad, 0.3);
    EXPECT_EQ(leak.object_index, 7);
  }
}

TEST(SpectralLeakage, AReturnBetweenTwoCellsFillsBothEqually) {
  // 10.5 m is 21.0 cells: half a cell below the centre of cell 21, so the cell below reads it as
  // strongly (W(0.5) / W(0.5), 0 dB); one above and two below W(1.5) / W(0.5) = 0.2 (-13.98 dB),
  // two above W(2.5) / W(0.5) (-30.9 dB). 19 dB over the threshold; in range rate at the centre, the
  // diagonals are 6.02 dB lower again: only the cell below's pass.
  Detections d{return_at(10.5, 0.125, 69.0)};
  add_spectral_leakage(hann_cells(), 50.0, d);
  ASSERT_EQ(d.size(), 8u);
  struct Expected {
    double range_m, range_rate_mps, amplitude_db;
  };
  const double minus_14_db = 20.0 * std::log10(0.2), minus_6_db = 20.0 * std::log10(0.5);
  const Expected expected[] = {{9.5, 0.125, 69.0 + minus_14_db}, {10.0, -0.125, 69.0 + minus_6_db}, {10.0, 0.125, 69.0},
                               {10.0, 0.375, 69.0 + minus_6_db}, {10.5, -0.125, 69.0 + minus_6_db}, {10.5, 0.375, 69.0 + minus_6_db},
                               {11.0, 0.125, 69.0 + minus_14_db}};
  for (int k = 0; k < 7; ++k) {
    const Detection& leak = d[static_cast<std::size_t>(k) + 1];
    EXPECT_NEAR(leak.range_m, expected[k].range_m, 1e-12) << k;
    EXPECT_NEAR(leak.range_rate_mps, expected[k].range_rate_mps, 1e-12) << k;
    EXPECT_NEAR(leak.amplitude_db, expected[k].amplitude_db, 1e-9) << k;
  }
}

TEST(SpectralLeakage, NoWindowOrNoMarginLeaksNothing) {
  Detections d{return_at(10.25, 0.125, 60.0)};
  ResolutionCell none = hann_cells();
  none.window = SpectralWindow::none;
  add_spectral_leakage(none, 50.0, d);
  EXPECT_EQ(d.size(), 1u);
  Detections weak{return_at(10.25, 0.125, 55.0)};  // 5 dB over: the neighbours at -6.02 dB stay under
  add_spectral_leakage(hann_cells(), 50.0, weak);
  EXPECT_EQ(weak.size(), 1u);
}

}  // namespace
}  // namespace spectral_leakage_test
}  // namespace rcsim
