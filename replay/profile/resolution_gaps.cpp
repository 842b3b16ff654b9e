// The resolution cells from the gaps between pairs of detections of one sensor cycle
// (docs/sensor-profiles.md, aimotive_lrr: "pairs of detections at the same range: none closer in
// range rate", "pairs at the same azimuth and range rate"). A radar reports at most one detection
// per range-Doppler cell (paper III-C), so around every detection lies an empty rectangle of one
// range cell by one range-rate cell: pairs at one radial speed are at least a range cell apart in
// range, and pairs at one range at least a range-rate cell apart in radial speed.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "common/angles.hpp"
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

// Distances between pairs of detections, of which only the low tail is read: the gap's edge
// (scanned up to the 5 % quantile, counting up to 1.5 times it), the 1 % and 5 % quantiles, and a
// histogram up to 4 times the gap. `sorted` holds every distance up to a cut beyond all of those,
// `total` counts them all: 400 Astyx frames have 10^8 pairs at one radial speed, held whole 1.3 GB.
struct Distances {
  std::vector<double> sorted;
  std::size_t total = 0;
  std::size_t size() const { return total; }
  // The q quantile of all of them (q up to 5 %: within `sorted`).
  double quantile(double q) const {
    if (total == 0) return std::nan("");
    const double h = std::clamp(q, 0.0, 1.0) * static_cast<double>(total - 1);
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
    return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
  }
};

// Sorts distances (non-negative, not NaN) as std::sort would, in linear time: a non-negative
// double's bits, read as an unsigned integer, order as its value, so a least-significant-digit
// radix sort of the bits (11 bits a pass, a pass skipped where every value shares its digit)
// gives the same order. 400 Astyx frames keep 6.4 million pairs' distances a pass; std::sort was
// a quarter of derive's time.
void sort_distances(std::vector<double>& values) {
  constexpr int kDigitBits = 11;
  constexpr std::size_t kDigits = std::size_t{1} << kDigitBits;
  if (values.size() < 4096) {
    std::sort(values.begin(), values.end());
    return;
  }
  std::vector<double> buffer(values.size());
  std::vector<std::size_t> counts(kDigits);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    const auto digit = [shift](double v) { return (std::bit_cast<std::uint64_t>(v) >> shift) & (kDigits - 1); };
    std::fill(counts.begin(), counts.end(), 0);
    for (const double v : values) ++counts[digit(v)];
    if (std::find(counts.begin(), counts.end(), values.size()) != counts.end()) continue;  // one digit: order kept
    std::size_t at = 0;
    for (std::size_t& c : counts) at += std::exchange(c, at);
    for (const double v : values) buffer[counts[digit(v)]++] = v;
    values.swap(buffer);
  }
}

// The pairs' distances as a histogram of their logarithms (1/64 of an octave a bin): where the
// low tail ends, to a bin. The bins a flat array over every finite double's (a map's node per
// bin cost a tree walk per pair: 10^8 pairs on 400 Astyx frames).
class OctaveHistogram {
 public:
  OctaveHistogram() : counts_(static_cast<std::size_t>(kBins), 0) {}
  void add(double v) {
    ++total_;
    if (v > 0.0) ++counts_[index_of(static_cast<int>(std::floor(std::log2(v) * kBinsPerOctave)))];
  }
  // An upper bound of the value of rank k (from 0, in ascending order) of those added.
  double upper_bound_of_rank(std::size_t k) const {
    std::size_t below = zeros();
    if (k < below) return 0.0;
    for (int i = 0; i < kBins; ++i) {
      below += counts_[static_cast<std::size_t>(i)];
      if (k < below) return std::exp2(static_cast<double>(i - kOffset + 1) / kBinsPerOctave);
    }
    return std::numeric_limits<double>::infinity();
  }
  // How many were added up to x (an upper bound: x's bin counted whole).
  std::size_t at_most(double x) const {
    if (!(x > 0.0)) return zeros();
    if (std::isinf(x)) return total_;
    const std::size_t last = index_of(static_cast<int>(std::floor(std::log2(x) * kBinsPerOctave)));
    std::size_t n = zeros();
    for (std::size_t i = 0; i <= last; ++i) n += counts_[i];
    return n;
  }
  std::size_t total() const { return total_; }
  // The distances of 0 (two detections at one value: beams of one cell, a written value's last decimal).
  std::size_t zeros() const {
    std::size_t zeros = total_;
    for (const std::size_t n : counts_) zeros -= n;
    return zeros;
  }

 private:
  static constexpr double kBinsPerOctave = 64.0;
  // log2 of a positive finite double lies in [-1075, 1024].
  static constexpr int kOffset = 1075 * 64, kBins = (1075 + 1025) * 64;
  static std::size_t index_of(int bin) { return static_cast<std::size_t>(std::clamp(bin + kOffset, 0, kBins - 1)); }
  std::vector<std::size_t> counts_;
  std::size_t total_ = 0;
};

// |d_other| of the pairs of one cycle with |d_key| < key_window, over all cycles, those of
// |d_other| <= drop_at_most left out: two passes, the first for where the low tail ends, the
// second keeping it (up to 4 times an upper bound of the 5 % quantile's neighbours).
template <class Key, class Other>
Distances pair_gaps(const DetectionPool& pool, Key key, Other other, double key_window, double drop_at_most = -1.0) {
  // Each cycle's (key, other) by key, once for both passes, side by side in memory: the pairs'
  // loop (10^8 pairs on 400 Astyx frames) reads two arrays instead of following pointers.
  std::vector<std::size_t> starts{0};
  std::vector<double> keys, others;
  {
    std::vector<std::pair<double, double>> cycle;
    for (const PooledCycle& c : pool.cycles) {
      cycle.clear();
      for (const PooledDetection& d : c.detections) cycle.emplace_back(key(d), other(d));
      std::sort(cycle.begin(), cycle.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [k, o] : cycle) keys.push_back(k), others.push_back(o);
      starts.push_back(keys.size());
    }
  }
  const auto for_each_gap = [&](const auto& visit) {
    for (std::size_t c = 0; c + 1 < starts.size(); ++c) {
      const std::size_t end = starts[c + 1];
      for (std::size_t i = starts[c]; i < end; ++i) {
        const double key_i = keys[i], other_i = others[i];
        for (std::size_t j = i + 1; j < end && keys[j] - key_i < key_window; ++j) {
          const double gap = std::abs(others[j] - other_i);
          if (gap > drop_at_most) visit(gap);
        }
      }
    }
  };
  OctaveHistogram histogram;
  for_each_gap([&](double gap) { histogram.add(gap); });
  Distances gaps;
  gaps.total = histogram.total();
  if (gaps.total == 0) return gaps;
  // The 5 % quantile of the distances above 0: where many pairs lie at one value (an imaging
  // array's beams of one cell at one range), the low tail read lies beyond them.
  const std::size_t zeros = histogram.zeros(), nonzero = gaps.total - zeros;
  const auto rank_5 = zeros + static_cast<std::size_t>(std::floor(0.05 * static_cast<double>(nonzero > 0 ? nonzero - 1 : 0))) + 1;
  const double cut = 4.0 * histogram.upper_bound_of_rank(std::min(rank_5, gaps.total - 1));
  gaps.sorted.reserve(histogram.at_most(cut));  // not twice what is kept, as growing by doubling
  for_each_gap([&](double gap) {
    if (gap <= cut) gaps.sorted.push_back(gap);
  });
  sort_distances(gaps.sorted);
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
  // The interval from the evidence: an edge's, from where the density first rises half as sharply
  // (2-fold, half the pairs beyond) to where it rises twice as sharply (8-fold); no edge: the 0.5 %
  // to 2 % quantiles.
  double low = 0.0, high = 0.0;
  // Pairs just beyond it ([b, 2 b)) and just within it ((0, b), the same value apart): a cell the
  // pairs leave no emptier within than beside is not shown by them (continuous Doppler: the 1 %
  // quantile of a smooth spread).
  std::ptrdiff_t beside = 0, within = 0, near = 0;
  bool supported() const { return distance > 0.0 && beside >= static_cast<std::ptrdiff_t>(kMinPairs) && beside >= kEdgeContrast * within; }
  // Shown, but barely: no edge, too few pairs beside it to place it, or a wide interval.
  // Few pairs in the first quarter beyond the edge: the density rises beyond it rather than at it
  // (a sparse scene's pairs), so the cell may lie well below (a sparse road read 1.19 m for 1.0
  // with 15 of 202 there).
  bool weak() const { return !edge || beside < kWeakBeside || near < kWeakNear || high - low > kWeakSpread * distance; }
  static constexpr std::ptrdiff_t kWeakBeside = 200, kWeakNear = 30;
  static constexpr double kWeakSpread = 0.2;
};
Gap gap_edge(const Distances& distances) {
  const std::vector<double>& sorted = distances.sorted;
  const auto first = std::upper_bound(sorted.begin(), sorted.end(), kSameValue);
  // Quantiles of the distances above the same value (pairs at one value are beams of one cell).
  const auto same = static_cast<std::size_t>(first - sorted.begin());
  const auto above_same = [&](double q) {
    if (first == sorted.end()) return distances.quantile(q);
    const double h = static_cast<double>(same) + q * static_cast<double>(distances.size() - same - 1);
    const auto lo = std::min(static_cast<std::size_t>(std::floor(h)), sorted.size() - 1);
    const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
    return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
  };
  const double scan_end = above_same(0.05);
  // Beyond the edge at least 1 pair in 1000: a dense scene's few pairs at the CSV's last decimal
  // are no edge.
  const auto min_above = std::max<std::ptrdiff_t>(kMinPairs, static_cast<std::ptrdiff_t>(distances.size() / 1000));
  // The first b at which the pairs in [b, 1.5 b) are `contrast` times those in [b/2, b), with at
  // least `least` beyond; the end of the scan where none.
  const auto first_rise = [&](double contrast, std::ptrdiff_t least, std::vector<double>::const_iterator from) -> std::optional<double> {
    for (auto it = from; it != sorted.end() && *it <= scan_end; ++it) {
      const double b = *it;
      const auto above = std::lower_bound(it, sorted.end(), 1.5 * b) - it;
      const auto below = it - std::lower_bound(first, it, 0.5 * b);
      if (above >= least && static_cast<double>(above) >= contrast * static_cast<double>(std::max<std::ptrdiff_t>(below, 1))) return b;
    }
    return std::nullopt;
  };
  Gap gap;
  if (const auto b = first_rise(kEdgeContrast, min_above, first)) {
    gap.distance = *b, gap.edge = true;
    gap.low = first_rise(0.5 * kEdgeContrast, std::max<std::ptrdiff_t>(1, min_above / 2), first).value_or(*b);
    const auto at_b = std::lower_bound(first, sorted.end(), *b);
    gap.high = first_rise(2.0 * kEdgeContrast, min_above, at_b).value_or(scan_end);
  } else {
    gap.distance = above_same(kGapQuantile);
    gap.low = above_same(0.005), gap.high = above_same(0.02);
  }
  // Where the pairs beyond the edge are few, the cell may lie below the first of them: with n pairs
  // in its first quarter beyond ([b, 1.25 b)), an empty stretch of 3 / (their density), 0.75 b / n,
  // below b is as likely as 5 % (order statistics of a flat density).
  gap.near = std::lower_bound(sorted.begin(), sorted.end(), 1.25 * gap.distance) - std::lower_bound(sorted.begin(), sorted.end(), gap.distance);
  if (gap.edge) gap.low = std::min(gap.low, gap.distance * (1.0 - 0.75 / static_cast<double>(std::max<std::ptrdiff_t>(gap.near, 1))));
  gap.low = std::max(0.0, std::min(gap.low, gap.distance)), gap.high = std::max(gap.high, gap.distance);
  gap.beside = std::lower_bound(sorted.begin(), sorted.end(), 2.0 * gap.distance) - std::lower_bound(sorted.begin(), sorted.end(), gap.distance);
  gap.within = std::lower_bound(first, sorted.end(), gap.distance) - first;
  return gap;
}

// The pairs of one cycle inside one range-Doppler cell (the very same radial speed, within half a
// range cell), as two beams of one cell: apart in azimuth at one elevation, the distance of their
// azimuth sines (u, direction cosine across the array: equal beams in u, not in angle), or apart
// in elevation (an array that resolves elevation, as the Astyx HiRes: almost all its pairs).
struct SameCellPairs {
  Distances azimuth_gaps_rad;  // asin(|du|), all of them
  std::size_t elevation_pairs = 0;
};
constexpr double kSameElevationSine = 0.005;  // 0.3 deg: the Astyx array's finest elevation step

SameCellPairs same_cell_pairs(const DetectionPool& pool, double range_cell_m) {
  SameCellPairs pairs;
  std::vector<const PooledDetection*> sorted;
  const auto elevation_of = [](const PooledDetection& d) { return std::isfinite(d.elevation_rad) ? d.elevation_rad : 0.0; };  // none: 0
  for (const PooledCycle& c : pool.cycles) {
    sorted.clear();
    for (const PooledDetection& d : c.detections) sorted.push_back(&d);
    std::sort(sorted.begin(), sorted.end(), [](const auto* a, const auto* b) { return a->range_m < b->range_m; });
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      for (std::size_t j = i + 1; j < sorted.size() && sorted[j]->range_m - sorted[i]->range_m < 0.5 * range_cell_m; ++j) {
        const PooledDetection &a = *sorted[i], &b = *sorted[j];
        if (std::abs(a.range_rate_mps - b.range_rate_mps) > kSameValue) continue;
        const double el_a = elevation_of(a), el_b = elevation_of(b);
        if (std::abs(std::sin(el_a) - std::sin(el_b)) >= kSameElevationSine) {
          ++pairs.elevation_pairs;
          continue;
        }
        const double du = std::abs(std::sin(a.azimuth_rad) * std::cos(el_a) - std::sin(b.azimuth_rad) * std::cos(el_b));
        if (du > kSameValue) pairs.azimuth_gaps_rad.sorted.push_back(std::asin(std::min(1.0, du)));
      }
    }
  }
  sort_distances(pairs.azimuth_gaps_rad.sorted);
  pairs.azimuth_gaps_rad.total = pairs.azimuth_gaps_rad.sorted.size();
  return pairs;
}

// The pairs' distances over [0, hi) in 60 bins, all beyond in the last (those not held lie beyond
// hi: the cut is at least 4 times the 5 % quantile, hi at most 4 times the gap below it).
DerivationFigure distances_figure(std::string title, std::string x_label, const Distances& d, double hi, double marker,
                                  std::string marker_label) {
  DerivationFigure f = histogram_figure(std::move(title), std::move(x_label), d.sorted, hi, 60, marker, std::move(marker_label));
  f.counts.back() += static_cast<long long>(d.total - d.sorted.size());
  return f;
}

// A radar that resolves azimuth reports two beams of one range-Doppler cell often: at least this
// share of its detections (the aiMotive radar's near-duplicates are 0.3 %).
constexpr double kMinSameCellShare = 0.01;

// The azimuth cell: the edge of the azimuth distances of same-cell pairs at one elevation, where
// they are enough to show an array that resolves azimuth; else the base's.
DerivedValue azimuth_cell(const DetectionPool& pool, const Cells& cells, std::vector<DerivationFigure>& figures) {
  const SameCellPairs pairs = same_cell_pairs(pool, cells.range_m);
  const Distances& gaps = pairs.azimuth_gaps_rad;
  const double share = pool.detections > 0 ? static_cast<double>(gaps.size()) / static_cast<double>(pool.detections) : 0.0;
  const Gap gap = gaps.size() >= kMinPairs ? gap_edge(gaps) : Gap{};
  if (share < kMinSameCellShare || !(gap.distance > 0.0)) {
    return {"resolution.azimuth_cell_deg", nullptr, ValueSource::base,
            fmt::format("not shown: among {} detections, {} pair(s) inside one range-Doppler cell at one elevation ({:.2f} %; an "
                        "array that resolves azimuth: at least {:.0f} %, their azimuth distance its beam), {} at two elevations",
                        pool.detections, gaps.size(), 100.0 * share, 100.0 * kMinSameCellShare, pairs.elevation_pairs),
            static_cast<long long>(gaps.size())};
  }
  const double cell_deg = rad_to_deg(gap.distance);
  figures.push_back(distances_figure("Azimuth distances of pairs inside one range-Doppler cell, at one elevation", "asin(|du|) / rad",
                                     gaps, 4.0 * gap.distance, gap.distance, "azimuth cell"));
  return with_interval({"resolution.azimuth_cell_deg", round_to(cell_deg, 0.1), ValueSource::derived,
          fmt::format("{} pairs inside one range-Doppler cell at one elevation ({:.1f} % of the detections; {} more at two "
                      "elevations): {} {:.2f} deg (1 % quantile {:.2f}, 5 % {:.2f})",
                      gaps.size(), 100.0 * share, pairs.elevation_pairs,
                      gap.edge ? "their density rises 4-fold at" : "no edge stands out; their 1 % quantile", cell_deg,
                      rad_to_deg(gaps.quantile(kGapQuantile)), rad_to_deg(gaps.quantile(0.05))),
          static_cast<long long>(gaps.size())}, rad_to_deg(gap.low), rad_to_deg(gap.high), gap.weak());
}

// A radar whose FFT windows leak (resolution.spectral_window) reports a strong return again one
// cell away, at its angle: at least this share of the detections has such a twin (the Astyx HiRes
// 29 %, the aiMotive radar under 0.1 %: its peak search drops them).
constexpr double kMinLeakageTwinShare = 0.05;
constexpr double kSameAngleRad = 0.5 * kPi / 180.0;

// The share of detections with a twin one range-rate cell further at one range (within a quarter
// cell) and one azimuth (within 0.5 deg); one range cell further at one radial speed, for the evidence.
DerivedValue spectral_window(const DetectionPool& pool, const Cells& cells) {
  long long rate_twins = 0, range_twins = 0;
  std::vector<const PooledDetection*> sorted;
  for (const PooledCycle& c : pool.cycles) {
    sorted.clear();
    for (const PooledDetection& d : c.detections) sorted.push_back(&d);
    std::sort(sorted.begin(), sorted.end(), [](const auto* a, const auto* b) { return a->range_m < b->range_m; });
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const PooledDetection& a = *sorted[i];
      bool rate_twin = false, range_twin = false;
      // From a quarter cell nearer to a cell and a quarter further: the twin one cell up in range
      // rate (at about its range) or in range.
      std::size_t j = i;
      while (j > 0 && a.range_m - sorted[j - 1]->range_m < 0.25 * cells.range_m) --j;
      for (; j < sorted.size() && sorted[j]->range_m - a.range_m < 1.25 * cells.range_m; ++j) {
        const PooledDetection& b = *sorted[j];
        if (j == i || std::abs(angle_difference_rad(a.azimuth_rad, b.azimuth_rad)) > kSameAngleRad) continue;
        const double dr_cells = (b.range_m - a.range_m) / cells.range_m;
        const double dv_cells = (b.range_rate_mps - a.range_rate_mps) / cells.range_rate_mps;
        rate_twin = rate_twin || (std::abs(dr_cells) < 0.25 && std::abs(dv_cells - 1.0) < 0.25);
        range_twin = range_twin || (std::abs(dr_cells - 1.0) < 0.25 && std::abs(dv_cells) < 0.25);
      }
      rate_twins += rate_twin ? 1 : 0;
      range_twins += range_twin ? 1 : 0;
    }
  }
  const double n = std::max<double>(1.0, static_cast<double>(pool.detections));
  const double rate_share = static_cast<double>(rate_twins) / n, range_share = static_cast<double>(range_twins) / n;
  const bool leaks = rate_share >= kMinLeakageTwinShare;
  return {"resolution.spectral_window", leaks ? "hann" : "none", ValueSource::derived,
          fmt::format("{:.1f} % of the detections have a twin one range-rate cell further at their range and azimuth, {:.1f} % one "
                      "range cell further at their radial speed ({} {:.0f} %: {})",
                      100.0 * rate_share, 100.0 * range_share, leaks ? "at least" : "under", 100.0 * kMinLeakageTwinShare,
                      leaks ? "the FFTs' window leaks, taken as Hann" : "no leakage reported"),
          pool.detections};
}

}  // namespace

std::vector<DerivedValue> derive_resolution(const DetectionPool& pool, const nlohmann::json& base, Cells& cells,
                                           std::vector<DerivationFigure>& figures) {
  // Two rounds: the range cell from pairs at one radial speed, the range-rate cell from pairs
  // within half that range cell, the range cell again from pairs within a quarter of the range-rate
  // cell (where that one is shown).
  const auto base_cell = [&](const char* pointer) {
    const auto p = nlohmann::json::json_pointer(pointer);
    return base.contains(p) ? base.at(p).get<double>() : 0.0;
  };
  const double base_range_m = base_cell("/resolution/range_cell_m"), base_range_rate_mps = base_cell("/resolution/range_rate_cell_mps");
  Distances range_gaps = pair_gaps(pool, range_rate_of, range_of, kSameRangeRateMps);
  Distances range_rate_gaps;
  Gap range_gap, range_rate_gap;
  bool read = false;
  for (int round = 0; round < 2 && range_gaps.size() >= kMinPairs; ++round) {
    const Gap this_range_gap = gap_edge(range_gaps);
    // Pairs at the very same radial speed within half a range cell are two beams of one cell (an
    // imaging array's); the range-rate cell is the gap beyond them.
    // A range cell the pairs do not show: the pairs within half the base's (where it has one).
    const double window_m = this_range_gap.supported() || !(base_range_m > 0.0) ? this_range_gap.distance : base_range_m;
    Distances rate_gaps = pair_gaps(pool, range_of, range_rate_of, 0.5 * window_m, kSameValue);
    if (rate_gaps.size() < kMinPairs) break;
    const Gap this_rate_gap = gap_edge(rate_gaps);
    if (!(this_range_gap.distance > 0.0 && this_rate_gap.distance > 0.0)) break;
    range_gap = this_range_gap, range_rate_gap = this_rate_gap, read = true;
    range_rate_gaps = std::move(rate_gaps);
    if (round == 0 && range_rate_gap.supported()) {
      // The first round's distances let go first (not both held: 50 MB each on 400 Astyx
      // frames), taken again in the rare case the second round has too few pairs.
      range_gaps = Distances{};
      Distances again = pair_gaps(pool, range_rate_of, range_of, 0.25 * range_rate_gap.distance);
      if (again.size() < kMinPairs) {
        range_gaps = pair_gaps(pool, range_rate_of, range_of, kSameRangeRateMps);
        break;
      }
      range_gaps = std::move(again);
    } else {
      break;
    }
  }
  if (!read) {
    const std::string why = fmt::format("too few pairs of detections in one cycle at one radial speed ({}) to show a gap", range_gaps.size());
    cells = {base_range_m, base_range_rate_mps, false};
    std::vector<DerivedValue> values{{"resolution.range_cell_m", nullptr, ValueSource::base, why, 0},
                                     {"resolution.range_rate_cell_mps", nullptr, ValueSource::base, why, 0}};
    if (base_range_m > 0.0 && base_range_rate_mps > 0.0) {
      values.push_back(azimuth_cell(pool, cells, figures));
      values.push_back(spectral_window(pool, cells));
    }
    return values;
  }
  const auto described = [](const Distances& gaps, const Gap& gap, const char* unit, const char* pairs) {
    return fmt::format("{} pairs {}: {} {:.3f} {} (1 % quantile {:.3f}, 5 % {:.3f}); {} pairs beside it (up to twice, {} in the first "
                       "quarter), {} within it{}",
                       gaps.size(), pairs, gap.edge ? "their density rises 4-fold at" : "no edge stands out; their 1 % quantile",
                       gap.distance, unit, gaps.quantile(kGapQuantile), gaps.quantile(0.05), gap.beside, gap.near, gap.within,
                       gap.weak() ? fmt::format("; weak: {}", !gap.edge                       ? "no edge, a quantile"
                                                              : gap.beside < Gap::kWeakBeside ? "few pairs beside it"
                                                              : gap.near < Gap::kWeakNear     ? "few pairs at its edge"
                                                                                              : "its edge rises slowly (a wide interval)")
                                  : "");
  };
  // A cell the pairs do not show (no emptier within than beside it: continuous values, a smooth
  // spread) is not derived: the base's, said why.
  const auto unsupported = [](const Gap& gap, const char* unit, double base_value) {
    return fmt::format("not shown by the pairs: {} within {:.4f} {} and {} beside it (up to twice) - no gap, as from continuous values "
                       "or too few pairs (a cell needs {} beside and {} times as many as within); the base's {:g}",
                       gap.within, gap.distance, unit, gap.beside, kMinPairs, kEdgeContrast, base_value);
  };
  std::vector<DerivedValue> values;
  const long long range_support = static_cast<long long>(range_gaps.size());
  const long long rate_support = static_cast<long long>(range_rate_gaps.size());
  if (!range_gap.supported()) {
    // The range-rate pairs were chosen within half the base's range cell.
    values.push_back({"resolution.range_cell_m", nullptr, ValueSource::base, unsupported(range_gap, "m", base_range_m), range_support});
    cells = {base_range_m, base_range_rate_mps, false};
    if (range_rate_gap.supported() && base_range_m > 0.0) {
      cells.range_rate_mps = range_rate_gap.distance;
      values.push_back(with_interval({"resolution.range_rate_cell_mps", round_to(range_rate_gap.distance, 0.001), ValueSource::derived,
                                      described(range_rate_gaps, range_rate_gap, "m/s", "within half the base's range cell"), rate_support},
                                     range_rate_gap.low, range_rate_gap.high, range_rate_gap.weak()));
    } else {
      values.push_back({"resolution.range_rate_cell_mps", nullptr, ValueSource::base,
                        range_rate_gap.supported() ? "not shown: its pairs are those within half a range cell, which neither the pairs "
                                                     "nor the base show"
                                                   : unsupported(range_rate_gap, "m/s", base_range_rate_mps),
                        rate_support});
    }
  } else {
    cells = {range_gap.distance, range_rate_gap.supported() ? range_rate_gap.distance : base_range_rate_mps, true, range_gap.low,
             range_gap.high};
    const double range_step = range_gap.distance < 0.5 ? 0.001 : 0.01;
    values.push_back(with_interval({"resolution.range_cell_m", round_to(range_gap.distance, range_step), ValueSource::derived,
                                    described(range_gaps, range_gap, "m", "at one radial speed"), range_support},
                                   range_gap.low, range_gap.high, range_gap.weak()));
    if (range_rate_gap.supported()) {
      values.push_back(with_interval({"resolution.range_rate_cell_mps", round_to(range_rate_gap.distance, 0.001), ValueSource::derived,
                                      described(range_rate_gaps, range_rate_gap, "m/s", "within half a range cell"), rate_support},
                                     range_rate_gap.low, range_rate_gap.high, range_rate_gap.weak()));
    } else {
      values.push_back({"resolution.range_rate_cell_mps", nullptr, ValueSource::base,
                        unsupported(range_rate_gap, "m/s", base_range_rate_mps), rate_support});
    }
  }
  figures.push_back(distances_figure("Range distances of pairs at one radial speed", "range distance / m", range_gaps, 4.0 * range_gap.distance,
                                     range_gap.distance, range_gap.supported() ? "range cell" : "no gap (the base's cell)"));
  figures.push_back(distances_figure("Radial-speed distances of pairs within half a range cell", "radial-speed distance / (m/s)",
                                     range_rate_gaps, 4.0 * range_rate_gap.distance, range_rate_gap.distance,
                                     range_rate_gap.supported() ? "range-rate cell" : "no gap (the base's cell)"));
  if (cells.range_m > 0.0 && cells.range_rate_mps > 0.0) {
    values.push_back(azimuth_cell(pool, cells, figures));
    values.push_back(spectral_window(pool, cells));
  }
  return values;
}

}  // namespace rcsim::replay::profile
