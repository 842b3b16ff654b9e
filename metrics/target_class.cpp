#include "metrics/target_class.hpp"

#include <cmath>

namespace rcsim::metrics {

std::string_view target_class_name(TargetClass c) {
  switch (c) {
    case TargetClass::object: return "object";
    case TargetClass::stationary_background: return "background";
    case TargetClass::other: return "other";
  }
  return "other";
}

double stationary_range_rate_mps(const Vec2& v_WS_S, double azimuth_rad) {
  return -(v_WS_S.x() * std::cos(azimuth_rad) + v_WS_S.y() * std::sin(azimuth_rad));
}

TargetClass classify_target(int object, double range_rate_mps, double azimuth_rad, const Vec2& v_WS_S,
                            double stationary_gate_mps) {
  if (object >= 0) return TargetClass::object;
  const double compensated_mps = range_rate_mps - stationary_range_rate_mps(v_WS_S, azimuth_rad);
  return std::abs(compensated_mps) <= stationary_gate_mps ? TargetClass::stationary_background : TargetClass::other;
}

}  // namespace rcsim::metrics
