#pragma once
// Sum and delta antenna patterns of the monopulse sensor (paper III-D, eq. (6)) and the
// additive sensing ratio (eq. (7)) with its exact inverse.
#include <cmath>
#include <complex>

#include "sensor/sensor_config.hpp"

namespace rcsim {

// |z| without hypot's overflow guards: pointer magnitudes are far from overflow.
inline double magnitude(const std::complex<double>& z) { return std::sqrt(std::norm(z)); }

struct AntennaPointers {
  std::complex<double> sum;
  std::complex<double> delta;
};

class MonopulseAntenna {
 public:
  explicit MonopulseAntenna(const AntennaGeometry& geometry);

  // Paper eq. (6): H(phi) = si(pi L/lambda sin phi) cos phi * 1/2 (1 +- exp(j 2 pi d/lambda sin phi)).
  AntennaPointers pattern(double azimuth_rad) const { return pattern(std::sin(azimuth_rad), std::cos(azimuth_rad)); }
  // The same from sin phi and cos phi (the sensor cycle has them from the line of sight). Inline:
  // returned through memory from another file, the pointers stall on store forwarding.
  AntennaPointers pattern(double sin_phi, double cos_phi) const {
    // u = pi d/lambda sin phi; 1/2 (1 +- exp(j 2u)) = exp(j u) cos u  and  -j exp(j u) sin u.
    const double u = spacing_factor_ * sin_phi;
    const double cos_u = std::cos(u), sin_u = std::sin(u);
    const double x = length_factor_ * sin_phi;
    const double sin_x = equal_factors_ ? sin_u : std::sin(x);
    const double si = std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : sin_x / x;
    const double element = si * cos_phi;
    // sum = element cos u (cos u + j sin u);  delta = element sin u (sin u - j cos u).
    const double sum_weight = element * cos_u, delta_weight = element * sin_u;
    return {{sum_weight * cos_u, sum_weight * sin_u}, {delta_weight * sin_u, -(delta_weight * cos_u)}};
  }
  // |H_sum(phi)|, the antenna pattern A^phi of eq. (2) (1 at boresight).
  double sum_magnitude(double azimuth_rad) const { return magnitude(pattern(azimuth_rad).sum); }
  // n of A^phi = |H_sum|^n (AntennaGeometry); 1 for the paper's pattern.
  double amplitude_pattern_exponent() const { return amplitude_pattern_exponent_; }

  // Paper eq. (7): ASR = (|H_delta| - |H_sum|) / (|H_delta| + |H_sum|), in [-1, 1].
  static double additive_sensing_ratio(const AntennaPointers& pointers);
  // |phi| from the ASR, the closed-form inverse of eq. (7): with u = pi d/lambda sin phi the
  // common factor cancels and ASR = tan(|u| - pi/4), so |u| = atan(ASR) + pi/4.
  double absolute_azimuth_from_asr(double asr) const;
  // The estimated azimuth: |phi| from eq. (7), the sign from the phase between delta and sum
  // (H_delta / H_sum = -j tan(u) for one target: Im(H_delta conj(H_sum)) < 0 means phi > 0).
  double estimate_azimuth(const AntennaPointers& pointers) const;

 private:
  double length_factor_;   // pi L / lambda
  double spacing_factor_;  // pi d / lambda
  bool equal_factors_;     // L = d (as in the srr24): the si argument equals u, one sine serves both
  double amplitude_pattern_exponent_;
};

}  // namespace rcsim
