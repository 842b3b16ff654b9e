#pragma once
// Quantiles, once: linear interpolation between order statistics (Hyndman & Fan type 7, as
// numpy's default), so that the median of {1, 2} is 1.5.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace rcsim {

// The q-quantile (0 <= q <= 1, clamped) of ascending values; NaN for none.
inline double quantile_of_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::nan("");
  const double h = std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

// The same of values in any order.
inline double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return quantile_of_sorted(values, q);
}

inline double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

}  // namespace rcsim
