// The reference simulator's objects, propagation, tracker and recordings: physics it models that
// the reflection-center model does not, and its independence from that model.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/angles.hpp"
#include "synth/propagation.hpp"
#include "synth/reference_simulator.hpp"
#include "synth/scatterers.hpp"
#include "synth/synth_tracker.hpp"
#include "test_support.hpp"

namespace rcsim::synth {
namespace {

namespace fs = std::filesystem;

TEST(SynthScatterers, CarOutlineTouchesItsBoxAndFacesOutwards) {
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  double max_x = 0.0, max_y = 0.0;
  int facets = 0;
  for (const auto& s : car.scatterers) {
    EXPECT_LE(std::abs(s.p_O.x()), 2.3 + 1e-9);
    EXPECT_LE(std::abs(s.p_O.y()), 0.9 + 1e-9);
    if (s.kind != ScattererKind::facet) continue;
    ++facets;
    max_x = std::max(max_x, std::abs(s.p_O.x()));
    max_y = std::max(max_y, std::abs(s.p_O.y()));
    // The normal points away from the centre.
    EXPECT_GT(s.p_O.dot(Vec2(std::cos(s.axis_rad), std::sin(s.axis_rad))), 0.0);
  }
  EXPECT_GT(facets, 100);  // dense along the contour
  EXPECT_NEAR(max_x, 2.3, 0.01);
  EXPECT_NEAR(max_y, 0.9, 0.01);
}

TEST(SynthScatterers, FacetIsSpecular) {
  Scatterer f;
  f.kind = ScattererKind::facet;
  f.facet_length_m = 0.1;
  f.strength = 0.1 * 0.2;
  const double lambda = 0.0125;
  // Physical optics at normal incidence: sqrt(4 pi) A / lambda.
  EXPECT_NEAR(facet_sqrt_rcs_m(f, 0.0, lambda), std::sqrt(4.0 * kPi) * 0.02 / lambda, 1e-9);
  // First null at sin(theta) = lambda / (2 ds); nothing from behind.
  EXPECT_NEAR(facet_sqrt_rcs_m(f, std::asin(lambda / 0.2), lambda), 0.0, 1e-9);
  EXPECT_EQ(facet_sqrt_rcs_m(f, 2.0, lambda), 0.0);
}

TEST(SynthPropagation, NearerBodyHidesTheOneBehind) {
  const SynthConfig config;
  const Propagator p(config);
  const ScattererBody pole = make_body("pole", 0.1, 0.1);
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  SensorState sensor;  // at the origin, looking along +x
  BodyState behind, wall;
  behind.X_WB = {15.0, 0.0, 0.0};
  wall.X_WB = {8.0, 0.0, kPi / 2};  // a car broadside across the line of sight
  const auto alone = p.echoes(sensor, {PlacedBody{&pole, behind}}, {});
  ASSERT_EQ(alone.size(), 1u);
  const auto hidden = p.echoes(sensor, {PlacedBody{&pole, behind}, PlacedBody{&car, wall}}, {});
  for (const auto& e : hidden) EXPECT_LT(e.range_m, 10.0);
}

TEST(SynthPropagation, BackAndForthEchoesAtShortRangeOnly) {
  const SynthConfig config;
  const Propagator p(config);
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  SensorState sensor;
  BodyState near_car, far_car;
  near_car.X_WB = {1.0 + 2.3, 0.0, kPi};  // front 1 m ahead, facing the sensor
  far_car.X_WB = {6.0 + 2.3, 0.0, kPi};
  const auto count_beyond = [](const std::vector<Echo>& echoes, double r_m) {
    int n = 0;
    for (const auto& e : echoes) n += e.range_m > r_m && std::abs(std::remainder(e.range_m, 1.0)) < 0.05 ? 1 : 0;
    return n;
  };
  const auto near_echoes = p.echoes(sensor, {PlacedBody{&car, near_car}}, {});
  double direct = 0.0, double_bounce = 0.0;
  for (const auto& e : near_echoes) {
    if (std::abs(e.range_m - 1.0) < 0.02) direct = std::max(direct, std::abs(e.sum));
    if (std::abs(e.range_m - 2.0) < 0.04) double_bounce = std::max(double_bounce, std::abs(e.sum));
  }
  EXPECT_GT(direct, 0.0);
  EXPECT_GT(double_bounce, 0.0);
  EXPECT_GT(count_beyond(near_echoes, 1.9), 0);
  for (const auto& e : p.echoes(sensor, {PlacedBody{&car, far_car}}, {})) EXPECT_LT(e.range_m, 11.0);
}

TEST(SynthTracker, ConfirmsAfterFourHitsAndDropsAfterMisses) {
  TrackerConfig config;
  SynthTracker tracker(config, 0.04);
  Detection d;
  d.range_m = 10.0;
  d.range_rate_mps = -2.0;
  d.azimuth_rad = 0.1;
  d.amplitude_db = 15.0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(tracker.step({d}).empty()) << k;
    d.range_m += d.range_rate_mps * 0.04;
  }
  const auto reported = tracker.step({d});
  ASSERT_EQ(reported.size(), 1u);
  EXPECT_NEAR(reported[0].range_m, d.range_m, 0.05);
  EXPECT_NEAR(reported[0].range_rate_mps, -2.0, 0.1);
  // Missed: not reported while coasting, deleted after max_misses_confirmed + 1 misses.
  EXPECT_TRUE(tracker.step({}).empty());
  EXPECT_EQ(tracker.tracks().size(), 1u);
  for (int k = 0; k < config.max_misses_confirmed; ++k) tracker.step({});
  EXPECT_TRUE(tracker.tracks().empty());
  // A false detection that never repeats never reaches the target list.
  SynthTracker other(config, 0.04);
  d.range_m = 20.0;
  EXPECT_TRUE(other.step({d}).empty());
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(other.step({}).empty());
}

TEST(SynthReference, CarCloseByGivesSeveralTargetsAndAnnotationsAreImperfect) {
  Scene scene = testing::single_sensor_scene(1.0);
  testing::add_object(scene, "car", "passenger_car", {testing::sample(0.0, 6.0, 1.0, -2.4, 3.0)});
  const Recording rec = make_recording(scene, SynthConfig{}, 4, {"close_car", "", "test"});
  ASSERT_EQ(rec.ego.size(), static_cast<std::size_t>(scene.cycle_count()));
  std::vector<int> per_cycle(rec.ego.size(), 0);
  for (const auto& t : rec.targets) {
    EXPECT_EQ(t.t_s, rec.ego[t.cycle].t_s);
    EXPECT_GE(t.id, 0);
    ++per_cycle[t.cycle];
  }
  // A car approaching obliquely within a few metres: several targets, none before the 4th cycle.
  EXPECT_EQ(per_cycle[0] + per_cycle[1] + per_cycle[2], 0);
  EXPECT_GE(*std::max_element(per_cycle.begin(), per_cycle.end()), 2);
  EXPECT_LE(*std::max_element(per_cycle.begin(), per_cycle.end()), 15);
  ASSERT_EQ(rec.objects.size(), 1u);
  EXPECT_EQ(rec.objects[0].object_class, "passenger_car");
  double max_error_m = 0.0, sum_error_m = 0.0;
  for (const auto& b : rec.boxes[0]) {
    const auto truth = scene.objects[0].trajectory.state_at(b.t_s);
    const double e = std::hypot(b.x_m - truth.X_WB.x_m, b.y_m - truth.X_WB.y_m);
    max_error_m = std::max(max_error_m, e);
    sum_error_m += e;
  }
  EXPECT_GT(sum_error_m / static_cast<double>(rec.boxes[0].size()), 0.005);  // not the truth
  EXPECT_LT(max_error_m, 0.25);                         // but a few centimetres
}

// Independence (docs/synth.md): the reference uses neither the reflection-center object models nor the
// sensor model's stages. It reads what a sensor profile states about the radar (carrier, cells,
// field of view, cycle time, the scale its amplitude reads on: AmplitudeLawKind), never the
// model's amplitude law itself (AmplitudeLaw).
TEST(SynthReference, IndependentOfTheReflectionCenterModel) {
  const fs::path dir = fs::path(RCSIM_SOURCE_DIR) / "src" / "synth";
  const std::regex forbidden(R"(#include\s*"(sim|sensor)/|PointReflector|PlaneReflector|VisibilityFunction|\.points\b|\.planes\b|ercs|MonopulseAntenna|rcsim::Simulation\b|SensorConfig::|AmplitudeLaw\b|ResolutionCell)");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    ++files;
    std::smatch m;
    const std::string s = text.str();
    EXPECT_FALSE(std::regex_search(s, m, forbidden)) << entry.path() << " uses " << m.str();
  }
  EXPECT_GE(files, 10);
}

// A polyline (guard rail) is no body the reference has a model of: refused by name, not drawn as
// a point at its mean.
TEST(ReferenceSimulator, RefusesPolylineObjects) {
  Scene scene = testing::single_sensor_scene(0.2);
  SceneObject rail;
  rail.id = "rail_left";
  rail.model_name = "guard_rail";
  rail.model = expand_polyline(testing::library().at("guard_rail"), {{10.0, 3.5}, {-10.0, 3.5}});
  rail.trajectory = Trajectory({testing::sample(0.0, 0.0, 0.0, 0.0, 0.0)});
  scene.objects.push_back(rail);
  try {
    ReferenceSimulator simulator(scene, SynthConfig{}, 1);
    FAIL() << "a polyline was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rail_left"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsim::synth
