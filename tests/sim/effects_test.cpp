// Effects: multibounce (paper V/VI), occlusion, clutter (paper VI).
#include "sim/effects.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/angles.hpp"
#include "common/decibel.hpp"
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

TEST(Effects, MultibounceDuplicatesAtIntegerMultiples) {
  Scene scene = single_sensor_scene();
  scene.effects.multibounce = true;
  add_object(scene, "near", "pole", {sample(0, 1.0, 0.0, 0, -0.5)});
  add_object(scene, "far", "pole", {sample(0, 5.0, 0.0, 0, 0)});
  SimulationOptions o;
  o.level = ListLevel::ideal;
  Simulation sim(scene, o);
  sim.run_cycle(0);
  const auto& t = sim.sensor_state(0).ideal;
  ASSERT_EQ(t.size(), 4u);  // near x1, x2, x3; far only direct (beyond 3 m)
  EXPECT_DOUBLE_EQ(t[2].range_m, 2.0);
  EXPECT_DOUBLE_EQ(t[3].range_m, 3.0);
  EXPECT_DOUBLE_EQ(t[3].range_rate_mps, 3.0 * t[0].range_rate_mps);
  EXPECT_NEAR(t[2].ercs, std::pow(10.0, -6.0 / 20.0), 1e-12);  // 6 dB per extra round trip
  EXPECT_NEAR(t[3].ercs, std::pow(10.0, -12.0 / 20.0), 1e-12);
  EXPECT_EQ(t[3].bounce_order, 3);
}

TEST(Effects, SegmentBoxIntersection) {
  const Pose2 box{5.0, 0.0, 0.3};
  EXPECT_TRUE(segment_hits_box({0, 0}, {10, 0}, box, 4.6, 1.8));
  EXPECT_FALSE(segment_hits_box({0, 0}, {2.4, 0}, box, 4.6, 1.8));  // nearest corner at x = 2.54
  EXPECT_FALSE(segment_hits_box({0, 5}, {10, 5}, box, 4.6, 1.8));
  EXPECT_TRUE(segment_hits_box({5, 0}, {5, 0}, box, 4.6, 1.8));  // degenerate segment inside
}

TEST(Effects, OcclusionHidesWhatIsBehindANearerObject) {
  Scene scene = single_sensor_scene();
  add_object(scene, "behind", "pole", {sample(0, 15.0, 0.0, 0, 0)});
  add_object(scene, "car", "passenger_car", {sample(0, 8.0, 0.0, kPi / 2, 0)});
  SimulationOptions o;
  o.level = ListLevel::ideal;
  {
    Simulation sim(scene, o);
    sim.run_cycle(0);
    bool pole_seen = false;
    for (const auto& t : sim.sensor_state(0).ideal) pole_seen = pole_seen || t.object_index == 0;
    EXPECT_TRUE(pole_seen);
  }
  scene.effects.occlusion = true;
  Simulation sim(scene, o);
  sim.run_cycle(0);
  for (const auto& t : sim.sensor_state(0).ideal) EXPECT_EQ(t.object_index, 1);
  EXPECT_FALSE(sim.sensor_state(0).ideal.empty());
}

TEST(Effects, ClutterRateAndPlacement) {
  const SensorConfig config = builtin_sensor_config("srr24");
  SensorKinematics sensor;
  sensor.v_WS_W = {10.0, 0.0};
  Rng rng(11);
  Detections detections;
  const int cycles = 20000;
  for (int k = 0; k < cycles; ++k) add_clutter(config, sensor, rng, detections);
  EXPECT_NEAR(static_cast<double>(detections.size()) / cycles, config.clutter.false_detections_per_cycle, 0.02);
  for (const auto& d : detections) {
    ASSERT_LE(std::abs(d.azimuth_rad), config.fov.azimuth_half_rad);
    ASSERT_GE(d.amplitude_db, config.amplitude.detection_threshold_db);
    ASSERT_NEAR(d.range_rate_mps, -10.0 * std::cos(d.azimuth_rad), 1e-9);  // stationary
    ASSERT_EQ(d.object_index, -1);
  }
}

TEST(Effects, OffUnlessAsked) {
  Scene scene = single_sensor_scene(2.0);
  add_object(scene, "near", "pole", {sample(0, 1.0, 0.0, 0, 0)});
  Simulation sim(scene, SimulationOptions{ListLevel::detections, 5, true});
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    EXPECT_EQ(sim.sensor_state(0).detections.size(), 1u);  // no duplicates, no clutter
  }
}


// apply_occlusion by hand: a pole 15 m ahead behind a car standing across the line of sight at
// 8 m (yaw 90 deg: its box spans x 7.1 .. 8.9, y -2.3 .. 2.3).
struct OcclusionCase {
  std::vector<SceneObject> objects;
  std::vector<BodyState> states;
  std::vector<unsigned char> candidates = {1, 1};
  IdealTargets ideal;
  OcclusionCase() {
    for (const auto& [model, pose] : {std::pair{"pole", Pose2{15.0, 0.0, 0.0}}, std::pair{"passenger_car", Pose2{8.0, 0.0, kPi / 2}}}) {
      SceneObject o;
      o.id = model;
      o.model_name = model;
      o.model = testing::library().at(model);
      objects.push_back(o);
      BodyState state;
      state.X_WB = pose;
      states.push_back(state);
    }
    // 0: the pole, straight behind the car; 1: the car's side at 7.1 m; 2: a pole target at
    // (15, 5), whose line of sight passes x = 8.9 at y = 2.97 > 2.3: beside the car, not behind it.
    const auto target = [&](double x_m, double y_m, double ercs, int object) {
      IdealTarget& t = ideal.emplace_back();
      t.p_WT_W = {x_m, y_m};
      t.range_m = std::hypot(x_m, y_m);
      t.ercs = ercs;
      t.object_index = object;
    };
    target(15.0, 0.0, 1.0, 0);
    target(7.1, 0.0, 2.0, 1);
    target(15.0, 5.0, 1.0, 0);
  }
  void apply(double loss_db) {
    OcclusionConfig config;
    config.loss_db = loss_db;
    apply_occlusion(config, SensorKinematics{}, objects, states, candidates, ideal);
  }
};

TEST(Effects, OcclusionWithAFiniteLossLowersTheErcsByIt) {
  OcclusionCase c;
  c.apply(10.0);
  ASSERT_EQ(c.ideal.size(), 3u);
  // -10 dB on the ERCS (an amplitude): x 10^(-10/20) = 0.316228; the others unchanged.
  EXPECT_NEAR(c.ideal[0].ercs, 0.31622776601683794, 1e-15);
  EXPECT_NEAR(amplitude_to_db(c.ideal[0].ercs), -10.0, 1e-12);
  EXPECT_EQ(c.ideal[1].ercs, 2.0);
  EXPECT_EQ(c.ideal[2].ercs, 1.0);
  // Twice: another 10 dB (the loss applies per call, once per target however many boxes).
  c.apply(10.0);
  EXPECT_NEAR(c.ideal[0].ercs, 0.1, 1e-14);
  OcclusionCase zero;
  zero.apply(0.0);
  EXPECT_EQ(zero.ideal[0].ercs, 1.0);
  OcclusionCase loss_6db;
  loss_6db.apply(6.0);
  EXPECT_NEAR(loss_6db.ideal[0].ercs, std::pow(10.0, -0.3), 1e-15);  // 0.501187
  // An object that is no candidate (culled out of the view) hides nothing.
  OcclusionCase not_candidate;
  not_candidate.candidates[1] = 0;
  not_candidate.apply(10.0);
  EXPECT_EQ(not_candidate.ideal[0].ercs, 1.0);
}

TEST(Effects, OcclusionWithAnInfiniteLossRemovesTheTarget) {
  OcclusionCase c;
  c.apply(std::numeric_limits<double>::infinity());
  ASSERT_EQ(c.ideal.size(), 2u);
  EXPECT_EQ(c.ideal[0].object_index, 1);  // the car's side, then the pole beside it, in order
  EXPECT_EQ(c.ideal[0].ercs, 2.0);
  EXPECT_EQ(c.ideal[1].p_WT_W, Vec2(15.0, 5.0));
  EXPECT_EQ(c.ideal[1].ercs, 1.0);
  EXPECT_TRUE(std::isinf(OcclusionConfig{}.loss_db));  // the default: the paper's hiding
}

TEST(Effects, OcclusionLossIsReadFromTheSensorConfiguration) {
  EXPECT_TRUE(std::isinf(builtin_sensor_config("srr24").occlusion.loss_db));
  nlohmann::json doc = testing::builtin_sensor_json("srr24");
  const nlohmann::json lrr = testing::builtin_sensor_json("aimotive_lrr");
  ASSERT_TRUE(lrr.contains("occlusion"));  // the 77 GHz profile weakens, does not hide
  EXPECT_EQ(builtin_sensor_config("aimotive_lrr").occlusion.loss_db, lrr["occlusion"]["loss_db"].get<double>());
  ASSERT_FALSE(doc.is_null());
  doc["occlusion"] = {{"loss_db", 6.5}};
  EXPECT_EQ(parse_sensor_config(JsonField(doc, "s.json", "")).occlusion.loss_db, 6.5);
  for (const double bad : {-1.0, 1e6}) {
    doc["occlusion"] = {{"loss_db", bad}};
    try {
      parse_sensor_config(JsonField(doc, "s.json", ""));
      FAIL() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("occlusion.loss_db"), std::string::npos) << e.what();
    }
  }
}

TEST(Effects, OcclusionLossInTheSensorCycle) {
  // The scene of OcclusionHidesWhatIsBehindANearerObject with a 10-dB loss: the pole stays, its
  // ERCS 10 dB down; the car's targets are those without occlusion.
  Scene scene = single_sensor_scene();
  add_object(scene, "behind", "pole", {sample(0, 15.0, 0.0, 0, 0)});
  add_object(scene, "car", "passenger_car", {sample(0, 8.0, 0.0, kPi / 2, 0)});
  SimulationOptions o;
  o.level = ListLevel::ideal;
  Simulation open(scene, o);
  open.run_cycle(0);
  scene.effects.occlusion = true;
  scene.sensors[0].config.occlusion.loss_db = 10.0;
  Simulation weakened(scene, o);
  weakened.run_cycle(0);
  const auto& a = open.sensor_state(0).ideal;
  const auto& b = weakened.sensor_state(0).ideal;
  ASSERT_EQ(a.size(), b.size());
  int poles = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].object_index, b[i].object_index);
    if (a[i].object_index == 0) {
      ++poles;
      EXPECT_NEAR(b[i].ercs, a[i].ercs * std::pow(10.0, -0.5), 1e-15);
      // and its echo 10 dB weaker: eq. (3) is linear in the ERCS
      EXPECT_NEAR(amplitude_to_db(weakened.sensor_state(0).echoes[i].amplitude),
                  amplitude_to_db(open.sensor_state(0).echoes[i].amplitude) - 10.0, 1e-9);
    } else {
      EXPECT_EQ(b[i].ercs, a[i].ercs);
    }
  }
  EXPECT_EQ(poles, 1);
}

}  // namespace
}  // namespace rcsim
