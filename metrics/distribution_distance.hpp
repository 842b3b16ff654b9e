#pragma once
// Distances between two empirical distributions (recorded against simulated samples of one
// quantity over a run):
// - the area metric (Ferson, Oberkampf, Ginzburg, "Model validation and predictive capability
//   for the thermal challenge problem", CMAME 197, 2008): the area between the two empirical
//   CDFs, which equals the Wasserstein-1 distance; in the unit of the quantity;
// - the two-sample Kolmogorov–Smirnov statistic: the largest vertical gap between the CDFs, in
//   [0, 1].
// Both are NaN when either sample is empty (no distance can be said).
#include <vector>

namespace rcsim::metrics {

struct DistributionDistance {
  double wasserstein1 = 0.0;
  double kolmogorov_smirnov = 0.0;
  int n_recorded = 0, n_simulated = 0;
  // Zero when computed from the samples; otherwise how far the approximation (sample_summary.hpp)
  // may be from the exact figure, at most.
  double wasserstein1_bound = 0.0, kolmogorov_smirnov_bound = 0.0;
};

// Takes the samples by value: they are sorted.
DistributionDistance distribution_distance(std::vector<double> recorded, std::vector<double> simulated);

}  // namespace rcsim::metrics
