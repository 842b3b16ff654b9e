#pragma once
// Radar amplitude simulation (paper III-B, eqs. (1)-(3)).
#include "sensor/sensor_config.hpp"
#include "sim/antenna.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// L{A} = 20 log10 |A / A0| dB (paper III-B).
double amplitude_to_db(double amplitude);
double db_to_amplitude(double level_db);
// The same level from the squared amplitude |A|^2 = power: 10 log10(power), no square root.
double power_to_db(double power);

// Paper eq. (1): the range-dependent amplitude of the reference reflector, linear (A0 = 1):
// L{A_ref^R(R)} = (26.5 - 0.75 R/m) dB with the srr24 values.
double reference_range_amplitude(const AmplitudeLaw& law, double range_m);

// Paper eqs. (2)-(3), (6), (8): for each ideal target the echo with amplitude
// A_n = A_ref^R(R_n) |H_sum(phi_n)|^n ERCS_n and the pointers A_ref^R(R_n) ERCS_n |H_sum|^(n-1) H(phi_n)
// (n = 1, the paper's, unless the sensor's antenna says otherwise).
void compute_echoes(const AmplitudeLaw& law, const MonopulseAntenna& antenna, const IdealTargets& ideal, Echoes& out);

}  // namespace rcsim
