// The resolution stage of `rcsim profile derive` (replay/profile/resolution_gaps.cpp, declared in
// derivation_stages.hpp): the range and range-rate cells read off the gaps between pairs of one
// cycle, on detections laid out a known cell apart, with the pairs counted by hand.
#include "replay/profile/derivation_stages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace rcsim::replay::profile::resolution_gaps_test {

// `cycles` cycles, each a full lattice of 5 ranges 1.5 m apart by 4 range rates 0.25 m/s apart
// (10 + 1.5 i m, -1 + 0.25 j m/s: exact in binary), one detection per cell.
DetectionPool lattice(int cycles) {
  DetectionPool pool;
  for (int k = 0; k < cycles; ++k) {
    PooledCycle& c = pool.cycles.emplace_back();
    c.cycle = k;
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 4; ++j) {
        PooledDetection d;
        d.range_m = 10.0 + 1.5 * i, d.range_rate_mps = -1.0 + 0.25 * j, d.azimuth_rad = 0.01 * (i + j);
        c.detections.push_back(d);
      }
    }
    pool.detections += 20;
  }
  return pool;
}

TEST(ProfileResolutionGaps, ALatticeGivesItsCellsWithThePairsCountedByHand) {
  // Pairs at one radial speed (|d rate| < 0.02 m/s: the same j): 4 x C(5, 2) = 40 a cycle, 120 in
  // three; their range gaps 1.5 m (16 a cycle), 3, 4.5, 6: the density rises from none below
  // 1.5 m to 48 pairs in [1.5, 2.25). Pairs within half of it, 0.75 m (the same i): 5 x C(4, 2)
  // = 30 a cycle, 90, gaps 0.25 m/s and multiples. Round two (pairs within a quarter of 0.25 m/s)
  // gives the same pairs again.
  const DetectionPool pool = lattice(3);
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_resolution(pool, nlohmann::json::object(), cells, figures);
  EXPECT_TRUE(cells.found);
  EXPECT_DOUBLE_EQ(cells.range_m, 1.5);
  EXPECT_DOUBLE_EQ(cells.range_rate_mps, 0.25);
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0].field, "resolution.range_cell_m");
  EXPECT_DOUBLE_EQ(values[0].value.get<double>(), 1.5);
  EXPECT_EQ(values[0].support, 120);
  EXPECT_EQ(values[0].evidence,
            "120 pairs at one radial speed: their density rises 4-fold at 1.500 m (1 % quantile 1.500, 5 % 1.500); 48 pairs beside "
            "it (up to twice, 48 in the first quarter), 0 within it; weak: few pairs beside it");
  // The edge is sharp (none below it, 48 at it): its interval reaches below it by 0.75 / 48 of it
  // (where the first of 48 pairs of a flat density could lie); but 48 pairs beside it are few (200
  // place it firmly): weak.
  EXPECT_DOUBLE_EQ(values[0].low, 1.5 * (1.0 - 0.75 / 48.0));
  EXPECT_DOUBLE_EQ(values[0].high, 1.5);
  EXPECT_TRUE(values[0].weak);
  EXPECT_EQ(values[1].field, "resolution.range_rate_cell_mps");
  EXPECT_DOUBLE_EQ(values[1].value.get<double>(), 0.25);
  EXPECT_EQ(values[1].support, 90);
  // No two detections share a range and radial speed: no beams of one cell, the azimuth cell is the base's.
  EXPECT_EQ(values[2].field, "resolution.azimuth_cell_deg");
  EXPECT_EQ(values[2].source, ValueSource::base);
  EXPECT_NE(values[2].evidence.find("not shown: among 60 detections, 0 pair(s) inside one range-Doppler cell at one elevation"),
            std::string::npos)
      << values[2].evidence;
  // Neighbours a cell apart lie 0.01 rad (0.57 deg) apart in azimuth: no twins, no leakage.
  EXPECT_EQ(values[3].field, "resolution.spectral_window");
  EXPECT_EQ(values[3].value, "none");
  EXPECT_EQ(values[3].evidence.substr(0, 40), "0.0 % of the detections have a twin one ");
  // Two histograms over 4 cells in 60 bins, the cell marked: the 1.5-m gaps (48) in the bin at 1.5 m.
  ASSERT_EQ(figures.size(), 2u);
  EXPECT_DOUBLE_EQ(figures[0].bin_width, 0.1);
  EXPECT_EQ(figures[0].counts[15], 48);
  EXPECT_DOUBLE_EQ(figures[0].marker, 1.5);
  EXPECT_DOUBLE_EQ(figures[1].marker, 0.25);
}

TEST(ProfileResolutionGaps, TwoBeamsOfOneCellDoNotCloseTheRangeRateGap) {
  // Every cycle adds a second detection in the cell (10 m, -1 m/s) at another azimuth, as an
  // imaging array's second beam: 3 pairs at the very same radial speed within half a range cell,
  // set aside; the cells stay.
  DetectionPool pool = lattice(3);
  for (PooledCycle& c : pool.cycles) {
    PooledDetection twin = c.detections.front();
    twin.azimuth_rad = 0.3;
    c.detections.push_back(twin);
    ++pool.detections;
  }
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_resolution(pool, nlohmann::json::object(), cells, figures);
  EXPECT_DOUBLE_EQ(cells.range_m, 1.5);
  EXPECT_DOUBLE_EQ(cells.range_rate_mps, 0.25);
  ASSERT_EQ(values.size(), 4u);
  // 3 pairs among 63 detections, 4.76 %, but fewer than the 20 a gap needs: the base's.
  EXPECT_EQ(values[2].source, ValueSource::base);
  EXPECT_NE(values[2].evidence.find("not shown: among 63 detections, 3 pair(s) inside one range-Doppler cell at one elevation (4.76 %"),
            std::string::npos)
      << values[2].evidence;
}

TEST(ProfileResolutionGaps, TwinsACellAwayAtOneAzimuthShowALeakingWindow) {
  // The lattice at one azimuth: 15 of each cycle's 20 detections have a twin one range-rate cell
  // further (j < 3), 16 one range cell further (i < 4): 75 % and 80 %, over the 5 % of a leak.
  DetectionPool pool = lattice(3);
  for (PooledCycle& c : pool.cycles) {
    for (PooledDetection& d : c.detections) d.azimuth_rad = 0.2;
  }
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_resolution(pool, nlohmann::json::object(), cells, figures);
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[3].source, ValueSource::derived);
  EXPECT_EQ(values[3].value, "hann");
  EXPECT_EQ(values[3].support, 60);
  EXPECT_NE(values[3].evidence.find("75.0 % of the detections have a twin one range-rate cell further at their range and azimuth, 80.0 % one range cell further"),
            std::string::npos)
      << values[3].evidence;
}

// An array that resolves azimuth: every cycle, the cell (10 m, -1 m/s) holds a second beam
// u = sin(az) 0.0175 (1.00 deg) further, at the same elevation: 30 same-cell pairs in 30 cycles,
// 4.8 % of the 630 detections, all asin(0.0175) = 1.003 deg apart: the azimuth cell is 1.0 deg. The
// second beam apart in elevation instead (0.02 in sin el) is counted apart and leaves the azimuth
// cell to the base.
TEST(ProfileResolutionGaps, BeamsOfOneCellAtOneElevationShowTheAzimuthCellAtTwoElevationsNot) {
  const auto with_twins = [](double du, double elevation_rad) {
    DetectionPool pool = lattice(30);
    for (PooledCycle& c : pool.cycles) {
      c.detections.front().elevation_rad = 0.0;
      PooledDetection twin = c.detections.front();
      twin.azimuth_rad = std::asin(std::sin(twin.azimuth_rad) + du);
      twin.elevation_rad = elevation_rad;
      c.detections.push_back(twin);
      ++pool.detections;
    }
    return pool;
  };
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> azimuth = derive_resolution(with_twins(0.0175, 0.0), nlohmann::json::object(), cells, figures);
  ASSERT_EQ(azimuth.size(), 4u);
  EXPECT_EQ(azimuth[2].source, ValueSource::derived) << azimuth[2].evidence;
  EXPECT_DOUBLE_EQ(azimuth[2].value.get<double>(), 1.0);
  EXPECT_EQ(azimuth[2].support, 30);
  EXPECT_NE(azimuth[2].evidence.find("30 pairs inside one range-Doppler cell at one elevation (4.8 % of the detections; 0 more at two elevations)"),
            std::string::npos)
      << azimuth[2].evidence;
  const std::vector<DerivedValue> elevation = derive_resolution(with_twins(0.0, std::asin(0.02)), nlohmann::json::object(), cells, figures);
  EXPECT_EQ(elevation[2].source, ValueSource::base);
  EXPECT_NE(elevation[2].evidence.find("0 pair(s) inside one range-Doppler cell at one elevation (0.00 %"), std::string::npos)
      << elevation[2].evidence;
  EXPECT_NE(elevation[2].evidence.find("30 at two elevations"), std::string::npos) << elevation[2].evidence;
}

TEST(ProfileResolutionGaps, ContinuousRadialSpeedsShowNoRangeRateCellItIsTheBases) {
  // 3 cycles of 200 detections at 40 ranges 1.5 m apart (a lattice: the range cell shows) whose
  // radial speeds are continuous over +-2 m/s (a radar that interpolates Doppler): the radial-speed distances of
  // pairs within half a range cell spread evenly from zero, as many within their 1 % quantile as
  // beside it. No gap: the base's 0.2 m/s, said why; the range cell stays derived.
  DetectionPool pool;
  std::uint64_t state = 48;
  for (int k = 0; k < 3; ++k) {
    PooledCycle& c = pool.cycles.emplace_back();
    for (int n = 0; n < 200; ++n) {
      PooledDetection d;
      d.range_m = 10.0 + 1.5 * (n % 40);
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // a seeded uniform draw
      d.range_rate_mps = -2.0 + 4.0 * static_cast<double>(state >> 11) / 9007199254740992.0;
      d.azimuth_rad = 0.001 * n;
      c.detections.push_back(d);
    }
    pool.detections += 200;
  }
  const nlohmann::json base = {{"resolution", {{"range_cell_m", 1.4}, {"range_rate_cell_mps", 0.2}}}};
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_resolution(pool, base, cells, figures);
  ASSERT_GE(values.size(), 2u);
  EXPECT_EQ(values[0].source, ValueSource::derived) << values[0].evidence;
  EXPECT_EQ(values[1].field, "resolution.range_rate_cell_mps");
  EXPECT_EQ(values[1].source, ValueSource::base) << values[1].evidence;
  EXPECT_NE(values[1].evidence.find("not shown by the pairs"), std::string::npos) << values[1].evidence;
  EXPECT_NE(values[1].evidence.find("the base's 0.2"), std::string::npos) << values[1].evidence;
  EXPECT_DOUBLE_EQ(cells.range_rate_mps, 0.2);
  EXPECT_EQ(values[0].source, ValueSource::derived) << values[0].evidence;
  EXPECT_DOUBLE_EQ(values[0].value.get<double>(), 1.5);
}

TEST(ProfileResolutionGaps, TooFewPairsLeaveBothCellsToTheBase) {
  // One cycle of 2 ranges by 4 rates: 4 pairs at one radial speed, fewer than the 20 a gap needs.
  DetectionPool pool;
  PooledCycle& c = pool.cycles.emplace_back();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 4; ++j) {
      PooledDetection d;
      d.range_m = 10.0 + 1.5 * i, d.range_rate_mps = 0.25 * j;
      c.detections.push_back(d);
    }
  }
  pool.detections = 8;
  Cells cells;
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_resolution(pool, nlohmann::json::object(), cells, figures);
  EXPECT_FALSE(cells.found);
  EXPECT_TRUE(figures.empty());
  ASSERT_EQ(values.size(), 2u);
  for (const DerivedValue& v : values) {
    EXPECT_EQ(v.source, ValueSource::base) << v.field;
    EXPECT_TRUE(v.value.is_null()) << v.field;
    EXPECT_EQ(v.evidence, "too few pairs of detections in one cycle at one radial speed (4) to show a gap");
  }
}

}  // namespace rcsim::replay::profile::resolution_gaps_test
