#include "sim/culling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angles.hpp"
#include "sim/amplitude.hpp"
#include "sim/detection.hpp"
#include "sim/effects.hpp"
#include "sim/visibility.hpp"

namespace rcsim {
namespace {
constexpr double kMarginDb = 1.0;  // against rounding in the amplitude chain
}  // namespace

double arc_reach_m(const PlaneReflector& plane) {
  // |c + r u|^2 = |c|^2 + r^2 + 2 r c.u is largest at u along c and falls off monotonically on
  // either side: on an arc that does not cover c's direction, the farthest point is an end.
  const Vec2& c = plane.center_O;
  if (c.squaredNorm() == 0.0 || plane.covers_direction(c)) return c.norm() + plane.radius_m;
  // A degenerate arc (no span) passes covers_direction for its own direction and the opposite one.
  if (!(plane.span_rad > 0.0)) {
    return std::max((c + plane.radius_m * plane.u_start_O).norm(), (c - plane.radius_m * plane.u_start_O).norm());
  }
  return std::max((c + plane.radius_m * plane.u_start_O).norm(), (c + plane.radius_m * plane.u_end_O).norm());
}

double reflection_radius_m(const ObjectModel& model) {
  double r = model.bounding_radius_m();
  for (const auto& p : model.planes) r = std::max(r, arc_reach_m(p));
  return r;
}

CullingBounds make_culling_bounds(const SensorConfig& config, const Effects& effects,
                                  std::span<const SceneObject> objects, bool range_culling, bool view_culling) {
  CullingBounds b;
  b.radius_m.reserve(objects.size());
  const bool box = config.extended_objects.surface == ExtendedObjects::Surface::box &&
                   config.extended_objects.diffuse_relative_ercs_per_sqrt_m > 0.0;
  for (const auto& o : objects) {
    double radius_m = reflection_radius_m(o.model);
    if (box && has_box_sides(o.model)) radius_m = std::max(radius_m, 0.5 * std::hypot(o.model.length_m, o.model.width_m));
    b.radius_m.push_back(radius_m);
  }
  b.by_view = view_culling && config.fov.azimuth_half_rad < 0.5 * kPi;
  b.cos_half = std::cos(config.fov.azimuth_half_rad);
  b.sin_half = std::sin(config.fov.azimuth_half_rad);
  const AmplitudeLaw& law = config.amplitude;
  if (!range_culling || !has_detection_range_bound(law)) return b;
  // Multibounce copies (effects.cpp): orders 2..max_order, each with its ERCS factor.
  double copies_ercs_factor = 1.0, max_copy_factor = 1.0;
  int orders = 1;
  if (effects.multibounce) {
    for (int k = 2; k <= config.multibounce.max_order; ++k) {
      const double f = multibounce_ercs_factor(config.multibounce, k);
      copies_ercs_factor += f;
      max_copy_factor = std::max(max_copy_factor, f);
      ++orders;
    }
  }
  // Diffuse face pieces (visibility.hpp): at most max_pieces_per_face per plane, pieces of length
  // l_k summing to the chord L, each of ERCS r e sqrt(l_k): together at most r e sqrt(n L).
  const double diffuse = config.extended_objects.diffuse_relative_ercs_per_sqrt_m;
  const double max_pieces = config.extended_objects.max_pieces_per_face;
  const auto diffuse_ercs_bound = [&](const PlaneReflector& p, double pieces) {
    return diffuse * p.ercs * std::sqrt(pieces * (p.radius_m * (p.u_end_O - p.u_start_O)).norm());
  };
  std::vector<double> strongest_diffuse(objects.size(), 0.0);
  double ercs_sum = 0.0, echo_count = 0.0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ObjectModel& model = objects[i].model;
    for (const auto& p : model.points) ercs_sum += p.ercs_max;  // visibility <= 1 (paper II-C)
    for (const auto& p : model.planes) ercs_sum += p.ercs;
    echo_count += static_cast<double>(model.reflector_count());
    if (!(diffuse > 0.0)) continue;
    if (box && has_box_sides(model)) {  // four sides of ERCS 1 m^2 (ideal_targets.cpp)
      for (const double side_m : {model.width_m, model.width_m, model.length_m, model.length_m}) {
        ercs_sum += diffuse * std::sqrt(max_pieces * side_m);
        strongest_diffuse[i] = std::max(strongest_diffuse[i], diffuse * std::sqrt(side_m));
      }
      echo_count += 4.0 * max_pieces;
      continue;
    }
    for (const auto& p : model.planes) {
      ercs_sum += diffuse_ercs_bound(p, max_pieces);
      strongest_diffuse[i] = std::max(strongest_diffuse[i], diffuse_ercs_bound(p, 1.0));
    }
    echo_count += max_pieces * static_cast<double>(model.planes.size());
  }
  ercs_sum *= copies_ercs_factor;
  echo_count *= orders;
  const double tiny = std::numeric_limits<double>::min();
  // A fluctuating target can be detected below the threshold: down to detection_floor_db.
  const double headroom_db = kMarginDb + (law.detection_threshold_db - detection_floor_db(config));
  // (a): L0 - s (R - range_cell) + 20 log10(sum ERCS) < threshold.
  const double range_a_m =
      detection_range_bound_m(law, std::max(ercs_sum, tiny), headroom_db) + config.resolution.range_cell_m;
  b.by_range = true;
  b.cull_distance_m.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    // (b): L0 - s R + 20 log10(N max_ercs) < threshold.
    const double strongest = std::max(std::max(objects[i].model.max_ercs(), strongest_diffuse[i]) * max_copy_factor, tiny);
    const double range_b_m = detection_range_bound_m(law, echo_count * strongest, headroom_db);
    const double range_m = std::max({range_a_m, range_b_m, 0.0});
    b.cull_distance_m.push_back(range_m + b.radius_m[i]);
  }
  return b;
}

bool keep_object(const CullingBounds& bounds, const FieldOfView& fov, std::size_t i, const Vec2& p_SO_S,
                 double distance2_m2, unsigned char* may_occlude) {
  const double margin_m = bounds.radius_m[i] + 1e-3 + 1e-9 * std::sqrt(distance2_m2);
  if (bounds.by_view) {
    // Signed distances beyond the wedge's two edges y = +-tan(half) x.
    if (p_SO_S.y() * bounds.cos_half - p_SO_S.x() * bounds.sin_half > margin_m ||
        -p_SO_S.y() * bounds.cos_half - p_SO_S.x() * bounds.sin_half > margin_m) {
      return false;
    }
  }
  const double occlude_reach_m = fov.max_range_m + margin_m;
  if (may_occlude != nullptr && distance2_m2 <= occlude_reach_m * occlude_reach_m) *may_occlude = 1;
  // Beyond the view range by more than the reflection circle: no reflection point in view.
  const double reach_m = fov.max_range_m + bounds.radius_m[i];
  if (distance2_m2 > reach_m * reach_m) return false;
  const double cull_m = bounds.by_range ? bounds.cull_distance_m[i] : 0.0;
  return !(bounds.by_range && distance2_m2 > cull_m * cull_m);
}

}  // namespace rcsim
