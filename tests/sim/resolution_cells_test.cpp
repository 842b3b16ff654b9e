// Paper III-C, eqs. (4)-(5).
#include "sim/resolution_cells.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "common/rng.hpp"

namespace rcsim {
namespace {

Echo echo(double range_m, double rate_mps, double amplitude, int index) {
  Echo e;
  e.range_m = range_m;
  e.range_rate_mps = rate_mps;
  e.amplitude = amplitude;
  e.sum_pointer = amplitude;
  e.delta_pointer = 0.1 * amplitude;
  e.ideal_index = index;
  return e;
}

TEST(ResolutionCells, CellsInElevationKeepEchoesACellApartAndWeighTheirElevation) {
  // Same range and range rate; elevations 0, 1 deg and 4 deg; 2-deg cells in elevation.
  Echoes echoes{echo(20.0, 0.0, 3.0, 0), echo(20.0, 0.0, 1.0, 1), echo(20.0, 0.0, 2.0, 2)};
  const double deg = std::numbers::pi / 180.0;
  echoes[1].elevation_rad = 1.0 * deg;
  echoes[2].elevation_rad = 4.0 * deg;
  ResolutionCell cells_in_elevation;
  cells_in_elevation.elevation_cell_rad = 2.0 * deg;
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(cells_in_elevation, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 2u);
  // The strongest cell holds echoes 0 and 1: elevation (3 x 0 + 1 x 1) / 4 = 0.25 deg (eq. (4)).
  EXPECT_EQ(cells[0].member_count, 2);
  EXPECT_NEAR(cells[0].elevation_rad, 0.25 * deg, 1e-15);
  EXPECT_NEAR(cells[1].elevation_rad, 4.0 * deg, 1e-15);
  // Without cells in elevation all three merge, at (0 + 1 + 8) / 6 = 1.5 deg.
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_NEAR(cells[0].elevation_rad, 1.5 * deg, 1e-15);
}

TEST(ResolutionCells, AnArrayThatResolvesAzimuthKeepsEchoesABeamApart) {
  // Same range and range rate; azimuths 0, 0.4 deg and 2 deg; 1-deg beams.
  Echoes echoes{echo(20.0, 0.0, 3.0, 0), echo(20.0, 0.0, 1.0, 1), echo(20.0, 0.0, 2.0, 2)};
  echoes[0].azimuth_rad = 0.0;
  echoes[1].azimuth_rad = 0.4 * std::numbers::pi / 180.0;
  echoes[2].azimuth_rad = 2.0 * std::numbers::pi / 180.0;
  ResolutionCell beams;
  beams.azimuth_cell_rad = std::numbers::pi / 180.0;
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(beams, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 2u);
  // The strongest beam holds echoes 0 and 1: azimuth (3 * 0 + 1 * 0.4) / 4 = 0.1 deg (eq. (4) on the angle).
  EXPECT_EQ(cells[0].member_count, 2);
  EXPECT_NEAR(cells[0].azimuth_rad, 0.1 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(cells[0].amplitude_upper, 4.0);
  EXPECT_EQ(cells[1].member_count, 1);
  EXPECT_NEAR(cells[1].azimuth_rad, 2.0 * std::numbers::pi / 180.0, 1e-15);
  // The paper's cells (no beams) merge all three.
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].member_count, 3);
}

TEST(ResolutionCells, MembersMergeWithAmplitudeWeights) {
  Echoes echoes{echo(10.10, -1.0, 1.0, 0), echo(10.00, -1.2, 3.0, 1)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 1.0, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 1u);
  // eqs. (4)-(5): w = 3/4, 1/4
  EXPECT_NEAR(cells[0].range_m, 0.75 * 10.00 + 0.25 * 10.10, 1e-12);
  EXPECT_NEAR(cells[0].range_rate_mps, 0.75 * -1.2 + 0.25 * -1.0, 1e-12);
  EXPECT_DOUBLE_EQ(cells[0].amplitude_upper, 4.0);
  EXPECT_EQ(cells[0].member_count, 2);
  EXPECT_EQ(cells[0].strongest_ideal_index, 1);
  EXPECT_NEAR(cells[0].sum_pointer.real(), 4.0, 1e-12);
}

TEST(ResolutionCells, CellIsCentredOnTheStrongest) {
  // 0.16 m from the strongest is outside its 0.30 m cell even though within 0.30 m.
  Echoes echoes{echo(10.0, 0.0, 5.0, 0), echo(10.16, 0.0, 1.0, 1), echo(9.86, 0.0, 1.0, 2)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].member_count, 2);  // 10.0 and 9.86
  EXPECT_EQ(cells[1].member_count, 1);  // 10.16 on its own
  EXPECT_DOUBLE_EQ(cells[1].range_m, 10.16);
}

TEST(ResolutionCells, SeparateInRangeRate) {
  Echoes echoes{echo(10.0, 0.0, 2.0, 0), echo(10.0, 0.3, 2.0, 1)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 1.0, echoes, buffers, cells);
  EXPECT_EQ(cells.size(), 2u);
}

TEST(ResolutionCells, UpperBoundBelowThresholdGivesNoEntry) {
  Echoes echoes{echo(10.0, 0.0, 0.9, 0), echo(10.05, 0.0, 0.9, 1), echo(20.0, 0.0, 1.5, 2)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 2.0, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 0u);  // 1.8 < 2 and 1.5 < 2
  form_resolution_cells(ResolutionCell{}, 1.7, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_DOUBLE_EQ(cells[0].amplitude_upper, 1.8);
}

TEST(ResolutionCells, StrongestFirstWithoutMovingTheEchoes) {
  Echoes echoes{echo(10.0, 0.0, 1.0, 0), echo(12.0, 0.0, 2.0, 1)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].strongest_ideal_index, 1);  // the stronger echo's cell first
  EXPECT_EQ(cells[1].strongest_ideal_index, 0);
  EXPECT_EQ(echoes[0].ideal_index, 0);  // echoes[i] still belongs to ideal target i
  EXPECT_EQ(echoes[1].ideal_index, 1);
}

TEST(ResolutionCells, EqualAmplitudesTakeTheLowerIdealIndexFirst) {
  // Both within one cell of each other: the centre (and so the cell's truth) is the lower index.
  Echoes echoes{echo(10.1, 0.0, 1.0, 3), echo(10.0, 0.0, 1.0, 2)};
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, buffers, cells);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].strongest_ideal_index, 2);
  EXPECT_EQ(cells[0].member_count, 2);
}

// The cells the direct way (paper III-C): echoes sorted strongest first, each free one the centre
// of a cell that takes every free echo within half a cell, scanned over all echoes: O(n^2).
ResolutionCells cells_by_full_scan(const ResolutionCell& cell, double threshold_amplitude, Echoes echoes) {
  std::sort(echoes.begin(), echoes.end(), [](const Echo& a, const Echo& b) {
    if (a.amplitude != b.amplitude) return a.amplitude > b.amplitude;
    return a.ideal_index < b.ideal_index;
  });
  std::vector<bool> taken(echoes.size(), false);
  ResolutionCells out;
  for (std::size_t i = 0; i < echoes.size(); ++i) {
    if (taken[i]) continue;
    ResolutionCellSum c;
    c.strongest_ideal_index = echoes[i].ideal_index;
    double weighted_range = 0.0, weighted_rate = 0.0;
    for (std::size_t j = i; j < echoes.size(); ++j) {
      const Echo& e = echoes[j];
      if (taken[j] || std::abs(e.range_m - echoes[i].range_m) > 0.5 * cell.range_cell_m ||
          std::abs(e.range_rate_mps - echoes[i].range_rate_mps) > 0.5 * cell.range_rate_cell_mps) {
        continue;
      }
      c.amplitude_upper += e.amplitude;
      weighted_range += e.amplitude * e.range_m;
      weighted_rate += e.amplitude * e.range_rate_mps;
      c.sum_pointer += e.sum_pointer;
      c.delta_pointer += e.delta_pointer;
      ++c.member_count;
      taken[j] = true;
    }
    if (c.amplitude_upper < threshold_amplitude) continue;
    c.range_m = weighted_range / c.amplitude_upper;
    c.range_rate_mps = weighted_rate / c.amplitude_upper;
    out.push_back(c);
  }
  return out;
}

TEST(ResolutionCells, NeighboursInRangeGiveTheCellsOfTheFullScanExactly) {
  // Dense clusters (many echoes per cell, chains of overlapping cells), equal amplitudes and equal
  // ranges, over many random scenes; the buffers are reused from scene to scene as in the cycle.
  Rng rng(21, 0);
  ResolutionCellBuffers buffers;
  ResolutionCells cells;
  for (int scene = 0; scene < 2000; ++scene) {
    const int n = static_cast<int>(rng.uniform(0.0, 60.0));
    const double spread_m = rng.uniform(0.2, 30.0);
    Echoes echoes;
    for (int i = 0; i < n; ++i) {
      double range_m = 5.0 + rng.uniform(0.0, spread_m);
      if (i > 0 && rng.uniform01() < 0.1) range_m = echoes[static_cast<std::size_t>(i - 1)].range_m;
      const double amplitude = rng.uniform01() < 0.2 ? 1.0 : rng.uniform(0.1, 5.0);
      Echo e = echo(range_m, rng.uniform(-1.0, 1.0), amplitude, i);
      e.sum_pointer = std::complex<double>(amplitude * rng.uniform(-1.0, 1.0), amplitude * rng.uniform(-1.0, 1.0));
      echoes.push_back(e);
    }
    const ResolutionCell cell{rng.uniform(0.1, 1.0), rng.uniform(0.2, 2.0)};
    const double threshold = rng.uniform(0.0, 3.0);
    const Echoes before = echoes;
    form_resolution_cells(cell, threshold, echoes, buffers, cells);
    const ResolutionCells expected = cells_by_full_scan(cell, threshold, echoes);
    ASSERT_EQ(cells.size(), expected.size()) << "scene " << scene;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      EXPECT_EQ(cells[k].strongest_ideal_index, expected[k].strongest_ideal_index);
      EXPECT_EQ(cells[k].member_count, expected[k].member_count);
      // Bit for bit: the members add up in the same order (strongest first).
      EXPECT_EQ(cells[k].range_m, expected[k].range_m);
      EXPECT_EQ(cells[k].range_rate_mps, expected[k].range_rate_mps);
      EXPECT_EQ(cells[k].amplitude_upper, expected[k].amplitude_upper);
      EXPECT_EQ(cells[k].sum_pointer, expected[k].sum_pointer);
      EXPECT_EQ(cells[k].delta_pointer, expected[k].delta_pointer);
    }
    for (std::size_t i = 0; i < echoes.size(); ++i) EXPECT_EQ(echoes[i].ideal_index, before[i].ideal_index);
  }
}

}  // namespace
}  // namespace rcsim
