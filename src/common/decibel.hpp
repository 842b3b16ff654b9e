#pragma once
// The one place where levels in decibels and linear quantities meet (paper III-B:
// L{A} = 20 log10 |A / A0| dB with A0 = 1). Through the natural exp and log
// (20 log10 a = (20 / ln 10) ln a), each faster than pow and log10.
#include <cmath>
#include <numbers>

namespace rcsim {

// An amplitude (field quantity) and its level: 20 log10 a.
inline double amplitude_to_db(double amplitude) { return (20.0 / std::numbers::ln10) * std::log(amplitude); }
inline double db_to_amplitude(double level_db) { return std::exp((std::numbers::ln10 / 20.0) * level_db); }

// A power (|A|^2) and its level: 10 log10 p, the same level as the amplitude's without a square root.
inline double power_to_db(double power) { return (10.0 / std::numbers::ln10) * std::log(power); }
inline double db_to_power(double level_db) { return std::exp((std::numbers::ln10 / 10.0) * level_db); }

}  // namespace rcsim
