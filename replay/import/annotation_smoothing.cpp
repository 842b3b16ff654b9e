#include "replay/import/annotation_smoothing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace rcsim::replay {

std::vector<std::vector<LocalFit>> smooth_local_quadratic(const std::vector<double>& t_s,
                                                          const std::vector<const std::vector<double>*>& series,
                                                          double half_window_s) {
  const std::size_t n = t_s.size(), n_series = series.size();
  std::vector<std::vector<LocalFit>> fits(n_series, std::vector<LocalFit>(n));
  std::vector<Eigen::Vector3d> rhs(n_series);
  std::size_t first = 0, last = 0;  // the window [first, last)
  for (std::size_t i = 0; i < n; ++i) {
    while (t_s[i] - t_s[first] > half_window_s) ++first;
    last = std::max(last, i + 1);
    while (last < n && t_s[last] - t_s[i] <= half_window_s) ++last;
    const std::size_t count = last - first;
    const auto keep_sample = [&] {
      for (std::size_t k = 0; k < n_series; ++k) fits[k][i] = {(*series[k])[i], 0.0};
    };
    if (count == 1 || half_window_s <= 0.0) {
      keep_sample();
      continue;
    }
    // Weighted least squares in u = (t − t_i) / reach (scaled for conditioning).
    const int degree = count >= 4 ? 2 : 1;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    for (auto& r : rhs) r.setZero();
    // Tricube weights reach zero at the kernel's edge; put that edge a quarter beyond the farthest
    // sample of the window so that every sample in it counts.
    const double reach_s = 1.25 * std::max(t_s[i] - t_s[first], t_s[last - 1] - t_s[i]);
    for (std::size_t j = first; j < last; ++j) {
      const double u = (t_s[j] - t_s[i]) / reach_s;
      const double a = 1.0 - std::abs(u) * u * u;
      const double w = a * a * a;  // (1 − |u|³)³
      const Eigen::Vector3d basis(1.0, u, degree == 2 ? u * u : 0.0);
      normal.noalias() += w * basis * basis.transpose();
      for (std::size_t k = 0; k < n_series; ++k) rhs[k].noalias() += (w * (*series[k])[j]) * basis;
    }
    if (degree == 1) normal(2, 2) = 1.0;  // decouple the unused coefficient
    const Eigen::LDLT<Eigen::Matrix3d> solver(normal);
    for (std::size_t k = 0; k < n_series; ++k) {
      const Eigen::Vector3d beta = solver.solve(rhs[k]);
      fits[k][i] = beta.allFinite() ? LocalFit{beta(0), beta(1) / reach_s} : LocalFit{(*series[k])[i], 0.0};
    }
  }
  return fits;
}

std::vector<LocalFit> smooth_local_quadratic(const std::vector<double>& t_s, const std::vector<double>& y,
                                             double half_window_s) {
  return smooth_local_quadratic(t_s, std::vector<const std::vector<double>*>{&y}, half_window_s).front();
}

}  // namespace rcsim::replay
