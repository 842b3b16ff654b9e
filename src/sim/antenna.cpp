#include "sim/antenna.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim {

MonopulseAntenna::MonopulseAntenna(const AntennaGeometry& geometry)
    : length_factor_(kPi * geometry.dipole_length_wavelengths),
      spacing_factor_(kPi * geometry.element_spacing_wavelengths),
      equal_factors_(length_factor_ == spacing_factor_),
      amplitude_pattern_exponent_(geometry.amplitude_pattern_exponent) {}

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
  // Im(H_delta conj(H_sum)), without the full complex product.
  const double phase_term = pointers.delta.imag() * pointers.sum.real() - pointers.delta.real() * pointers.sum.imag();
  return phase_term < 0.0 ? magnitude_rad : -magnitude_rad;
}

}  // namespace rcsim
