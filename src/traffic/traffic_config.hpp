#pragma once
// What `rcsim traffic` is asked to make: the layout, the demand, the vehicle mix and the ego's
// sensors. Validated once (validate_traffic_config) before anything is simulated.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "traffic/idm.hpp"
#include "traffic/mobil.hpp"

namespace rcsim::traffic {

enum class Layout { Highway, Ring, Intersection };

// A vehicle class of the mix: its object model, box and IDM parameters; the desired speed v0 of
// each vehicle is drawn from a normal distribution truncated to +-2 sigma.
struct VehicleClass {
  std::string name;   // id prefix in the scene ("car", "truck")
  std::string model;  // object model name (`rcsim models`)
  double length_m = 4.6;
  double width_m = 1.8;
  IdmParameters idm;  // idm.desired_speed_mps is the mean of the distribution
  double desired_speed_sigma_mps = 0.0;
};

struct SensorMount {
  std::string id;
  std::string type;
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
};

struct TrafficConfig {
  Layout layout = Layout::Highway;
  int lanes = 3;                   // highway and ring: lanes in the one direction of travel
  double length_m = 0.0;           // highway/ring: road length; intersection: each arm. 0 = automatic
  double lane_width_m = 3.5;
  double curve_radius_m = 0.0;     // highway: 0 = straight, else winding with this smallest radius
  double curve_wavelength_m = 2000.0;
  double duration_s = 60.0;
  double warmup_s = 30.0;          // simulated before scene time 0, not written
  double density_vpkm = 20.0;      // initial vehicles per km and lane (ring: the density throughout)
  std::optional<double> inflow_vph;  // vehicles per hour entering each road (all lanes); none:
                                     // the equilibrium flow at density_vpkm
  double truck_share = 0.15;       // fraction of trucks with trailer in the mix
  std::uint64_t seed = 1;
  double step_s = 0.1;             // integration step (ballistic update)
  double sample_interval_s = 0.3;  // trajectory sample spacing in the scene; a multiple of step_s
  double lane_change_time_s = 4.0; // lateral motion of a lane change, at the speed when it starts
  double min_lane_change_length_m = 30.0;
  double conflict_request_distance_m = 120.0;  // intersection: where a vehicle asks to cross
  double cycle_time_s = 0.0;       // scene cycle_time_s; 0 = the sensors' default
  std::vector<SensorMount> sensors;  // empty: the default pair of srr24 front corner sensors
  std::vector<VehicleClass> classes;  // empty: default_vehicle_classes(layout)
  MobilParameters mobil;
  bool record_steps = false;       // keep every step's state (tests)
};

// Passenger cars (Treiber 2000 Table I on the highway; urban v0 at the intersection) and trucks
// with trailer.
std::vector<VehicleClass> default_vehicle_classes(Layout layout);
std::vector<SensorMount> default_sensors();

// Fills the defaults (classes, sensors, automatic length, inflow) and refuses impossible input
// with rcsim::InputError naming the option. output_dir resolves sensor configuration paths.
TrafficConfig resolve_traffic_config(TrafficConfig config, const std::string& output_dir);

// The largest desired speed a vehicle of the class can draw (mean + 2 sigma).
inline double max_desired_speed_mps(const VehicleClass& c) {
  return c.idm.desired_speed_mps + 2.0 * c.desired_speed_sigma_mps;
}

const char* layout_name(Layout layout);

}  // namespace rcsim::traffic
