#include "sim/amplitude.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rcsim {

namespace {
// The radar equation's 1/R^4 is taken no closer than this (a reflector at the antenna).
constexpr double kRadarEquationMinRangeM = 1e-3;
}  // namespace

double reference_range_level_db(const AmplitudeLaw& law, double range_m) {
  switch (law.kind) {
    case AmplitudeLawKind::paper_eq1:
      return law.reference_level_db - law.reference_slope_db_per_m * range_m;  // eq. (1)
    case AmplitudeLawKind::radar_equation:  // P_r ~ sigma G^2 / R^4, as SNR in dB
      return law.snr_at_1m_for_1m2_db + law.reference_rcs_dbsm -
             law.range_exponent * power_to_db(std::max(range_m, kRadarEquationMinRangeM));  // 10 n log10 R
  }
  return 0.0;
}

double reference_range_amplitude(const AmplitudeLaw& law, double range_m) {
  return db_to_amplitude(reference_range_level_db(law, range_m));
}

bool has_detection_range_bound(const AmplitudeLaw& law) {
  // A range-compensated amplitude (exponent 0) does not fall with range: no bound.
  if (law.kind == AmplitudeLawKind::radar_equation) return law.range_exponent > 0.0;
  return law.reference_slope_db_per_m > 0.0;
}

double detection_range_bound_m(const AmplitudeLaw& law, double ercs, double headroom_db) {
  switch (law.kind) {
    case AmplitudeLawKind::paper_eq1:
      return (law.reference_level_db - law.detection_threshold_db + headroom_db + amplitude_to_db(ercs)) /
             law.reference_slope_db_per_m;  // eq. (1)
    case AmplitudeLawKind::radar_equation:
      if (!(law.range_exponent > 0.0)) return std::numeric_limits<double>::infinity();  // no fall with range
      // R^n = 10^((level at 1 m + 20 log10 ERCS - threshold + headroom) / 10)
      return std::pow(db_to_power(reference_range_level_db(law, 1.0) - law.detection_threshold_db + headroom_db +
                                  amplitude_to_db(ercs)),
                      1.0 / law.range_exponent);
  }
  return 0.0;
}

double radar_cross_section_estimate_dbsm(const AmplitudeLaw& law, const MonopulseAntenna& antenna, double range_m,
                                         double azimuth_rad, double amplitude_db) {
  const double pattern_db = antenna.amplitude_pattern_exponent() * amplitude_to_db(antenna.sum_magnitude(azimuth_rad));
  return law.reference_rcs_dbsm + amplitude_db - reference_range_level_db(law, range_m) - pattern_db;
}

void apply_detection_threshold(double threshold_db, Detections& detections) {
  std::erase_if(detections, [&](const Detection& d) { return d.amplitude_db < threshold_db; });
}

void compute_echoes(const AmplitudeLaw& law, const MonopulseAntenna& antenna, const IdealTargets& ideal, Echoes& out) {
  out.clear();
  const double extra_pattern_power = antenna.amplitude_pattern_exponent() - 1.0;
  for (std::size_t i = 0; i < ideal.size(); ++i) {
    const auto& t = ideal[i];
    double weight = reference_range_amplitude(law, t.range_m) * t.ercs;  // A_ref^R(R_n) ERCS_n, eq. (8)
    const AntennaPointers h = antenna.pattern(t.sin_azimuth, t.cos_azimuth);  // eq. (6)
    // eq. (2) with A^phi = |H_sum|^n: the extra |H_sum|^(n-1) scales both pointers (|H_sum| <= 1, so
    // no overflow; 0 at +-90 deg stays 0).
    if (extra_pattern_power != 0.0) weight *= std::pow(magnitude(h.sum), extra_pattern_power);
    Echo& e = out.emplace_back();  // built in place: a copy from the stack stalls on store forwarding
    e.range_m = t.range_m;
    e.range_rate_mps = t.range_rate_mps;
    e.sum_pointer = weight * h.sum;
    e.delta_pointer = weight * h.delta;
    e.amplitude = magnitude(e.sum_pointer);  // eqs. (2)-(3): A^phi = |H_sum|
    e.azimuth_rad = t.azimuth_rad;  // an array that resolves azimuth forms its beams by it
    e.elevation_rad = t.elevation_rad;
    e.ideal_index = static_cast<int>(i);
  }
}

}  // namespace rcsim
