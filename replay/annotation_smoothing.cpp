#include "replay/annotation_smoothing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace rcsim::replay {

std::vector<LocalFit> smooth_local_quadratic(const std::vector<double>& t_s, const std::vector<double>& y,
                                             double half_window_s) {
  const std::size_t n = t_s.size();
  std::vector<LocalFit> fits(n);
  std::size_t first = 0, last = 0;  // the window [first, last)
  for (std::size_t i = 0; i < n; ++i) {
    while (t_s[i] - t_s[first] > half_window_s) ++first;
    last = std::max(last, i + 1);
    while (last < n && t_s[last] - t_s[i] <= half_window_s) ++last;
    const std::size_t count = last - first;
    if (count == 1 || half_window_s <= 0.0) {
      fits[i] = {y[i], 0.0};
      continue;
    }
    // Weighted least squares in τ = t − t_i (scaled by the window for conditioning).
    const int degree = count >= 4 ? 2 : 1;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    // Tricube weights reach zero at the kernel's edge; put that edge a quarter beyond the farthest
    // sample of the window so that every sample in it counts.
    const double reach_s = 1.25 * std::max(t_s[i] - t_s[first], t_s[last - 1] - t_s[i]);
    for (std::size_t j = first; j < last; ++j) {
      const double u = (t_s[j] - t_s[i]) / reach_s;
      const double w = std::pow(1.0 - std::pow(std::abs(u), 3), 3);
      const Eigen::Vector3d basis(1.0, u, degree == 2 ? u * u : 0.0);
      normal += w * basis * basis.transpose();
      rhs += w * basis * y[j];
    }
    if (degree == 1) normal(2, 2) = 1.0;  // decouple the unused coefficient
    const Eigen::Vector3d beta = normal.ldlt().solve(rhs);
    if (!beta.allFinite()) {
      fits[i] = {y[i], 0.0};
      continue;
    }
    fits[i] = {beta(0), beta(1) / reach_s};
  }
  return fits;
}

}  // namespace rcsim::replay
