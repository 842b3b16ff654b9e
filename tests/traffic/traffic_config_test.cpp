// resolve_traffic_config of traffic/traffic_config.hpp: the defaults it fills (vehicle classes,
// sensors, automatic road length, inflow) by hand, and the input it refuses, naming the option.
#include "traffic/traffic_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/input_error.hpp"

namespace rcsim::traffic_config_test {

using traffic::Layout;
using traffic::TrafficConfig;
using traffic::resolve_traffic_config;

TrafficConfig short_run(Layout layout) {
  TrafficConfig c;
  c.layout = layout;
  c.duration_s = 10.0;
  c.warmup_s = 0.0;
  if (layout == Layout::Intersection) c.lanes = 1;
  return c;
}

TEST(TrafficConfigResolve, FillsTheDefaultsAndTheAutomaticLength) {
  TrafficConfig highway = short_run(Layout::Highway);
  highway.truck_share = 0.0;
  highway = resolve_traffic_config(highway, ".");
  ASSERT_EQ(highway.classes.size(), 2u);
  EXPECT_EQ(highway.classes[0].model, "passenger_car");
  EXPECT_EQ(highway.classes[1].model, "truck_trailer");
  EXPECT_NEAR(highway.classes[0].idm.desired_speed_mps, 120.0 / 3.6, 1e-12);
  ASSERT_EQ(highway.sensors.size(), 2u);
  EXPECT_EQ(highway.sensors[0].id, "front_left");
  EXPECT_EQ(highway.sensors[1].id, "front_right");
  // The ego drives up to (120 + 2 x 10) km/h = 38.9 m/s for 10 s: 200 + 388.9 + 300 = 888.9 m,
  // rounded up to 900 m.
  EXPECT_DOUBLE_EQ(highway.length_m, 900.0);
  // Inflow: three lanes at the equilibrium flow of the car (4.6 m, no trucks) at 20 /km.
  ASSERT_TRUE(highway.inflow_vph.has_value());
  EXPECT_NEAR(*highway.inflow_vph,
              3.0 * traffic::idm_equilibrium_at_density(highway.classes[0].idm, 4.6, 20.0).flow_vph, 1e-9);

  const TrafficConfig ring = resolve_traffic_config(short_run(Layout::Ring), ".");
  EXPECT_DOUBLE_EQ(ring.length_m, 5000.0);
  EXPECT_EQ(ring.inflow_vph, 0.0);  // closed

  // Intersection arms: urban cars (50 km/h); at least 250 m for a short run without warm-up.
  TrafficConfig crossing = short_run(Layout::Intersection);
  crossing.inflow_vph = 600.0;
  crossing = resolve_traffic_config(crossing, ".");
  EXPECT_NEAR(crossing.classes[0].idm.desired_speed_mps, 50.0 / 3.6, 1e-12);
  EXPECT_DOUBLE_EQ(crossing.length_m, 250.0);
  EXPECT_EQ(crossing.inflow_vph, 600.0);  // given: kept
  EXPECT_STREQ(traffic::layout_name(crossing.layout), "intersection");
}

TEST(TrafficConfigResolve, JamDensityOfTheMix) {
  // 15 % trucks of 16.5 m, cars of 4.6 m: mean length 6.385 m, jam at 1000 / (2 + 6.385) = 119.26 /km.
  TrafficConfig c = short_run(Layout::Highway);
  c.density_vpkm = 119.2;
  EXPECT_NO_THROW(resolve_traffic_config(c, "."));
  c.density_vpkm = 119.3;
  try {
    resolve_traffic_config(c, ".");
    FAIL() << "a density above the jam density was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--density-vpkm");
    EXPECT_NE(std::string(e.what()).find("at or above the jam density of this mix (119.3 vehicles/km"), std::string::npos)
        << e.what();
  }
  // Cars alone pack denser: 1000 / 6.6 = 151.5 /km.
  c.truck_share = 0.0;
  c.density_vpkm = 150.0;
  EXPECT_NO_THROW(resolve_traffic_config(c, "."));
}

struct RefusedCase {
  std::string what;
  std::function<void(TrafficConfig&)> change;
  std::string option;
  std::string message;  // the whole text of the error
};

TEST(TrafficConfigResolve, RefusesImpossibleInputNamingTheOption) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<RefusedCase> cases = {
      {"nine lanes", [](TrafficConfig& c) { c.lanes = 9; }, "--lanes", "9 lanes: at most 8 are supported"},
      {"two-lane intersection", [](TrafficConfig& c) { c.layout = Layout::Intersection, c.lanes = 2; }, "--lanes",
       "2 lanes: the intersection's roads have one lane per direction"},
      {"narrow lane", [](TrafficConfig& c) { c.lane_width_m = 2.0; }, "--lane-width-m",
       "2 m: a lane is 2.5 m to 5 m wide"},
      {"no duration", [](TrafficConfig& c) { c.duration_s = 0.0; }, "--duration-s",
       "0 s: must be > 0 and at most one day"},
      {"negative warm-up", [](TrafficConfig& c) { c.warmup_s = -1.0; }, "--warmup-s", "-1 s: must be 0 to 3600"},
      {"curved ring", [](TrafficConfig& c) { c.layout = Layout::Ring, c.curve_radius_m = 500.0; },
       "--curve-radius-m", "only the highway layout can be curved"},
      {"tight curve", [](TrafficConfig& c) { c.curve_radius_m = 200.0; }, "--curve-radius-m",
       "200 m: a gently curved highway has radii of 300 m or more"},
      {"empty ring", [](TrafficConfig& c) { c.layout = Layout::Ring, c.density_vpkm = 0.0; }, "--density-vpkm",
       "a ring road needs a density > 0"},
      {"ring inflow", [](TrafficConfig& c) { c.layout = Layout::Ring, c.inflow_vph = 100.0; }, "--inflow-vph",
       "a ring road is closed: no inflow"},
      {"flood", [](TrafficConfig& c) { c.lanes = 2, c.inflow_vph = 7201.0; }, "--inflow-vph",
       "7201 vehicles/h: more than one vehicle per second and lane cannot enter"},
      {"off-grid samples", [](TrafficConfig& c) { c.sample_interval_s = 0.25; }, "--sample-interval-s",
       "0.25 s: must be 0.1 to 1 s and a multiple of the 0.1 s step"},
      {"negative cycle", [](TrafficConfig& c) { c.cycle_time_s = -0.05; }, "--cycle-time-s",
       "-0.05 s: cannot be negative"},
      {"small ring", [](TrafficConfig& c) { c.layout = Layout::Ring, c.length_m = 200.0; }, "--length-m",
       "200 m: a ring road needs at least 300 m"},
      {"short arms", [](TrafficConfig& c) { c.layout = Layout::Intersection, c.lanes = 1, c.length_m = 100.0; },
       "--length-m", "100 m: each intersection arm must be at least 250 m for this duration and warm-up"},
      {"empty sensor id", [](TrafficConfig& c) { c.sensors = {{"", "srr24", 0.0, 0.0, 0.0}}; }, "--sensor 1",
       "empty sensor id"},
      {"sensor id twice",
       [](TrafficConfig& c) { c.sensors = {{"a", "srr24", 0.0, 0.0, 0.0}, {"a", "srr24", 1.0, 0.0, 0.0}}; },
       "--sensor 2", "sensor id \"a\" given twice"},
      {"sensor pose", [nan](TrafficConfig& c) { c.sensors = {{"a", "srr24", nan, 0.0, 0.0}}; }, "--sensor 1",
       "pose not finite"},
  };
  for (const RefusedCase& rc : cases) {
    TrafficConfig c = short_run(Layout::Highway);
    rc.change(c);
    try {
      resolve_traffic_config(c, ".");
      ADD_FAILURE() << rc.what << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "rcsim traffic") << rc.what;
      EXPECT_EQ(e.where(), rc.option) << rc.what;
      EXPECT_EQ(std::string(e.what()), "rcsim traffic: " + rc.option + ": " + rc.message) << rc.what;
    }
  }
}

}  // namespace rcsim::traffic_config_test
