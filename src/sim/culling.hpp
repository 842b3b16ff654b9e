#pragma once
// The broad phase of the sensor cycle: objects that cannot produce or change a target are skipped
// before their reflection centers are visited (docs/fidelity.md, "Culling").
#include <span>
#include <vector>

#include "scene/scene.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim {

// Per sensor and scene, built once. An object is skipped when the distance from the sensor to its
// origin exceeds cull_distance_m (range bound below), or when its bounding circle lies outside the
// view wedge by more than a margin (no reflection point of it can pass the view check).
struct CullingBounds {
  bool by_range = false;
  bool by_view = false;
  double cos_half = 0.0, sin_half = 1.0;  // of the view field's half angle
  std::vector<double> cull_distance_m;  // per object: detectable range bound + bounding radius
  std::vector<double> radius_m;         // per object: circle about its origin holding every reflection point
};

// The farthest a plane reflector's reflection point (on its arc, plane_reflection_point_O) can lie
// from the object origin: |centre| + radius if the arc covers the centre's direction, else the
// farther arc end. Flat sides are arcs of large circles: the whole circle would be far too loose.
double arc_reach_m(const PlaneReflector& plane);
// A circle about the object origin that holds every reflection point (points and plane arcs).
double reflection_radius_m(const ObjectModel& model);

// The range bound, from the amplitude law, eq. (1): A_ref(R) = 10^((L0 - s R) / 20), |H_sum| <= 1.
// Removing an echo X from the cell formation (eqs. (4)-(5), strongest first) can change only
//  (a) a cell containing X: its members lie within one range cell of X, so its upper amplitude is at
//      most A_ref(R_X - range_cell) * (sum of every ERCS in the scene, multibounce copies included);
//  (b) a cell formed after X's: every member is weaker than X, so its upper amplitude is at most
//      N_echoes * A_X <= N_echoes * A_ref(R_X) * max_ercs(object of X).
// Echoes of an object whose nearest reflection point is beyond both bounds (plus a 1 dB margin) can
// only change cells below the threshold, which yield no entry (III-C) and draw no noise: the output
// is identical. Range culling is off at ListLevel::ideal (the ideal list shows every echo) and
// when the slope s is not positive.
CullingBounds make_culling_bounds(const SensorConfig& config, const Effects& effects,
                                  std::span<const SceneObject> objects, bool range_culling, bool view_culling);

// The per-sensor pass of the broad phase for object i, whose origin lies at p_SO_S (sensor frame),
// distance2_m2 from the sensor: false when it is outside the view wedge by more than its
// reflection circle (plus a margin), or beyond the view range plus that circle, or beyond its
// cull distance. Before the range tests, sets *may_occlude (when given) to 1 if the object can lie
// on a line of sight to a point in view (a far or faint object still hides what is behind it).
bool keep_object(const CullingBounds& bounds, const FieldOfView& fov, std::size_t i, const Vec2& p_SO_S,
                 double distance2_m2, unsigned char* may_occlude);

}  // namespace rcsim
