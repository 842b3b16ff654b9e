#pragma once
// Smoothing of annotated object boxes before they become trajectories. Annotation is manual and
// noisy (a few centimetres, about a degree per box); differentiating it directly would turn that
// into wild yaw rates (1° of noise at 25 Hz gives about 0.3 rad/s by central differences). Each
// sample is replaced by a local quadratic regression over the samples within ±half_window_s,
// weighted with the tricube kernel (LOESS: W. S. Cleveland, "Robust locally weighted regression
// and smoothing scatterplots", JASA 74, 1979); the yaw rate is the slope of the yaw fit at the
// sample. A quadratic keeps constant acceleration and steady turns unbiased to first order.
#include <cstddef>
#include <span>
#include <vector>

namespace rcsim::replay {

struct LocalFit {
  double value = 0.0;
  double slope_per_s = 0.0;
};

// The fit at sample i of every series over the window [first, last) of the samples (those within
// ±half_window_s of t_i), into fits[k]. The batch functions below and the streaming import
// (streaming_import.hpp) both fit through this one function, so they agree to the last bit.
void fit_local_quadratic(std::span<const double> t_s, std::span<const double* const> series, std::size_t i,
                         std::size_t first, std::size_t last, double half_window_s, std::span<LocalFit> fits);

// Fits y(t) around every t_i; t strictly increasing, same length as y.
std::vector<LocalFit> smooth_local_quadratic(const std::vector<double>& t_s, const std::vector<double>& y,
                                             double half_window_s);

// The same for several series sampled at the same times (they share the weights and the normal
// equations): result[k][i] is series k's fit at t_i.
std::vector<std::vector<LocalFit>> smooth_local_quadratic(const std::vector<double>& t_s,
                                                          const std::vector<const std::vector<double>*>& series,
                                                          double half_window_s);

}  // namespace rcsim::replay
