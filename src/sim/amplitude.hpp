#pragma once
// Radar amplitude simulation (paper III-B, eqs. (1)-(3)).
#include "common/decibel.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/antenna.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {


// Paper eq. (1): the range-dependent amplitude of the reference reflector, linear (A0 = 1):
// L{A_ref^R(R)} = (26.5 - 0.75 R/m) dB with the srr24 values.
double reference_range_amplitude(const AmplitudeLaw& law, double range_m);

// Paper eq. (1) solved for the range: beyond it an echo of this ERCS on boresight stays below the
// detection threshold, L0 - s R + 20 log10(ERCS) = threshold - headroom_db. Not clamped: negative
// when never detectable; needs s > 0. `headroom_db` > 0 moves the bound out (a safety margin).
double detection_range_bound_m(const AmplitudeLaw& law, double ercs, double headroom_db = 0.0);

// The III-B detection decision on a cell's resulting amplitude: keeps detections at or above the
// threshold.
void apply_detection_threshold(double threshold_db, Detections& detections);

// Paper eqs. (2)-(3), (6), (8): for each ideal target the echo with amplitude
// A_n = A_ref^R(R_n) |H_sum(phi_n)|^n ERCS_n and the pointers A_ref^R(R_n) ERCS_n |H_sum|^(n-1) H(phi_n)
// (n = 1, the paper's, unless the sensor's antenna says otherwise).
void compute_echoes(const AmplitudeLaw& law, const MonopulseAntenna& antenna, const IdealTargets& ideal, Echoes& out);

}  // namespace rcsim
