#pragma once
// Small traffic runs for the traffic tests: a highway at 30 vehicles/km, a fifth trucks, 40 s.
#include <cstdint>

#include "traffic/traffic_config.hpp"

namespace rcsim::testing {

inline traffic::TrafficConfig small_highway(std::uint64_t seed) {
  traffic::TrafficConfig c;
  c.layout = traffic::Layout::Highway;
  c.duration_s = 40.0;
  c.warmup_s = 10.0;
  c.density_vpkm = 30.0;
  c.truck_share = 0.2;
  c.seed = seed;
  c.record_steps = true;
  return traffic::resolve_traffic_config(c, ".");
}

}  // namespace rcsim::testing
