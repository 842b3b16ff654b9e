// The whole sensor cycle (paper Fig. 13) on scenes whose answers follow from the equations by hand.
#include "sim/sensor_cycle.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"
#include "sensor_json.hpp"

namespace rcsim {
namespace {

using testing::add_object;
using testing::sample;
using testing::single_sensor_scene;

SimulationOptions exact(ListLevel level) {
  SimulationOptions o;
  o.level = level;
  o.noise = false;
  return o;
}

Scene pole_at(double range_m, double azimuth_rad) {
  Scene scene = single_sensor_scene();
  add_object(scene, "pole", "pole",
             {sample(0, range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad), 0, 0)});
  return scene;
}

TEST(SensorCycle, ReferenceReflectorAmplitudeAtBoresight) {
  const Scene scene = pole_at(10.0, 0.0);
  Simulation sim(scene, exact(ListLevel::detections));
  sim.run_cycle(0);
  const auto& d = sim.sensor_state(0).detections;
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(d[0].amplitude_db, 19.0, 1e-9);  // eq. (1): 26.5 - 0.75 * 10
  EXPECT_NEAR(d[0].range_m, 10.0, 1e-12);
  EXPECT_NEAR(d[0].azimuth_rad, 0.0, 1e-12);
  EXPECT_NEAR(d[0].range_rate_mps, 0.0, 1e-12);
}

TEST(SensorCycle, ReferenceReflectorDropsBelowThresholdAt27Point3m) {
  // 26.5 - 0.75 R = 6 dB  =>  R = 27.333 m
  for (const auto& [range_m, expected] : {std::pair{27.30, 1u}, std::pair{27.36, 0u}}) {
    const Scene scene = pole_at(range_m, 0.0);
    Simulation sim(scene, exact(ListLevel::detections));
    sim.run_cycle(0);
    EXPECT_EQ(sim.sensor_state(0).detections.size(), expected) << range_m << " m";
  }
}

TEST(SensorCycle, LoneReflectorAngleIsExactAcrossTheViewField) {
  for (double deg = -34.0; deg <= 34.0; deg += 2.0) {
    const Scene scene = pole_at(8.0, deg_to_rad(deg));
    Simulation sim(scene, exact(ListLevel::detections));
    sim.run_cycle(0);
    const auto& d = sim.sensor_state(0).detections;
    ASSERT_EQ(d.size(), 1u) << deg;
    EXPECT_NEAR(d[0].azimuth_rad, deg_to_rad(deg), 1e-12) << deg << " deg";
    EXPECT_NEAR(d[0].range_m, 8.0, 1e-12);
    // eq. (2): the amplitude follows the sum pattern
    const MonopulseAntenna antenna{AntennaGeometry{}};
    EXPECT_NEAR(d[0].amplitude_db, 20.5 + 20 * std::log10(antenna.sum_magnitude(deg_to_rad(deg))), 1e-9);
  }
}

TEST(SensorCycle, OutsideTheViewFieldNothingIsSeen) {
  const Scene scene = pole_at(8.0, deg_to_rad(36.0));
  Simulation sim(scene, exact(ListLevel::ideal));
  sim.run_cycle(0);
  EXPECT_TRUE(sim.sensor_state(0).ideal.empty());
}

TEST(SensorCycle, TwoEqualReflectorsInOneCellMergeToTheMiddle) {
  // Paper Fig. 10: two reflectors at 10 and 20 deg, same range and range rate, one cell.
  Scene scene = single_sensor_scene();
  for (const double deg : {10.0, 20.0}) {
    add_object(scene, "pole" + std::to_string(int(deg)), "pole",
               {sample(0, 12.0 * std::cos(deg_to_rad(deg)), 12.0 * std::sin(deg_to_rad(deg)), 0, 0)});
  }
  Simulation sim(scene, exact(ListLevel::detections));
  sim.run_cycle(0);
  const auto& d = sim.sensor_state(0).detections;
  ASSERT_EQ(d.size(), 1u);
  // By hand from eqs. (6)-(8): sum both pointers, invert eq. (7): 14.7410 deg.
  EXPECT_NEAR(rad_to_deg(d[0].azimuth_rad), 14.741019656, 1e-6);
  EXPECT_NEAR(rad_to_deg(d[0].azimuth_rad), 15.0, 0.3);
}

TEST(SensorCycle, RangeRateIncludesYawRateAndMountingOffset) {
  // Ego turning on the spot at 0.5 rad/s; sensor 3.7 m ahead of the ego origin, looking left.
  // Its velocity is omega x r = (0, 1.85) m/s; a pole 10 m to its left sees it approach at 1.85 m/s.
  Scene scene = single_sensor_scene();
  auto ego = sample(0, 0, 0, 0, 0);
  ego.yaw_rate_radps = 0.5;
  scene.ego = Trajectory({ego});
  scene.sensors[0].X_VS = {3.7, 0.0, kPi / 2};
  add_object(scene, "pole", "pole", {sample(0, 3.7, 10.0, 0, 0)});
  Simulation sim(scene, exact(ListLevel::ideal));
  sim.run_cycle(0);
  const auto& t = sim.sensor_state(0).ideal;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].range_rate_mps, -1.85, 1e-12);
  EXPECT_NEAR(t[0].azimuth_rad, 0.0, 1e-12);
}

TEST(SensorCycle, RangeRateIncludesTheTargetsYawRate) {
  // A pole reflector mounted 2 m ahead of a body spinning at 1 rad/s about a centre 10 m ahead
  // of the sensor: the reflector at (12, 0) moves with (0, 2) m/s: perpendicular, range rate 0.
  // One mounted 2 m to the left at (10, 2) moves with (-2, 0): range rate -2 * 10/|(10, 2)|.
  Scene scene = single_sensor_scene();
  ObjectModel model = testing::library().at("pole");
  model.points[0].p_OR_O = {0.0, 2.0};
  SceneObject object;
  object.id = "spinner";
  object.model_name = "custom";
  object.model = model;
  auto s = sample(0, 10.0, 0.0, 0.0, 0.0);
  s.yaw_rate_radps = 1.0;
  object.trajectory = Trajectory({s});
  scene.objects.push_back(object);
  Simulation sim(scene, exact(ListLevel::ideal));
  sim.run_cycle(0);
  const auto& t = sim.sensor_state(0).ideal;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].range_rate_mps, -2.0 * 10.0 / std::hypot(10.0, 2.0), 1e-12);
}

TEST(SensorCycle, PerpendicularCrossingHoldsLateralPositionThenFollowsCorner) {
  // Paper Fig. 4/5: a car crosses 6 m ahead from left to right at 2 m/s (yaw -90 deg).
  Scene scene = single_sensor_scene(8.0);
  add_object(scene, "car", "passenger_car", {sample(0, 6.9, 8.0, -kPi / 2, 2.0)});
  Simulation sim(scene, exact(ListLevel::detections));
  std::vector<std::pair<double, double>> side, corner;  // (car y, nearest target's lateral y)
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    const auto& detections = sim.sensor_state(0).detections;
    if (detections.empty()) continue;
    const Detection* nearest = &detections[0];
    for (const auto& d : detections) {
      if (d.range_m < nearest->range_m) nearest = &d;
    }
    const double car_y_m = sim.snapshot().objects[0].X_WB.y_m;
    const double lateral_m = nearest->range_m * std::sin(nearest->azimuth_rad);
    if (std::abs(car_y_m) < 1.0) side.emplace_back(car_y_m, lateral_m);
    if (car_y_m < -3.2 && car_y_m > -4.5) corner.emplace_back(car_y_m, lateral_m);
  }
  // Least-squares slope of the nearest target's lateral position against the car's position.
  const auto slope = [](const std::vector<std::pair<double, double>>& xy) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const auto& [x, y] : xy) {
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
    }
    const double n = static_cast<double>(xy.size());
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
  };
  // While the side faces the sensor, the nearest target stays put (wheel houses in the same cell
  // make it wobble by some centimetres) although the car moves 2 m.
  ASSERT_GT(side.size(), 20u);
  EXPECT_LT(std::abs(slope(side)), 0.15);
  for (const auto& [car, lateral] : side) EXPECT_NEAR(lateral, 0.0, 0.25) << "car at " << car;
  // Then the rear corner (2.3 m behind the centre) carries it: lateral = car y + 2.3, slope 1.
  ASSERT_GT(corner.size(), 5u);
  EXPECT_NEAR(slope(corner), 1.0, 0.1);
  for (const auto& [car, lateral] : corner) EXPECT_NEAR(lateral, car + 2.3, 0.2) << "car at " << car;
}

TEST(SensorCycle, SidePlaneReflectionPointBarelyMovesWithTheCar) {
  // Ideal level: the side plane's reflection point is the foot of the line to its circle centre;
  // with the model's 72 m radius it moves d/(r+d) = 6/78 of the car's motion.
  Scene scene = single_sensor_scene(1.0);
  add_object(scene, "car", "passenger_car", {sample(0, 6.9, 0.5, -kPi / 2, 2.0)});
  Simulation sim(scene, exact(ListLevel::ideal));
  std::vector<double> lateral;
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    for (const auto& t : sim.sensor_state(0).ideal) {
      if (t.kind == ReflectorKind::Plane) lateral.push_back(t.p_WT_W.y());
    }
  }
  ASSERT_EQ(lateral.size(), static_cast<std::size_t>(sim.cycle_count()));
  const double car_motion_m = 2.0 * scene.cycle_time_at(sim.cycle_count() - 1);
  EXPECT_NEAR(lateral.front() - lateral.back(), car_motion_m * 6.02 / (72.2 + 6.02), 0.01);
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

TEST(SensorCyclePresence, AnObjectTakesPartOnlyWhilePresent) {
  // A pole at 10 m, present only from 0.2 s to 0.4 s; a guide board between it and the sensor,
  // present only until 0.3 s, hides it while both are there (occlusion on).
  Scene scene = testing::single_sensor_scene(1.0);
  scene.effects.occlusion = true;
  testing::add_object(scene, "pole", "pole", {testing::sample(0, 10.0, 0.0, 0, 0)});
  scene.objects.back().presence = {{0.2, 0.4}};
  testing::add_object(scene, "board", "guide_board", {testing::sample(0, 5.0, 0.0, kPi / 2, 0)});
  scene.objects.back().presence = {{-1.0, 0.3}};
  SimulationOptions options;
  options.level = ListLevel::ideal;
  options.noise = false;
  Simulation sim(scene, options);
  const auto pole_targets = [&](double t_s) {
    sim.run_at(t_s);
    int n = 0;
    for (const auto& t : sim.sensor_state(0).ideal) n += t.object_index == 0;
    return n;
  };
  EXPECT_EQ(pole_targets(0.1), 0);   // not yet present
  EXPECT_EQ(pole_targets(0.25), 0);  // present, but behind the board
  EXPECT_EQ(pole_targets(0.35), 1);  // the board has gone
  EXPECT_EQ(pole_targets(0.5), 0);   // gone itself
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

TEST(SensorCycleReports, DetectionsWithoutTrackingSectionParse) {
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  ASSERT_FALSE(doc.is_null());
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).reports, ListLevel::tracks);  // absent: tracks
  doc["reports"] = "detections";
  doc.erase("tracking");
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).reports, ListLevel::detections);
  EXPECT_EQ(builtin_sensor_config("aimotive_lrr").reports, ListLevel::detections);
  // A tracker needs its section.
  doc["reports"] = "tracks";
  EXPECT_NE(testing::sensor_config_error(doc).find("tracking"), std::string::npos) << testing::sensor_config_error(doc);
  doc.erase("reports");
  EXPECT_NE(testing::sensor_config_error(doc).find("tracking"), std::string::npos) << testing::sensor_config_error(doc);
  doc["reports"] = "foo";
  doc["tracking"] = testing::builtin_sensor_json("srr24")["tracking"];
  EXPECT_NE(testing::sensor_config_error(doc).find("reports"), std::string::npos) << testing::sensor_config_error(doc);
  EXPECT_NE(testing::sensor_config_error(doc).find("foo"), std::string::npos) << testing::sensor_config_error(doc);
}

TEST(SensorCycleReports, ASensorThatReportsDetectionsReportsThemAtTheTracksLevel) {
  // Two poles and a car, noise and clutter on: at the tracks level the sensor reports, cycle by
  // cycle, exactly the detections the detections level gives with the same seed (no tracker: no
  // 4-hit confirmation, so already in the first cycle).
  Scene scene = testing::single_sensor_scene(0.6);
  scene.effects.clutter = true;
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  doc["reports"] = "detections";
  doc.erase("tracking");
  scene.sensors[0].config = parse_sensor_config(JsonField(doc, "s.json", ""));
  testing::add_object(scene, "pole", "pole", {testing::sample(0, 10.0, 1.0, 0, 0)});
  testing::add_object(scene, "pole2", "pole", {testing::sample(0, 14.0, -3.0, 0, 0)});
  testing::add_object(scene, "car", "passenger_car", {testing::sample(0, 20.0, 2.0, kPi, 3.0)});
  SimulationOptions at_tracks;
  at_tracks.level = ListLevel::tracks;
  at_tracks.seed = 11;
  SimulationOptions at_detections = at_tracks;
  at_detections.level = ListLevel::detections;
  Simulation tracks(scene, at_tracks), detections(scene, at_detections);
  ASSERT_GT(tracks.cycle_count(), 10);
  std::size_t total = 0;
  for (int k = 0; k < tracks.cycle_count(); ++k) {
    tracks.run_cycle(k);
    detections.run_cycle(k);
    const auto& reported = tracks.sensor_state(0).reported;
    const auto& detected = detections.sensor_state(0).detections;
    ASSERT_EQ(reported.size(), detected.size()) << "cycle " << k;
    if (k == 0) {
      EXPECT_GE(reported.size(), 3u);
    }
    for (std::size_t i = 0; i < reported.size(); ++i) {
      EXPECT_EQ(reported[i].range_m, detected[i].range_m) << "cycle " << k;
      EXPECT_EQ(reported[i].azimuth_rad, detected[i].azimuth_rad) << "cycle " << k;
      EXPECT_EQ(reported[i].amplitude_db, detected[i].amplitude_db) << "cycle " << k;
    }
    total += reported.size();
  }
  EXPECT_GT(total, 3u * static_cast<std::size_t>(tracks.cycle_count()));
  // The same scene with the srr24's tracker reports nothing in the first three cycles (III-E).
  scene.sensors[0].config = builtin_sensor_config("srr24");
  Simulation tracked(scene, at_tracks);
  for (int k = 0; k < 3; ++k) {
    tracked.run_cycle(k);
    EXPECT_TRUE(tracked.sensor_state(0).reported.empty()) << "cycle " << k;
  }
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

// The model does not care where a relative scale puts its zero: the same radar with every level
// (law, threshold, noise floor) 100 dB lower detects the same cells, at amplitudes 100 dB lower.
TEST(SensorCycleNoiseFloor, AShiftedRelativeScaleDetectsTheSameCells) {
  const auto detections_with = [](double shift_db) {
    nlohmann::json doc = testing::builtin_sensor_json("astyx_hires");
    doc["amplitude"]["snr_at_1m_for_1m2_db"] = doc["amplitude"]["snr_at_1m_for_1m2_db"].get<double>() + shift_db;
    doc["amplitude"]["detection_threshold_db"] = doc["amplitude"]["detection_threshold_db"].get<double>() + shift_db;
    doc["amplitude"]["noise_floor_db"] = shift_db;
    doc.erase("background");
    Scene scene = testing::single_sensor_scene(0.5);
    scene.sensors[0].config = parse_sensor_config(JsonField(doc, "s.json", ""));
    scene.cycle_time_s = scene.sensors[0].config.cycle_time_s;
    testing::add_object(scene, "car", "passenger_car", {testing::sample(0.0, 15.0, 2.0, 0.3, 0.0)});
    SimulationOptions options;
    options.level = ListLevel::detections;
    options.seed = 5;
    Simulation simulation(scene, options);
    std::vector<Detection> all;
    for (int k = 0; k < simulation.cycle_count(); ++k) {
      simulation.run_cycle(k);
      const Detections& d = simulation.sensor_state(0).detections;
      all.insert(all.end(), d.begin(), d.end());
    }
    return all;
  };
  const std::vector<Detection> reference = detections_with(0.0), shifted = detections_with(-100.0);
  ASSERT_GT(reference.size(), 10u);
  ASSERT_EQ(shifted.size(), reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    EXPECT_NEAR(shifted[i].amplitude_db, reference[i].amplitude_db - 100.0, 1e-6);
    EXPECT_NEAR(shifted[i].azimuth_rad, reference[i].azimuth_rad, 1e-9);
    EXPECT_NEAR(shifted[i].range_m, reference[i].range_m, 1e-9);
  }
}

}  // namespace
}  // namespace rcsim
