// Hard cases of the geometric stages (docs/fidelity.md): degenerate sensor/reflector positions, cell
// boundaries, huge coordinates and long times. No NaN or infinity may leave any stage.
#include <gtest/gtest.h>

#include <random>

#include "hard_cases/hard_case_support.hpp"
#include "sim/visibility.hpp"

namespace rcsim {
namespace {

using testing::add_model_object;
using testing::expect_simulation_finite;
using testing::sample;

// prefix + k (not operator+ on a literal: GCC 12 warns falsely, -Wrestrict).
std::string label(const char* prefix, int k) {
  std::string s(prefix);
  s += std::to_string(k);
  return s;
}

Simulation run_few_cycles(const Scene& scene, int cycles, bool noise = true) {
  SimulationOptions options;
  options.seed = 11;
  options.noise = noise;
  Simulation sim(scene, options);
  for (int k = 0; k < cycles && k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    expect_simulation_finite(sim, label("cycle ", k));
  }
  return sim;
}

TEST(HardCaseGeometry, SensorInsidePlaneCircle) {
  const ObjectModel m = testing::plane_circle_model(2.0);
  const PlaneReflector& plane = m.planes[0];
  // Centre, inside, exactly on the edge: no outer reflection (Fig. 7).
  EXPECT_FALSE(plane_reflection_point_O(plane, Vec2(0.0, 0.0)).has_value());
  EXPECT_FALSE(plane_reflection_point_O(plane, Vec2(1.0, 0.5)).has_value());
  EXPECT_FALSE(plane_reflection_point_O(plane, Vec2(2.0, 0.0)).has_value());
  // Just outside the edge: a reflection point on the circle, at about zero range.
  const auto p = plane_reflection_point_O(plane, Vec2(std::nextafter(2.0, 3.0), 0.0));
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->norm(), 2.0, 1e-12);
  // In the sensor cycle: sensor at the centre, inside, on the edge and a hair outside.
  for (const double x_m : {0.0, 1.0, 2.0, std::nextafter(2.0, 3.0), 2.0 + 1e-12, 2.0 + 1e-300}) {
    Scene scene = testing::single_sensor_scene(0.2);
    scene.sensors[0].config.fov.min_range_m = 0.0;
    add_model_object(scene, "circle", m, {sample(0.0, -x_m, 0.0, 0.0, 0.0)});
    run_few_cycles(scene, 3);
  }
}

TEST(HardCaseGeometry, ReflectorOnTheSensor) {
  // A point reflector exactly on the sensor, one a hair in front, one at min range.
  // With the srr24's 0.2 m minimum range and with none (a sensor file may say min_range_m = 0).
  for (const double min_range_m : {0.2, 0.0}) {
    for (const double x_m : {0.0, 1e-300, 1e-160, 1e-12, 0.2, std::nextafter(0.2, 1.0)}) {
      Scene scene = testing::single_sensor_scene(0.2);
      scene.sensors[0].config.fov.min_range_m = min_range_m;
      add_model_object(scene, "p", testing::points_model({Vec2(0.0, 0.0)}), {sample(0.0, x_m, 0.0, 0.0, 0.0)});
      const Simulation sim = run_few_cycles(scene, 3);
      for (const auto& t : sim.sensor_state(0).ideal) {
        EXPECT_GE(t.range_m, min_range_m);
        EXPECT_GT(t.range_m, 0.0);
      }
    }
  }
}

TEST(HardCaseGeometry, ReflectorOnTheSensorAnyPose) {
  // A point reflector placed (in its object's frame) where the sensor is, for random object poses:
  // after rounding it lands exactly on the sensor, or a hair away in any direction.
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    Scene scene = testing::single_sensor_scene(0.1);
    scene.sensors[0].config.fov.min_range_m = 0.0;
    const Pose2 X_WO{3.0 * u(gen), 3.0 * u(gen), kPi * u(gen)};
    const Vec2 p_OS_O = inverse_transform_point(X_WO, Vec2(0.0, 0.0));
    add_model_object(scene, "p", testing::points_model({p_OS_O}), {sample(0.0, X_WO.x_m, X_WO.y_m, X_WO.yaw_rad, 0.0)});
    run_few_cycles(scene, 2);
  }
}

TEST(HardCaseGeometry, AzimuthAtAndBeyondNinety) {
  // Sensors with view fields up to and beyond +-90 deg; reflectors at +-90 deg and behind.
  for (const double half_deg : {35.0, 89.999, 90.0, 120.0, 180.0}) {
    Scene scene = testing::single_sensor_scene(0.2);
    scene.sensors[0].config.fov.azimuth_half_rad = half_deg * kPi / 180.0;
    std::vector<Vec2> points;
    for (const double az_deg : {-180.0, -135.0, -90.0, -89.9, 0.0, 89.9, 90.0, 135.0, 180.0}) {
      const double a = az_deg * kPi / 180.0;
      points.emplace_back(10.0 * std::cos(a), 10.0 * std::sin(a));
    }
    add_model_object(scene, "ring", testing::points_model(points), {sample(0.0, 0.0, 0.0, 0.0, 0.0)});
    const Simulation sim = run_few_cycles(scene, 5);
    for (const auto& t : sim.sensor_state(0).ideal) EXPECT_LE(std::abs(t.azimuth_rad), 0.5 * kPi) << half_deg;
  }
}

TEST(HardCaseGeometry, CoincidentReflectors) {
  // Three reflectors at one point and two objects at one place: one cell, finite, deterministic.
  Scene scene = testing::single_sensor_scene(0.4);
  const ObjectModel m = testing::points_model({Vec2(0.0, 0.0), Vec2(0.0, 0.0), Vec2(0.0, 0.0)});
  add_model_object(scene, "a", m, {sample(0.0, 10.0, 0.0, 0.0, 0.0)});
  add_model_object(scene, "b", m, {sample(0.0, 10.0, 0.0, 0.0, 0.0)});
  const Simulation sim = run_few_cycles(scene, 10, false);
  const auto& st = sim.sensor_state(0);
  ASSERT_EQ(st.cells.size(), 1u);
  EXPECT_EQ(st.cells[0].member_count, 6);
  EXPECT_NEAR(st.cells[0].range_m, 10.0, 1e-12);
  ASSERT_EQ(st.detections.size(), 1u);
  EXPECT_NEAR(st.detections[0].azimuth_rad, 0.0, 1e-9);
}

TEST(HardCaseGeometry, TargetsOnCellBoundaries) {
  // Reflectors exactly half a cell and a whole cell apart in range (binary-exact distances).
  const double cell_m = 0.25;  // exact in binary
  Scene scene = testing::single_sensor_scene(0.4);
  scene.sensors[0].config.resolution.range_cell_m = cell_m;
  // Strongest at 10 m; others at 10.125 (on the boundary: member), 10.25, 10.375, 10.5.
  for (int k = 0; k <= 4; ++k) {
    add_model_object(scene, label("p", k), testing::points_model({Vec2(0.0, 0.0)}, k == 0 ? 20.0 : 1.0),
                     {sample(0.0, 10.0 + 0.125 * k, 0.0, 0.0, 0.0)});
  }
  const Simulation sim = run_few_cycles(scene, 3, false);
  const auto& st = sim.sensor_state(0);
  ASSERT_FALSE(st.cells.empty());
  EXPECT_EQ(st.cells[0].member_count, 2);  // |dR| = half a cell counts as inside (III-C)
  int members = 0;
  for (const auto& c : st.cells) members += c.member_count;
  EXPECT_LE(members, 5);
}

TEST(HardCaseGeometry, MillionMetresFromOrigin) {
  // The same relative scene at the origin and 1e6 m away: the same target lists within 1e-6.
  const auto make = [](double offset_m) {
    Scene scene = testing::single_sensor_scene(1.0);
    scene.ego = Trajectory({sample(0.0, offset_m, -offset_m, 0.3, 5.0)});
    const double c = std::cos(0.3), s = std::sin(0.3);
    testing::add_object(scene, "car", "passenger_car",
                        {sample(0.0, offset_m + 15.0 * c, -offset_m + 15.0 * s, 0.3 + kPi, 3.0)});
    return scene;
  };
  const Scene near = make(0.0), far = make(1e6);
  SimulationOptions options;
  options.seed = 4;
  Simulation a(near, options), b(far, options);
  for (int k = 0; k < a.cycle_count(); ++k) {
    a.run_cycle(k);
    b.run_cycle(k);
    expect_simulation_finite(b, "far");
    const auto& da = a.sensor_state(0).detections;
    const auto& db = b.sensor_state(0).detections;
    ASSERT_EQ(da.size(), db.size()) << k;
    for (std::size_t i = 0; i < da.size(); ++i) {
      EXPECT_NEAR(da[i].range_m, db[i].range_m, 1e-6);
      EXPECT_NEAR(da[i].azimuth_rad, db[i].azimuth_rad, 1e-6);
      EXPECT_NEAR(da[i].range_rate_mps, db[i].range_rate_mps, 1e-6);
    }
  }
}

TEST(HardCaseGeometry, HundredThousandSeconds) {
  // Ego and car drive together at 10 m/s: at t near 1e5 s they are 1e6 m out, with the same relative
  // geometry as at t = 0.
  Scene scene = testing::single_sensor_scene(1e5 + 1.0);
  scene.ego = Trajectory({sample(0.0, 0.0, 0.0, 0.0, 10.0)});
  testing::add_object(scene, "car", "passenger_car", {sample(0.0, 12.0, 0.5, 0.0, 10.0)});
  SimulationOptions options;
  options.noise = false;
  Simulation early(scene, options), late(scene, options);
  const int first_late = scene.cycle_count() - 20;
  for (int k = 0; k < 20; ++k) {
    early.run_cycle(k);
    late.run_cycle(first_late + k);
    expect_simulation_finite(late, "late cycle");
    EXPECT_GT(late.snapshot().t_s, 1e5);
    const auto& de = early.sensor_state(0).detections;
    const auto& dl = late.sensor_state(0).detections;
    ASSERT_EQ(de.size(), dl.size());
    for (std::size_t i = 0; i < de.size(); ++i) {
      EXPECT_NEAR(de[i].range_m, dl[i].range_m, 1e-6);
      EXPECT_NEAR(de[i].azimuth_rad, dl[i].azimuth_rad, 1e-6);
    }
    EXPECT_EQ(early.sensor_state(0).reported.size(), late.sensor_state(0).reported.size());
  }
}

TEST(HardCaseGeometry, RandomGeometryProperties) {
  // Random sensor poses and objects, every model and effect: finite stages, targets in view,
  // detections at or above the threshold, culling invisible.
  std::mt19937_64 gen(20261122);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const char* models[] = {"passenger_car", "truck_trailer", "pole", "guide_board"};
  for (int trial = 0; trial < 60; ++trial) {
    Scene scene = testing::single_sensor_scene(0.4);
    scene.effects = {trial % 2 == 0, trial % 3 == 0, trial % 4 != 0};
    scene.ego = Trajectory({sample(0.0, 1e3 * u(gen), 1e3 * u(gen), kPi * u(gen), 15.0 * (1.0 + u(gen)))});
    scene.sensors[0].X_VS = {2.0 * u(gen), u(gen), kPi * u(gen)};
    const BodyState ego = scene.ego.state_at(0.0);
    const int n = 1 + trial % 12;
    for (int i = 0; i < n; ++i) {
      // Near the sensor, including on top of it and inside other objects.
      const Vec2 p = ego.X_WB.translation() + Vec2(30.0 * u(gen), 30.0 * u(gen)) * (i == 0 ? 0.05 : 1.0);
      testing::add_object(scene, label("o", i), models[static_cast<std::size_t>(i) % 4],
                          {sample(0.0, p.x(), p.y(), kPi * u(gen), 20.0 * (1.0 + u(gen)))});
    }
    for (const bool culling : {true, false}) {
      SimulationOptions options;
      options.seed = static_cast<std::uint64_t>(trial);
      options.culling = culling;
      Simulation sim(scene, options);
      for (int k = 0; k < sim.cycle_count(); ++k) {
        sim.run_cycle(k);
        const auto& st = sim.sensor_state(0);
        testing::expect_stages_finite(st, label("trial ", trial));
        const auto& fov = scene.sensors[0].config.fov;
        for (const auto& t : st.ideal) {
          if (t.bounce_order != 1) continue;
          EXPECT_LE(t.range_m, fov.max_range_m + 1e-9);
          EXPECT_LE(std::abs(t.azimuth_rad), fov.azimuth_half_rad + 1e-9);
        }
        for (const auto& d : st.detections) {
          if (d.object_index >= 0) {
            EXPECT_GE(d.amplitude_db, scene.sensors[0].config.amplitude.detection_threshold_db);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace rcsim
