#include "sim/antenna.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim {

MonopulseAntenna::MonopulseAntenna(const AntennaGeometry& geometry)
    : length_factor_(kPi * geometry.dipole_length_wavelengths), spacing_factor_(kPi * geometry.element_spacing_wavelengths) {}

AntennaPointers MonopulseAntenna::pattern(double azimuth_rad) const {
  const double sin_phi = std::sin(azimuth_rad);
  const double x = length_factor_ * sin_phi;
  const double si = std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
  const double element = si * std::cos(azimuth_rad);
  // 1/2 (1 +- exp(j 2u)) = exp(j u) cos u  and  -j exp(j u) sin u, with u = pi d/lambda sin phi.
  const double u = spacing_factor_ * sin_phi;
  const std::complex<double> phase(std::cos(u), std::sin(u));
  return {element * std::cos(u) * phase, element * std::sin(u) * std::complex<double>(0.0, -1.0) * phase};
}

double MonopulseAntenna::additive_sensing_ratio(const AntennaPointers& pointers) {
  const double d = magnitude(pointers.delta);
  const double s = magnitude(pointers.sum);
  if (!(d + s > 0.0)) return -1.0;  // no signal at all: take boresight
  return (d - s) / (d + s);
}

double MonopulseAntenna::absolute_azimuth_from_asr(double asr) const {
  const double u = std::atan(std::clamp(asr, -1.0, 1.0)) + 0.25 * kPi;  // |u| in [0, pi/2]
  return std::asin(std::min(1.0, u / spacing_factor_));
}

double MonopulseAntenna::estimate_azimuth(const AntennaPointers& pointers) const {
  const double magnitude_rad = absolute_azimuth_from_asr(additive_sensing_ratio(pointers));
  const double phase_term = (pointers.delta * std::conj(pointers.sum)).imag();
  return phase_term < 0.0 ? magnitude_rad : -magnitude_rad;
}

}  // namespace rcsim
