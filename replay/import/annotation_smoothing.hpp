#pragma once
// Smoothing of annotated object boxes before they become trajectories. Annotation is manual and
// noisy (a few centimetres, about a degree per box); differentiating it directly would turn that
// into wild yaw rates (1° of noise at 25 Hz gives about 0.3 rad/s by central differences). Each
// sample is replaced by a local quadratic regression over the samples within ±half_window_s,
// weighted with the tricube kernel (LOESS: W. S. Cleveland, "Robust locally weighted regression
// and smoothing scatterplots", JASA 74, 1979); the yaw rate is the slope of the yaw fit at the
// sample. A quadratic keeps constant acceleration and steady turns unbiased to first order.
#include <vector>

namespace rcsim::replay {

struct LocalFit {
  double value = 0.0;
  double slope_per_s = 0.0;
};

// Fits y(t) around every t_i; t strictly increasing, same length as y.
std::vector<LocalFit> smooth_local_quadratic(const std::vector<double>& t_s, const std::vector<double>& y,
                                             double half_window_s);

// The same for several series sampled at the same times (they share the weights and the normal
// equations): result[k][i] is series k's fit at t_i.
std::vector<std::vector<LocalFit>> smooth_local_quadratic(const std::vector<double>& t_s,
                                                          const std::vector<const std::vector<double>*>& series,
                                                          double half_window_s);

}  // namespace rcsim::replay
