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
  // 10 m and 0 m/s are the centres of their cells (20 and 0 cells: the map's cells are centred on
  // whole multiples, zero Doppler at a centre). 10 dB over the threshold: the neighbours in range
  // and in range rate at W(1) = -6.02 dB pass, the diagonals at W(1)^2 = -12.04 dB do not, two
  // cells away lies the null.
  Detections d{return_at(10.0, 0.0, 60.0)};
  add_spectral_leakage(hann_cells(), 50.0, d);
  ASSERT_EQ(d.size(), 5u);
  const double expected_db = 60.0 + 20.0 * std::log10(0.5);
  const double ranges_m[] = {9.5, 10.0, 10.0, 10.5}, rates_mps[] = {0.0, -0.25, 0.25, 0.0};
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
  // 10.25 m is 20.5 cells: on the edge, taken as cell 21 at offset -0.5, so cell 20 reads it as
  // strongly (W(0.5) / W(0.5), 0 dB); cells 22 and 19 W(1.5) / W(0.5) = 0.2 (-13.98 dB), cell 23
  // W(2.5) / W(0.5) (-30.9 dB). 19 dB over the threshold; in range rate at the centre, the
  // diagonals are 6.02 dB lower again: only cell 20's pass. The leaks lie at the detection's offset
  // moved 1e-6 cells off the edge (5e-7 m): in their own cells, never back in the detection's.
  Detections d{return_at(10.25, 0.0, 69.0)};
  add_spectral_leakage(hann_cells(), 50.0, d);
  ASSERT_EQ(d.size(), 8u);
  struct Expected {
    double range_m, range_rate_mps, amplitude_db;
  };
  const double minus_14_db = 20.0 * std::log10(0.2), minus_6_db = 20.0 * std::log10(0.5);
  const Expected expected[] = {{9.25, 0.0, 69.0 + minus_14_db}, {9.75, -0.25, 69.0 + minus_6_db}, {9.75, 0.0, 69.0},
                               {9.75, 0.25, 69.0 + minus_6_db},  {10.25, -0.25, 69.0 + minus_6_db}, {10.25, 0.25, 69.0 + minus_6_db},
                               {10.75, 0.0, 69.0 + minus_14_db}};
  const double cells_of[] = {19, 20, 20, 20, 21, 21, 22};
  for (int k = 0; k < 7; ++k) {
    const Detection& leak = d[static_cast<std::size_t>(k) + 1];
    EXPECT_NEAR(leak.range_m, expected[k].range_m + 5e-7, 1e-12) << k;
    EXPECT_EQ(map_cell_index(leak.range_m, 0.5), cells_of[k]) << k;
    EXPECT_NEAR(leak.range_rate_mps, expected[k].range_rate_mps, 1e-12) << k;
    EXPECT_NEAR(leak.amplitude_db, expected[k].amplitude_db, 1e-9) << k;
  }
}

TEST(SpectralLeakage, EveryLeakLiesInTheCellItIsFor) {
  // Cells of 0.075 m and 0.0812 m/s (the Astyx HiRes's, not exact in binary), detections on and
  // beside the cells' edges and centres: each leak's cell is its detection's plus (i, j), never its own.
  ResolutionCell cell;
  cell.range_cell_m = 0.075, cell.range_rate_cell_mps = 0.0812, cell.window = SpectralWindow::hann;
  int leaks = 0;
  for (int n = 1; n < 400; ++n) {
    for (const double offset : {-0.5, -0.4999999, -0.25, 0.0, 0.25, 0.4999999, 0.5}) {
      const double range_m = (n + offset) * cell.range_cell_m, rate_mps = (n % 13 - 6 + offset) * cell.range_rate_cell_mps;
      Detections d{return_at(range_m, rate_mps, 90.0)};
      add_spectral_leakage(cell, 45.0, d);
      const double r0 = map_cell_index(range_m, cell.range_cell_m), v0 = map_cell_index(rate_mps, cell.range_rate_cell_mps);
      for (std::size_t k = 1; k < d.size(); ++k) {
        const double dr = map_cell_index(d[k].range_m, cell.range_cell_m) - r0;
        const double dv = map_cell_index(d[k].range_rate_mps, cell.range_rate_cell_mps) - v0;
        EXPECT_TRUE(dr != 0.0 || dv != 0.0) << range_m << " " << rate_mps;
        EXPECT_LE(std::abs(dr), kLeakageReachCells);
        EXPECT_LE(std::abs(dv), kLeakageReachCells);
        // The leak's own offset is the detection's, off the edge by at most 1e-6 cells.
        EXPECT_NEAR(map_cell_offset(d[k].range_m, cell.range_cell_m), map_cell_offset(range_m, cell.range_cell_m), 1e-6 + 1e-9);
        ++leaks;
      }
      // No two leaks share a cell.
      for (std::size_t a = 1; a < d.size(); ++a) {
        for (std::size_t b = a + 1; b < d.size(); ++b) {
          EXPECT_FALSE(map_cell_index(d[a].range_m, cell.range_cell_m) == map_cell_index(d[b].range_m, cell.range_cell_m) &&
                       map_cell_index(d[a].range_rate_mps, cell.range_rate_cell_mps) ==
                           map_cell_index(d[b].range_rate_mps, cell.range_rate_cell_mps));
        }
      }
    }
  }
  EXPECT_GT(leaks, 399 * 7 * 8);  // 45 dB over: at least the eight neighbours each
}

TEST(SpectralLeakage, ANanAmplitudeLeaksNothing) {
  Detections d{return_at(10.0, 0.0, std::nan(""))};
  add_spectral_leakage(hann_cells(), 50.0, d);
  EXPECT_EQ(d.size(), 1u);
}

TEST(SpectralLeakage, NoWindowOrNoMarginLeaksNothing) {
  Detections d{return_at(10.0, 0.0, 60.0)};
  ResolutionCell none = hann_cells();
  none.window = SpectralWindow::none;
  add_spectral_leakage(none, 50.0, d);
  EXPECT_EQ(d.size(), 1u);
  Detections weak{return_at(10.0, 0.0, 55.0)};  // 5 dB over: the neighbours at -6.02 dB stay under
  add_spectral_leakage(hann_cells(), 50.0, weak);
  EXPECT_EQ(weak.size(), 1u);
}

}  // namespace
}  // namespace spectral_leakage_test
}  // namespace rcsim
