#include "traffic/traffic_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "common/input_error.hpp"
#include "scene/scene.hpp"

namespace rcsim::traffic {
namespace {

constexpr const char* kWhat = "rcsim traffic";

[[noreturn]] void refuse(const std::string& option, const std::string& message) {
  throw InputError(kWhat, option, message);
}

IdmParameters idm(double v0_kmh, double T_s, double s0_m, double a_mps2, double b_mps2) {
  IdmParameters p;
  p.desired_speed_mps = v0_kmh / 3.6;
  p.time_headway_s = T_s;
  p.min_gap_m = s0_m;
  p.max_accel_mps2 = a_mps2;
  p.comfortable_decel_mps2 = b_mps2;
  return p;
}

double mean_length_m(const TrafficConfig& c) {
  return (1.0 - c.truck_share) * c.classes.front().length_m + c.truck_share * c.classes.back().length_m;
}

}  // namespace

const char* layout_name(Layout layout) {
  switch (layout) {
    case Layout::Highway: return "highway";
    case Layout::Ring: return "ring";
    case Layout::Intersection: return "intersection";
  }
  return "?";
}

std::vector<VehicleClass> default_vehicle_classes(Layout layout) {
  VehicleClass car{"car", "passenger_car", 4.6, 1.8, {}, 0.0};
  VehicleClass truck{"truck", "truck_trailer", 16.5, 2.55, {}, 0.0};
  if (layout == Layout::Intersection) {
    car.idm = idm(50.0, 1.2, 2.0, 1.0, 1.5);  // urban car (Treiber & Kesting 2013, ch. 11 ranges)
    car.desired_speed_sigma_mps = 1.0;
    truck.idm = idm(45.0, 1.5, 2.0, 0.6, 1.2);
    truck.desired_speed_sigma_mps = 0.5;
  } else {
    car.idm = idm(120.0, 1.6, 2.0, 0.73, 1.67);  // Treiber, Hennecke, Helbing 2000, Table I
    car.desired_speed_sigma_mps = 10.0 / 3.6;
    truck.idm = idm(85.0, 1.8, 2.0, 0.4, 1.5);  // slower, longer headway, weaker engine
    truck.desired_speed_sigma_mps = 3.0 / 3.6;
  }
  return {car, truck};
}

std::vector<SensorMount> default_sensors() {
  return {{"front_left", "srr24", 3.7, 0.7, 0.5}, {"front_right", "srr24", 3.7, -0.7, -0.5}};
}

TrafficConfig resolve_traffic_config(TrafficConfig c, const std::string& output_dir) {
  if (c.classes.empty()) c.classes = default_vehicle_classes(c.layout);
  if (c.sensors.empty()) c.sensors = default_sensors();

  if (c.lanes < 1) refuse("--lanes", fmt::format("{} lanes: a road needs at least one lane", c.lanes));
  if (c.lanes > 8) refuse("--lanes", fmt::format("{} lanes: at most 8 are supported", c.lanes));
  if (c.layout == Layout::Intersection && c.lanes != 1) {
    refuse("--lanes", fmt::format("{} lanes: the intersection's roads have one lane per direction", c.lanes));
  }
  if (!(c.lane_width_m >= 2.5 && c.lane_width_m <= 5.0)) {
    refuse("--lane-width-m", fmt::format("{} m: a lane is 2.5 m to 5 m wide", c.lane_width_m));
  }
  if (!(c.duration_s > 0.0 && c.duration_s <= 86400.0)) {
    refuse("--duration-s", fmt::format("{} s: must be > 0 and at most one day", c.duration_s));
  }
  if (!(c.warmup_s >= 0.0 && c.warmup_s <= 3600.0)) refuse("--warmup-s", fmt::format("{} s: must be 0 to 3600", c.warmup_s));
  if (!(c.truck_share >= 0.0 && c.truck_share <= 1.0)) {
    refuse("--truck-share", fmt::format("{}: a share is between 0 and 1", c.truck_share));
  }
  if (!(c.length_m >= 0.0)) refuse("--length-m", fmt::format("{} m: a length cannot be negative", c.length_m));
  if (c.curve_radius_m != 0.0) {
    if (c.layout != Layout::Highway) refuse("--curve-radius-m", "only the highway layout can be curved");
    if (!(c.curve_radius_m >= 300.0)) {
      refuse("--curve-radius-m", fmt::format("{} m: a gently curved highway has radii of 300 m or more", c.curve_radius_m));
    }
  }
  const double jam_vpkm = 1000.0 / (c.classes.front().idm.min_gap_m + mean_length_m(c));
  if (!(c.density_vpkm >= 0.0)) refuse("--density-vpkm", fmt::format("{} vehicles/km: cannot be negative", c.density_vpkm));
  if (c.density_vpkm >= jam_vpkm) {
    refuse("--density-vpkm", fmt::format("{} vehicles/km and lane is at or above the jam density of this mix "
                                         "({:.1f} vehicles/km: bumper to bumper at the jam distance)",
                                         c.density_vpkm, jam_vpkm));
  }
  if (c.layout == Layout::Ring && c.density_vpkm <= 0.0) refuse("--density-vpkm", "a ring road needs a density > 0");
  if (c.inflow_vph) {
    if (!(*c.inflow_vph >= 0.0)) refuse("--inflow-vph", fmt::format("{} vehicles/h: cannot be negative", *c.inflow_vph));
    if (*c.inflow_vph > 3600.0 * c.lanes) {
      refuse("--inflow-vph", fmt::format("{} vehicles/h: more than one vehicle per second and lane cannot enter",
                                         *c.inflow_vph));
    }
    if (c.layout == Layout::Ring && *c.inflow_vph > 0.0) refuse("--inflow-vph", "a ring road is closed: no inflow");
  } else if (c.layout != Layout::Ring) {
    // The flow that keeps the road at the density: lanes x equilibrium flow of the mean car.
    c.inflow_vph = c.lanes * idm_equilibrium_at_density(c.classes.front().idm, mean_length_m(c),
                                                        std::max(c.density_vpkm, 1.0)).flow_vph;
  } else {
    c.inflow_vph = 0.0;
  }
  const double steps = c.sample_interval_s / c.step_s;
  if (!(c.sample_interval_s >= 0.1 && c.sample_interval_s <= 1.0) || std::abs(steps - std::round(steps)) > 1e-9) {
    refuse("--sample-interval-s",
           fmt::format("{} s: must be 0.1 to 1 s and a multiple of the {} s step", c.sample_interval_s, c.step_s));
  }
  if (!(c.cycle_time_s >= 0.0)) refuse("--cycle-time-s", fmt::format("{} s: cannot be negative", c.cycle_time_s));

  // The ego drives the whole scene on the road: the automatic length leaves room for it.
  const double v_max_mps = max_desired_speed_mps(c.classes.front());
  const double travel_m = v_max_mps * (c.warmup_s + c.duration_s);
  if (c.layout == Layout::Highway) {
    const double needed_m = 200.0 + travel_m + 300.0;
    if (c.length_m == 0.0) c.length_m = std::ceil(needed_m / 100.0) * 100.0;
    if (c.length_m < needed_m) {
      refuse("--length-m", fmt::format("{} m: the ego (desired speed up to {:.1f} m/s) would leave the highway before "
                                       "the scene ends; give at least {:.0f} m or use --layout ring",
                                       c.length_m, v_max_mps, needed_m));
    }
  } else if (c.layout == Layout::Ring) {
    if (c.length_m == 0.0) c.length_m = 5000.0;
    if (c.length_m < 300.0) refuse("--length-m", fmt::format("{} m: a ring road needs at least 300 m", c.length_m));
  } else {
    // Each arm: from its start to the conflict area, then as far again beyond it. The ego starts
    // far enough out to ask for the conflict area after the warm-up and must not run off the end.
    const double approach_m = c.conflict_request_distance_m + c.lane_width_m + v_max_mps * c.warmup_s + 40.0;
    const double needed_m = std::max({250.0, approach_m, travel_m - approach_m + 60.0});
    if (c.length_m == 0.0) c.length_m = std::ceil(needed_m / 10.0) * 10.0;
    if (c.length_m < needed_m) {
      refuse("--length-m", fmt::format("{} m: each intersection arm must be at least {:.0f} m for this duration and "
                                       "warm-up", c.length_m, needed_m));
    }
  }

  std::set<std::string> ids;
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    const SensorMount& s = c.sensors[i];
    const std::string where = fmt::format("--sensor {}", i + 1);
    if (s.id.empty()) refuse(where, "empty sensor id");
    if (!ids.insert(s.id).second) refuse(where, fmt::format("sensor id \"{}\" given twice", s.id));
    if (!std::isfinite(s.x_m) || !std::isfinite(s.y_m) || !std::isfinite(s.yaw_rad)) refuse(where, "pose not finite");
    try {
      (void)sensor_config_for_type(s.type, output_dir);
    } catch (const std::exception& e) {
      refuse(where, e.what());
    }
  }
  return c;
}

}  // namespace rcsim::traffic
