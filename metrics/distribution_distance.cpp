#include "metrics/distribution_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rcsim::metrics {

DistributionDistance distribution_distance(std::vector<double> a, std::vector<double> b) {
  DistributionDistance d;
  d.n_recorded = static_cast<int>(a.size());
  d.n_simulated = static_cast<int>(b.size());
  if (a.empty() || b.empty()) {
    d.wasserstein1 = d.kolmogorov_smirnov = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  // Sweep the merged sample points; between consecutive points both CDFs are constant.
  const double n_a = static_cast<double>(a.size()), n_b = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double x = std::min(a.front(), b.front());
  while (i < a.size() || j < b.size()) {
    const double next = j >= b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    const double gap = std::abs(static_cast<double>(i) / n_a - static_cast<double>(j) / n_b);
    d.wasserstein1 += gap * (next - x);  // ∫ |F_a − F_b| dx
    x = next;
    while (i < a.size() && a[i] == next) ++i;
    while (j < b.size() && b[j] == next) ++j;
    d.kolmogorov_smirnov = std::max(d.kolmogorov_smirnov,
                                     std::abs(static_cast<double>(i) / n_a - static_cast<double>(j) / n_b));
  }
  return d;
}

}  // namespace rcsim::metrics
