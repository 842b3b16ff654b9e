#include "replay/import/annotation_smoothing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <stdexcept>
#include <cmath>

namespace rcsim::replay {

void fit_local_quadratic(std::span<const double> t_s, std::span<const double* const> series, std::size_t i,
                         std::size_t first, std::size_t last, double half_window_s, std::span<LocalFit> fits) {
  const std::size_t n_series = series.size(), count = last - first;
  if (count == 1 || half_window_s <= 0.0) {
    for (std::size_t k = 0; k < n_series; ++k) fits[k] = {series[k][i], 0.0};
    return;
  }
  // Weighted least squares in u = (t − t_i) / reach (scaled for conditioning).
  const int degree = count >= 4 ? 2 : 1;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  constexpr std::size_t kMaxSeries = 8;
  if (n_series > kMaxSeries || fits.size() < n_series) throw std::invalid_argument("fit_local_quadratic: too many series");
  std::array<Eigen::Vector3d, kMaxSeries> rhs;
  for (std::size_t k = 0; k < n_series; ++k) rhs[k].setZero();
  // Tricube weights reach zero at the kernel's edge; put that edge a quarter beyond the farthest
  // sample of the window so that every sample in it counts.
  const double reach_s = 1.25 * std::max(t_s[i] - t_s[first], t_s[last - 1] - t_s[i]);
  for (std::size_t j = first; j < last; ++j) {
    const double u = (t_s[j] - t_s[i]) / reach_s;
    const double a = 1.0 - std::abs(u) * u * u;
    const double w = a * a * a;  // (1 − |u|³)³
    const Eigen::Vector3d basis(1.0, u, degree == 2 ? u * u : 0.0);
    normal.noalias() += w * basis * basis.transpose();
    for (std::size_t k = 0; k < n_series; ++k) rhs[k].noalias() += (w * series[k][j]) * basis;
  }
  if (degree == 1) normal(2, 2) = 1.0;  // decouple the unused coefficient
  const Eigen::LDLT<Eigen::Matrix3d> solver(normal);
  for (std::size_t k = 0; k < n_series; ++k) {
    const Eigen::Vector3d beta = solver.solve(rhs[k]);
    fits[k] = beta.allFinite() ? LocalFit{beta(0), beta(1) / reach_s} : LocalFit{series[k][i], 0.0};
  }
}

std::vector<std::vector<LocalFit>> smooth_local_quadratic(const std::vector<double>& t_s,
                                                          const std::vector<const std::vector<double>*>& series,
                                                          double half_window_s) {
  const std::size_t n = t_s.size(), n_series = series.size();
  std::vector<std::vector<LocalFit>> fits(n_series, std::vector<LocalFit>(n));
  std::vector<const double*> columns(n_series);
  for (std::size_t k = 0; k < n_series; ++k) columns[k] = series[k]->data();
  std::vector<LocalFit> at_i(n_series);
  std::size_t first = 0, last = 0;  // the window [first, last)
  for (std::size_t i = 0; i < n; ++i) {
    while (t_s[i] - t_s[first] > half_window_s) ++first;
    last = std::max(last, i + 1);
    while (last < n && t_s[last] - t_s[i] <= half_window_s) ++last;
    fit_local_quadratic(t_s, columns, i, first, last, half_window_s, at_i);
    for (std::size_t k = 0; k < n_series; ++k) fits[k][i] = at_i[k];
  }
  return fits;
}

std::vector<LocalFit> smooth_local_quadratic(const std::vector<double>& t_s, const std::vector<double>& y,
                                             double half_window_s) {
  return smooth_local_quadratic(t_s, std::vector<const std::vector<double>*>{&y}, half_window_s).front();
}

}  // namespace rcsim::replay
