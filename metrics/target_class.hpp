#pragma once
// What a target of a real drive is: a target of an annotated object, the stationary world the
// annotation leaves out (guard rails, signs, the road), or anything else (unannotated traffic,
// ghosts, clutter). The classes let the metrics tell model error on the annotated objects from
// the unmodelled world (docs/metrics.md).
#include <string_view>

#include "common/pose2.hpp"

namespace rcsim::metrics {

enum class TargetClass { object, stationary_background, other };

std::string_view target_class_name(TargetClass c);  // "object", "background", "other"

// The range rate a stationary point at `azimuth_rad` shows to a sensor moving with velocity
// v_WS_S (the sensor's own velocity, in the sensor frame): minus its projection on the line of
// sight (Kellner et al. 2013, eq. (2)).
double stationary_range_rate_mps(const Vec2& v_WS_S, double azimuth_rad);

// object >= 0 (the target lies within the gate of that annotated box): object. Otherwise the
// stationary background if its ego-motion-compensated radial speed, range_rate_mps minus what a
// stationary point there would show, is within stationary_gate_mps; else other.
TargetClass classify_target(int object, double range_rate_mps, double azimuth_rad, const Vec2& v_WS_S,
                            double stationary_gate_mps);

}  // namespace rcsim::metrics
