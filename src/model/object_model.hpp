#pragma once
// Reflection-center object models (paper section II): point reflection centers with a continuous
// visibility function of the impinging angle, and plane reflectors (circle sectors).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/angles.hpp"
#include "common/pose2.hpp"

namespace rcsim {

// Continuous visibility of a point reflection center over the impinging angle alpha, measured in
// the object frame from the object's longitudinal axis to the direction reflector -> sensor
// (paper II-B, Fig. 6): 1 within full_halfwidth of the centre direction, a raised-cosine fall to 0
// over falloff beyond that, 0 elsewhere.
class VisibilityFunction {
 public:
  VisibilityFunction() : VisibilityFunction(0.0, 0.0, 0.0) {}
  VisibilityFunction(double center_rad, double full_halfwidth_rad, double falloff_rad);

  double center_rad() const { return center_rad_; }
  double full_halfwidth_rad() const { return full_halfwidth_rad_; }
  double falloff_rad() const { return falloff_rad_; }

  double operator()(double alpha_rad) const;

  // Where the direction (dx, dy) to the sensor, of any length, falls: where the function is 1,
  // where it is 0, or in the fall-off between. The sensor cycle asks this of every point reflector
  // in range, so 1 and 0 are decided on squares, without normalizing. In the fall-off come cos and
  // sin of (alpha - center) for falloff_value(). A zero direction (sensor on the reflector) has
  // no impinging angle: zero.
  struct Zone {
    enum Kind : std::uint8_t { one, zero, falloff } kind = zero;
    double cos_delta = 1.0;
    double sin_delta = 0.0;
  };
  Zone zone(double dx, double dy) const {
    const double norm2 = dx * dx + dy * dy;
    if (!(norm2 > 0.0)) return {Zone::zero};
    const double k = dx * cos_center_ + dy * sin_center_;  // |d| cos(alpha - center)
    if (everywhere_ || cos_at_least(k, norm2, cos_full_edge_)) return {Zone::one};
    if (nowhere_beyond_ && !cos_at_least(k, norm2, cos_zero_edge_)) return {Zone::zero};
    const double inv_norm = 1.0 / std::sqrt(norm2);
    return {Zone::falloff, k * inv_norm, (dy * cos_center_ - dx * sin_center_) * inv_norm};
  }
  // The value in the fall-off zone (the raised cosine: two library calls).
  double falloff_value(double cos_delta, double sin_delta) const;
  // zone() and falloff_value() together.
  double from_direction(double dx, double dy) const {
    const Zone z = zone(dx, dy);
    if (z.kind == Zone::falloff) return falloff_value(z.cos_delta, z.sin_delta);
    return z.kind == Zone::one ? 1.0 : 0.0;
  }

 private:
  // Is cos(delta) = k / sqrt(norm2) at least cos_edge? The sign of k, then k^2 against
  // cos_edge^2 norm2.
  static bool cos_at_least(double k, double norm2, double cos_edge) {
    const double bound2 = cos_edge * cos_edge * norm2;
    return cos_edge >= 0.0 ? (k >= 0.0 && k * k >= bound2) : (k >= 0.0 || k * k <= bound2);
  }

  double center_rad_, full_halfwidth_rad_, falloff_rad_;
  double cos_center_, sin_center_;
  double cos_full_edge_, cos_zero_edge_;  // cos of the angles where it leaves 1 and reaches 0
  bool everywhere_, nowhere_beyond_;
};

// Micro-Doppler of a reflector on a limb or a wheel (docs/model.md, "Road users"): it moves back
// and forth along the object's heading about its place, so that its radial speed swings about the
// body's. Its speed along the heading is v + k |v| cos(phase(t)), with phase(t) = 2 pi t / T +
// phase_rad for a gait or a crank of period T, and |v| t / R + phase_rad for a point on a wheel of
// rolling radius R (period 2 pi R / |v|). A standing object (v = 0) does not swing. The point's
// position stays at its mean: the swing's reach (k |v| T / 2 pi, 0.2 m for a walking leg) is left out.
struct Swing {
  double relative_amplitude = 0.0;  // k: the swing's speed amplitude over the object's speed
  double period_s = 0.0;            // a gait's or a crank's period; 0: a wheel's, from rolling_radius_m
  double rolling_radius_m = 0.0;    // > 0 with period_s 0: a point on a wheel of this radius
  double phase_rad = 0.0;
  bool active() const { return relative_amplitude > 0.0; }
  // The swing's speed along the heading at t_s, for an object moving at speed_mps (signed).
  double speed_offset_mps(double speed_mps, double t_s) const {
    if (!active() || speed_mps == 0.0) return 0.0;
    const double phase_rad_t =
        (period_s > 0.0 ? kTwoPi * t_s / period_s : std::abs(speed_mps) * t_s / rolling_radius_m) + phase_rad;
    return relative_amplitude * speed_mps * std::cos(phase_rad_t);
  }
};

struct PointReflector {
  std::string name;
  Vec2 p_OR_O = Vec2::Zero();  // position in the object frame
  double z_m = 0.0;             // height above the road (a radar that measures elevation reads it)
  double ercs_max = 1.0;        // ERCS where the visibility function is 1 (paper II-C)
  VisibilityFunction visibility;
  Swing swing;                  // micro-Doppler; inactive: moves with the body

  // ERCS as the scaled visibility function (paper II-C).
  double ercs(double alpha_rad) const { return ercs_max * visibility(alpha_rad); }
};

// A plane reflector: the arc of a circle (seen in 3-D, part of a vertical cylinder surface), with
// constant ERCS (paper II-A, II-C). The arc runs counter-clockwise from start_rad over span_rad.
struct PlaneReflector {
  std::string name;
  Vec2 center_O = Vec2::Zero();
  double radius_m = 1.0;
  double start_rad = 0.0;
  double span_rad = 0.0;
  double ercs = 1.0;
  double z_m = 0.0;  // height of its specular point above the road
  // Unit directions from the centre to the arc's ends; set with start_rad and span_rad by set_arc.
  Vec2 u_start_O = Vec2::UnitX();
  Vec2 u_end_O = Vec2::UnitX();

  // Sets start_rad, span_rad (in [0, 2 pi]) and the arc-end directions together.
  void set_arc(double start_angle_rad, double span_angle_rad);
  Vec2 arc_point_O(double angle_rad) const;
  // Is the direction (from the circle centre, in the object frame) inside the sector? The arc
  // ends count as inside.
  bool covers_direction(double angle_rad) const;
  // The same for a direction vector of any positive length, by cross products with the arc-end
  // directions (no atan2): the sensor cycle asks this of every plane reflector in range.
  bool covers_direction(const Vec2& d_O) const {
    const double ccw_of_start = cross(u_start_O, d_O);  // >= 0: d at most a half turn past the start
    const double cw_of_end = cross(d_O, u_end_O);       // >= 0: the end at most a half turn past d
    if (span_rad <= kPi) return ccw_of_start >= 0.0 && cw_of_end >= 0.0;
    if (span_rad >= kTwoPi) return true;
    // Wider than a half turn: outside only strictly inside the gap from the end round to the start.
    return ccw_of_start >= 0.0 || cw_of_end >= 0.0;
  }
};

// A static object along a line (guard rail, wall; docs/static-world.md): the template a scene's
// polyline is expanded with (expand_polyline).
struct PolylineTemplate {
  double spacing_m = 4.0;  // posts every spacing_m along the line; face pieces at most this long
  double post_ercs = 0.0;  // 0: no posts
  // The posts' visibility; its centre is measured from the line's left normal (0: facing the side
  // to the left of the direction from one vertex to the next).
  VisibilityFunction post_visibility;
  // The face: plane reflectors of length l <= spacing_m facing left, ERCS face_ercs_per_m x l
  // (a flat face reflects coherently: amplitude grows with its length); 0: no face.
  double face_ercs_per_m = 0.0;
  double z_m = 0.0;  // version 2: the height of its posts and face above the road
};

struct ObjectModel {
  std::string name;
  std::string description;
  double length_m = 0.0;
  double width_m = 0.0;
  // Version 2 (a radar that measures elevation reads them): the body's height, where the diffuse
  // pieces of its box sides spread (0: not given, pieces at 0.5 m), and, for a thing that stands
  // above the road (a sign gantry, a bridge), the free height under it: lines of sight pass
  // beneath, so it hides nothing behind it.
  double height_m = 0.0;
  double clearance_m = 0.0;
  // Version 2: how strongly its body returns diffusely where a profile puts diffuse pieces on the
  // box sides (extended_objects.diffuse_surface "box"), relative to a car's metal body (1): a
  // person or a bicycle far less; 0 for a thing whose box holds no body (a gantry's). 0 to 1.
  double diffuse_ercs_factor = 1.0;
  bool has_swinging_points = false;  // some point reflector swings (set by parse_object_model; the sensor cycle skips the look-up where none does)
  std::vector<PointReflector> points;
  std::vector<PlaneReflector> planes;
  std::optional<PolylineTemplate> polyline;  // set: a template; a scene's polyline makes the model
  std::size_t polyline_points = 0;           // > 0: made by expand_polyline from that many points

  double max_ercs() const;
  std::size_t reflector_count() const { return points.size() + planes.size(); }
  // Radius of a circle about the object origin that contains every reflector.
  double bounding_radius_m() const;
};

// A plane reflector from the chord of its arc and the sagitta (how far the arc bulges outward,
// away from the object origin): the form used in the model files.
PlaneReflector plane_from_chord(std::string name, const Vec2& from_O, const Vec2& to_O, double sagitta_m,
                                double ercs);

// The same, the arc bulging towards `outward_O` (a unit vector normal to the chord).
PlaneReflector plane_from_chord_facing(std::string name, const Vec2& from_O, const Vec2& to_O, double sagitta_m,
                                       double ercs, const Vec2& outward_O);

// The model a polyline template makes along `vertices_O` (object frame, at least two, no two
// consecutive equal): posts at arc lengths 0, spacing, 2 spacing, ... (`post_K`), and each segment
// cut into ceil(length / spacing) face pieces (`face_K`), facing left. Its box is 1 mm: a
// polyline occludes nothing.
ObjectModel expand_polyline(const ObjectModel& polyline_model, const std::vector<Vec2>& vertices_O);

// The model stretched to another length and width: reflector positions scale with the box;
// plane reflectors keep passing through their scaled chord ends and apex.
ObjectModel scale_model(const ObjectModel& model, double length_m, double width_m);

}  // namespace rcsim
