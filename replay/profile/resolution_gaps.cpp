// The resolution cells from the gaps between pairs of detections of one sensor cycle
// (docs/sensor-profiles.md, aimotive_lrr: "pairs of detections at the same range: none closer in
// range rate", "pairs at the same azimuth and range rate"). A radar reports at most one detection
// per range-Doppler cell (paper III-C), so around every detection lies an empty rectangle of one
// range cell by one range-rate cell: pairs at one radial speed are at least a range cell apart in
// range, and pairs at one range at least a range-rate cell apart in radial speed.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/quantile.hpp"
#include "replay/profile/derivation_stages.hpp"

namespace rcsim::replay::profile {
namespace {

// "One radial speed" to begin with: finer than any radar's range-rate cell (0.08-0.5 m/s).
constexpr double kSameRangeRateMps = 0.02;
// The gap is the low quantile of the pairs' distances, not the least: a few near-duplicates
// (0.3 % on the aiMotive drive) do not close it.
constexpr double kGapQuantile = 0.01;
constexpr std::size_t kMinPairs = 20;
constexpr double kSameValue = 1e-6;
constexpr std::ptrdiff_t kEdgeContrast = 4;

// |d_other| of the pairs of one cycle with |d_key| < key_window, over all cycles.
template <class Key, class Other>
std::vector<double> pair_gaps(const DetectionPool& pool, Key key, Other other, double key_window) {
  std::vector<double> gaps;
  std::vector<const PooledDetection*> sorted;
  for (const PooledCycle& c : pool.cycles) {
    sorted.clear();
    for (const PooledDetection& d : c.detections) sorted.push_back(&d);
    std::sort(sorted.begin(), sorted.end(), [&](const auto* a, const auto* b) { return key(*a) < key(*b); });
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      for (std::size_t j = i + 1; j < sorted.size() && key(*sorted[j]) - key(*sorted[i]) < key_window; ++j) {
        gaps.push_back(std::abs(other(*sorted[j]) - other(*sorted[i])));
      }
    }
  }
  std::sort(gaps.begin(), gaps.end());
  return gaps;
}

// The gap's edge in ascending distances: the least distance b beyond which the pairs lie at least
// kEdgeContrast times as densely (in [b, 1.5 b)) as in the half below it ([b/2, b)), with at least
// kMinPairs (and 0.1 % of the pairs) beyond. A radar's few near-duplicates inside the cell (0.3 % of the aiMotive radar's
// detections) then do not close the gap, as they do a low quantile where pairs are sparse. Where
// no edge stands out among the lowest 5 % (pairs so dense that their count rises smoothly), the
// 1 % quantile.
struct Gap {
  double distance = 0.0;
  bool edge = false;
};
Gap gap_edge(const std::vector<double>& sorted) {
  const auto first = std::upper_bound(sorted.begin(), sorted.end(), kSameValue);
  const double scan_end = quantile_of_sorted(sorted, 0.05);
  // Beyond the edge at least 1 pair in 1000: a dense scene's few pairs at the CSV's last decimal
  // are no edge.
  const auto min_above = std::max<std::ptrdiff_t>(kMinPairs, static_cast<std::ptrdiff_t>(sorted.size() / 1000));
  for (auto it = first; it != sorted.end() && *it <= scan_end; ++it) {
    const double b = *it;
    const auto above = std::lower_bound(it, sorted.end(), 1.5 * b) - it;
    const auto below = it - std::lower_bound(first, it, 0.5 * b);
    if (above >= min_above && above >= kEdgeContrast * std::max<std::ptrdiff_t>(below, 1)) return {b, true};
  }
  return {quantile_of_sorted(sorted, kGapQuantile), false};
}

}  // namespace

std::vector<DerivedValue> derive_resolution(const DetectionPool& pool, Cells& cells, std::vector<DerivationFigure>& figures) {
  // Two rounds: the range cell from pairs at one radial speed, the range-rate cell from pairs
  // within half that range cell, the range cell again from pairs within a quarter of the range-rate
  // cell.
  std::vector<double> range_gaps = pair_gaps(pool, range_rate_of, range_of, kSameRangeRateMps);
  std::vector<double> range_rate_gaps;
  std::ptrdiff_t same_cell_pairs = 0;
  std::pair<bool, bool> edges;
  for (int round = 0; round < 2 && range_gaps.size() >= kMinPairs; ++round) {
    const Gap range_gap = gap_edge(range_gaps);
    const double range_m = range_gap.distance;
    std::vector<double> rate_gaps = pair_gaps(pool, range_of, range_rate_of, 0.5 * range_m);
    // Pairs at the very same radial speed within half a range cell are two beams of one cell (an
    // imaging array's); the range-rate cell is the gap beyond them.
    same_cell_pairs = std::upper_bound(rate_gaps.begin(), rate_gaps.end(), kSameValue) - rate_gaps.begin();
    rate_gaps.erase(rate_gaps.begin(), rate_gaps.begin() + same_cell_pairs);
    if (rate_gaps.size() < kMinPairs) break;
    const Gap range_rate_gap = gap_edge(rate_gaps);
    const double range_rate_mps = range_rate_gap.distance;
    if (!(range_m > 0.0 && range_rate_mps > 0.0)) break;
    cells = {range_m, range_rate_mps, true};
    edges = {range_gap.edge, range_rate_gap.edge};
    range_rate_gaps = std::move(rate_gaps);
    if (round == 0) range_gaps = pair_gaps(pool, range_rate_of, range_of, 0.25 * cells.range_rate_mps);
  }
  if (!cells.found) {
    const std::string why = fmt::format("too few pairs of detections in one cycle at one radial speed ({}) to show a gap", range_gaps.size());
    return {{"resolution.range_cell_m", nullptr, ValueSource::base, why, 0},
            {"resolution.range_rate_cell_mps", nullptr, ValueSource::base, why, 0}};
  }
  const auto described = [](const std::vector<double>& gaps, double gap, bool edge, const char* unit, const char* pairs) {
    return fmt::format("{} pairs {}: {} {:.3f} {} (1 % quantile {:.3f}, 5 % {:.3f})", gaps.size(), pairs,
                       edge ? "their density rises 4-fold at" : "no edge stands out; their 1 % quantile", gap, unit,
                       quantile_of_sorted(gaps, kGapQuantile), quantile_of_sorted(gaps, 0.05));
  };
  std::vector<DerivedValue> values{
      {"resolution.range_cell_m", round_to(cells.range_m, cells.range_m < 0.5 ? 0.001 : 0.01), ValueSource::derived,
       described(range_gaps, cells.range_m, edges.first, "m", "at one radial speed"), static_cast<long long>(range_gaps.size())},
      {"resolution.range_rate_cell_mps", round_to(cells.range_rate_mps, 0.001), ValueSource::derived,
       described(range_rate_gaps, cells.range_rate_mps, edges.second, "m/s", "within half a range cell"), static_cast<long long>(range_rate_gaps.size())}};
  figures.push_back(histogram_figure("Range distances of pairs at one radial speed", "range distance / m", range_gaps, 4.0 * cells.range_m,
                                     60, cells.range_m, "range cell"));
  figures.push_back(histogram_figure("Radial-speed distances of pairs within half a range cell", "radial-speed distance / (m/s)",
                                     range_rate_gaps, 4.0 * cells.range_rate_mps, 60, cells.range_rate_mps, "range-rate cell"));
  values.push_back({"resolution.azimuth_cell_deg", nullptr, ValueSource::base,
                    fmt::format("not shown: {} pair(s) at one radial speed within half a range cell (two beams of one "
                                "range-Doppler cell) among {} detections; their azimuth gap would be the beam's width",
                                same_cell_pairs, pool.detections),
                    0});
  return values;
}

}  // namespace rcsim::replay::profile
