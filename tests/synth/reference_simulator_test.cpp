// The reference simulator's recordings: targets and imperfect annotations of a close car, its
// independence from the reflection-center model, and the objects it refuses. (Its objects,
// propagation and tracker alone: scatterers_test.cpp, propagation_test.cpp, synth_tracker_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "synth/reference_simulator.hpp"
#include "test_support.hpp"

namespace rcsim::synth {
namespace {

namespace fs = std::filesystem;

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
