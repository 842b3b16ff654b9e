// Paper III-C, eqs. (4)-(5).
#include "sim/resolution_cells.hpp"

#include <gtest/gtest.h>

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

TEST(ResolutionCells, MembersMergeWithAmplitudeWeights) {
  Echoes echoes{echo(10.10, -1.0, 1.0, 0), echo(10.00, -1.2, 3.0, 1)};
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 1.0, echoes, cells);
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
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, cells);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].member_count, 2);  // 10.0 and 9.86
  EXPECT_EQ(cells[1].member_count, 1);  // 10.16 on its own
  EXPECT_DOUBLE_EQ(cells[1].range_m, 10.16);
}

TEST(ResolutionCells, SeparateInRangeRate) {
  Echoes echoes{echo(10.0, 0.0, 2.0, 0), echo(10.0, 0.3, 2.0, 1)};
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 1.0, echoes, cells);
  EXPECT_EQ(cells.size(), 2u);
}

TEST(ResolutionCells, UpperBoundBelowThresholdGivesNoEntry) {
  Echoes echoes{echo(10.0, 0.0, 0.9, 0), echo(10.05, 0.0, 0.9, 1), echo(20.0, 0.0, 1.5, 2)};
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 2.0, echoes, cells);
  ASSERT_EQ(cells.size(), 0u);  // 1.8 < 2 and 1.5 < 2
  form_resolution_cells(ResolutionCell{}, 1.7, echoes, cells);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_DOUBLE_EQ(cells[0].amplitude_upper, 1.8);
}

TEST(ResolutionCells, InputIndicesAreRestored) {
  Echoes echoes{echo(10.0, 0.0, 1.0, 0), echo(12.0, 0.0, 2.0, 1)};
  ResolutionCells cells;
  form_resolution_cells(ResolutionCell{}, 0.5, echoes, cells);
  EXPECT_EQ(echoes[0].ideal_index, 1);  // sorted strongest first
  EXPECT_EQ(echoes[1].ideal_index, 0);
}

}  // namespace
}  // namespace rcsim
