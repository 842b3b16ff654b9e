// Imaging arrays (docs/imaging-radar.md): a beam cell's angle and amplitude, and one detection
// per range-Doppler cell.
#include "sim/beamforming.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/angles.hpp"

namespace rcsim {
namespace {

TEST(Beamforming, EachBeamCellHasItsOwnAngleAndItsSumPointersAmplitude) {
  IdealTargets ideal(2);
  ideal[0].object_index = 4;
  ideal[1].object_index = 7;
  ResolutionCells cells(2);
  cells[0].range_m = 12.0;
  cells[0].range_rate_mps = -1.5;
  cells[0].azimuth_rad = 0.1;
  cells[0].sum_pointer = {30.0, 40.0};  // |50| -> 20 log10 50 = 33.979 dB
  cells[0].strongest_ideal_index = 1;
  cells[1].azimuth_rad = -0.3;
  cells[1].sum_pointer = {1.0, 0.0};
  cells[1].strongest_ideal_index = 0;
  Detections out;
  estimate_beam_angles(0.01, 1.0, cells, ideal, nullptr, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].azimuth_rad, 0.1);
  EXPECT_DOUBLE_EQ(out[0].range_m, 12.0);
  EXPECT_DOUBLE_EQ(out[0].range_rate_mps, -1.5);
  EXPECT_NEAR(out[0].amplitude_db, 20.0 * std::log10(50.0), 1e-12);
  EXPECT_EQ(out[0].object_index, 7);
  EXPECT_DOUBLE_EQ(out[1].azimuth_rad, -0.3);
  EXPECT_NEAR(out[1].amplitude_db, 0.0, 1e-12);
  EXPECT_EQ(out[1].object_index, 4);
}

TEST(Beamforming, AngleNoiseHasItsStandardDeviation) {
  IdealTargets ideal(1);
  ResolutionCells cells(20000);
  for (auto& c : cells) {
    c.sum_pointer = {1000.0, 0.0};
    c.strongest_ideal_index = 0;
  }
  Rng rng(3, 0);
  Detections out;
  estimate_beam_angles(0.02, 1.0, cells, ideal, &rng, out);
  double sum = 0.0, sum_sq = 0.0;
  for (const auto& d : out) {
    sum += d.azimuth_rad;
    sum_sq += d.azimuth_rad * d.azimuth_rad;
  }
  const double n = static_cast<double>(out.size());
  EXPECT_NEAR(sum / n, 0.0, 0.001);                          // 5 standard errors of 0.02 / sqrt(20000)
  EXPECT_NEAR(std::sqrt(sum_sq / n), 0.02, 0.02 * 0.025);   // about 5 standard errors of the std. dev.
}

Detection detection_at(double range_m, double rate_mps, double amplitude_db) {
  Detection d;
  d.range_m = range_m;
  d.range_rate_mps = rate_mps;
  d.amplitude_db = amplitude_db;
  return d;
}

TEST(Beamforming, OneDetectionPerRangeDopplerCellTheStrongestBeam) {
  ResolutionCell cell;
  cell.range_cell_m = 0.075;
  cell.range_rate_cell_mps = 0.0812;
  // The map's cells are centred on whole multiples: round(r / 0.075): 10.00 -> 133 (133.33),
  // 10.01 -> 133 (133.47), 10.02 -> 134 (133.6), 10.05 -> 134; round(rate / 0.0812): 0 -> 0, 0.09 -> 1.
  Detections d{detection_at(10.00, 0.0, 50.0), detection_at(10.02, 0.0, 55.0), detection_at(10.05, 0.0, 47.0),
               detection_at(10.02, 0.09, 46.0), detection_at(10.01, 0.0, 55.0)};
  std::vector<std::size_t> order;
  keep_strongest_beam_per_cell(cell, d, order);
  // Cell (133, 0): 10.01 at 55 dB over 10.00 at 50; (134, 0): 10.02 at 55 over 10.05 at 47; (134, 1). Order kept.
  ASSERT_EQ(d.size(), 3u);
  EXPECT_DOUBLE_EQ(d[0].range_m, 10.02);
  EXPECT_DOUBLE_EQ(d[0].amplitude_db, 55.0);
  EXPECT_DOUBLE_EQ(d[1].range_rate_mps, 0.09);
  EXPECT_DOUBLE_EQ(d[2].range_m, 10.01);
  EXPECT_DOUBLE_EQ(d[2].amplitude_db, 55.0);
}

// A radar with cells in elevation reports the strongest beam of each range-Doppler cell at each
// elevation cell: two beams of one range-Doppler cell 3 deg apart in elevation, both kept; two
// 0.5 deg apart (one 2-deg cell: round(el / 2 deg) both 0), the stronger only.
TEST(Beamforming, WithCellsInElevationOneDetectionPerElevationCellOfARangeDopplerCell) {
  ResolutionCell cell;
  cell.range_cell_m = 0.075;
  cell.range_rate_cell_mps = 0.0812;
  cell.elevation_cell_rad = 2.0 * kPi / 180.0;
  Detections d{detection_at(10.00, 0.0, 50.0), detection_at(10.00, 0.0, 48.0), detection_at(10.00, 0.0, 49.0)};
  d[1].elevation_rad = 3.0 * kPi / 180.0;
  d[2].elevation_rad = 0.5 * kPi / 180.0;
  std::vector<std::size_t> order;
  keep_strongest_beam_per_cell(cell, d, order);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0].amplitude_db, 50.0);
  EXPECT_DOUBLE_EQ(d[1].amplitude_db, 48.0);
  cell.elevation_cell_rad = 0.0;  // no cells in elevation: one per range-Doppler cell
  Detections one{detection_at(10.00, 0.0, 50.0), detection_at(10.00, 0.0, 48.0)};
  one[1].elevation_rad = 3.0 * kPi / 180.0;
  keep_strongest_beam_per_cell(cell, one, order);
  EXPECT_EQ(one.size(), 1u);
}

}  // namespace
}  // namespace rcsim
