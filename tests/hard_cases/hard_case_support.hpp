#pragma once
// Shared checks of the hard-case suite: no NaN or infinity leaves any stage of the sensor cycle.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace rcsim::testing {

inline bool finite(double x) { return std::isfinite(x); }
inline bool finite(const std::complex<double>& z) { return std::isfinite(z.real()) && std::isfinite(z.imag()); }

// Every output of every stage of one sensor cycle: ideal targets, echoes, cells, detections,
// reported targets and the tracker's table (states and covariances).
inline void expect_stages_finite(const SensorCycleState& st, const std::string& where) {
  for (const auto& t : st.ideal) {
    EXPECT_TRUE(finite(t.p_WT_W.x()) && finite(t.p_WT_W.y()) && finite(t.range_m) && finite(t.azimuth_rad) &&
                finite(t.sin_azimuth) && finite(t.cos_azimuth) && finite(t.range_rate_mps) && finite(t.ercs))
        << where << ": ideal target of object " << t.object_index;
    EXPECT_GE(t.range_m, 0.0) << where;
  }
  for (const auto& e : st.echoes) {
    EXPECT_TRUE(finite(e.range_m) && finite(e.range_rate_mps) && finite(e.amplitude) && finite(e.sum_pointer) &&
                finite(e.delta_pointer))
        << where << ": echo";
  }
  for (const auto& c : st.cells) {
    EXPECT_TRUE(finite(c.range_m) && finite(c.range_rate_mps) && finite(c.amplitude_upper) && finite(c.sum_pointer) &&
                finite(c.delta_pointer))
        << where << ": cell";
  }
  for (const auto& d : st.detections) {
    EXPECT_TRUE(finite(d.range_m) && finite(d.azimuth_rad) && finite(d.range_rate_mps) && finite(d.amplitude_db))
        << where << ": detection";
    EXPECT_LE(std::abs(d.azimuth_rad), 0.5 * kPi + 1e-12) << where;
  }
  for (const auto& r : st.reported) {
    EXPECT_TRUE(finite(r.range_m) && finite(r.azimuth_rad) && finite(r.range_rate_mps) && finite(r.amplitude_db))
        << where << ": reported target " << r.id;
  }
  for (const auto& t : st.tracker.tracks()) {
    EXPECT_TRUE(t.x.allFinite() && t.P.allFinite()) << where << ": track " << t.id;
  }
}

inline void expect_simulation_finite(const Simulation& sim, const std::string& where) {
  for (std::size_t s = 0; s < sim.sensor_count(); ++s) expect_stages_finite(sim.sensor_state(s), where);
}

// An object model with one plane reflector: a full circle of radius_m about the origin.
inline ObjectModel plane_circle_model(double radius_m) {
  ObjectModel m;
  m.name = "circle";
  m.length_m = 2.0 * radius_m;
  m.width_m = 2.0 * radius_m;
  PlaneReflector p;
  p.radius_m = radius_m;
  p.set_arc(0.0, kTwoPi);
  p.ercs = 10.0;
  m.planes.push_back(p);
  return m;
}

// An object model with point reflectors visible from everywhere, at the given positions.
inline ObjectModel points_model(const std::vector<Vec2>& p_OR_O, double ercs = 5.0) {
  ObjectModel m;
  m.name = "points";
  m.length_m = 0.5;
  m.width_m = 0.5;
  for (const auto& p : p_OR_O) {
    PointReflector r;
    r.p_OR_O = p;
    r.ercs_max = ercs;
    r.visibility = VisibilityFunction(0.0, kPi, 0.0);
    m.points.push_back(r);
  }
  return m;
}

inline void add_model_object(Scene& scene, const std::string& id, const ObjectModel& model,
                             const std::vector<TrajectorySample>& samples) {
  SceneObject object;
  object.id = id;
  object.model_name = model.name;
  object.model = model;
  object.trajectory = Trajectory(samples);
  scene.objects.push_back(object);
}

}  // namespace rcsim::testing
