#pragma once
// Radar amplitude simulation (paper III-B, eqs. (1)-(3)).
#include "common/decibel.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/antenna.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {


// The range-dependent level of the reference reflector (ERCS 1) on boresight, in dB:
// paper eq. (1), L{A_ref^R(R)} = (26.5 - 0.75 R/m) dB with the srr24 values; or the radar
// equation, P ~ sigma / R^4, as an SNR: K + sigma_ref - 40 log10(R / 1 m) (docs/amplitude.md).
double reference_range_level_db(const AmplitudeLaw& law, double range_m);
// The same as a linear amplitude (A0 = 1), A_ref^R(R) of eqs. (2), (8).
double reference_range_amplitude(const AmplitudeLaw& law, double range_m);

// Whether the law falls without bound with range (eq. (1) with a slope > 0, or the radar
// equation), so that an echo of finite ERCS has a range beyond which it stays below threshold.
bool has_detection_range_bound(const AmplitudeLaw& law);
// The law solved for the range: beyond it an echo of this ERCS on boresight stays below the
// detection threshold, level(R) + 20 log10(ERCS) = threshold - headroom_db. For eq. (1) not
// clamped: negative when never detectable; needs has_detection_range_bound. `headroom_db` > 0
// moves the bound out (a safety margin).
double detection_range_bound_m(const AmplitudeLaw& law, double ercs, double headroom_db = 0.0);

// What a radar that reports cross-sections writes beside a detection: its amplitude read back
// through eqs. (2), (6) and the radar equation at the measured range and azimuth,
// sigma = sigma_ref + A_dB - level(R) - 20 n log10 |H_sum(phi)| (docs/amplitude.md). Needs the radar
// equation (an eq. (1) level has no cross-section); the pattern's null gives +inf.
double radar_cross_section_estimate_dbsm(const AmplitudeLaw& law, const MonopulseAntenna& antenna, double range_m,
                                         double azimuth_rad, double amplitude_db);

// The III-B detection decision on a cell's resulting amplitude: keeps detections at or above the
// threshold.
void apply_detection_threshold(double threshold_db, Detections& detections);

// Paper eqs. (2)-(3), (6), (8): for each ideal target the echo with amplitude
// A_n = A_ref^R(R_n) |H_sum(phi_n)|^n ERCS_n and the pointers A_ref^R(R_n) ERCS_n |H_sum|^(n-1) H(phi_n)
// (n = 1, the paper's, unless the sensor's antenna says otherwise).
void compute_echoes(const AmplitudeLaw& law, const MonopulseAntenna& antenna, const IdealTargets& ideal, Echoes& out);

}  // namespace rcsim
