#include "synth/scatterers.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"
#include "common/decibel.hpp"
#include "common/rng.hpp"

namespace rcsim::synth {
namespace {

// Surface properties of one face of the outline.
struct FaceProfile {
  double height_m = 0.5;           // centre height of the reflecting band
  double vertical_extent_m = 0.3;  // its coherent vertical span
  double effective_height_m = 0.2;  // reflectivity-weighted height that reflects coherently
  bool mirrors = false;
};

struct OutlineSpec {
  double corner_radius_m = 0.35;
  double sagitta_front_m = 0.10, sagitta_rear_m = 0.10, sagitta_side_m = 0.03;
  double face_step_m = 0.10;  // facet length on the faces
  FaceProfile front, rear, side;
};

// Facet length on a stretch with radius of curvature rho: the normals of neighbouring facets
// differ by ds / rho, which must stay well inside one facet's lobe (first null at lambda / 2 ds),
// or the specular return falls between facets: ds <= sqrt(lambda rho) / 2. The facet is then also
// flat for the physical-optics formula (sagitta ds^2 / 8 rho < lambda / 32).
double facet_step_on_curve(double radius_m, double face_step_m, double lambda_m) {
  return std::clamp(0.5 * std::sqrt(radius_m * lambda_m), 0.01, face_step_m);
}

void add_facet(std::vector<Scatterer>& out, const Vec2& a, const Vec2& b, const Vec2& normal, const FaceProfile& f) {
  Scatterer s;
  s.kind = ScattererKind::facet;
  s.p_O = 0.5 * (a + b);
  s.facet_length_m = (b - a).norm();
  s.axis_rad = std::atan2(normal.y(), normal.x());
  s.height_m = f.height_m;
  s.vertical_extent_m = f.vertical_extent_m;
  s.strength = s.facet_length_m * f.effective_height_m;
  s.mirrors = f.mirrors;
  out.push_back(s);
}

// A parabolic face x = x0 - s (t/a)^2 along t in [-a, a], in a frame rotated by face_yaw.
void add_face(std::vector<Scatterer>& out, double x0, double half_span, double sagitta, double face_yaw,
              double face_step_m, const FaceProfile& profile, double lambda_m) {
  if (half_span <= 1e-6) return;
  const double radius_m = sagitta > 1e-6 ? half_span * half_span / (2.0 * sagitta) : 1e3;  // apex curvature
  const double step_m = facet_step_on_curve(radius_m, face_step_m, lambda_m);
  const int n = std::max(1, static_cast<int>(std::ceil(2.0 * half_span / step_m)));
  const auto point = [&](double t) { return rotate(face_yaw, Vec2(x0 - sagitta * (t / half_span) * (t / half_span), t)); };
  for (int i = 0; i < n; ++i) {
    const double t0 = -half_span + 2.0 * half_span * i / n;
    const double t1 = -half_span + 2.0 * half_span * (i + 1) / n;
    const double tm = 0.5 * (t0 + t1);
    const Vec2 normal = rotate(face_yaw, Vec2(1.0, 2.0 * sagitta * tm / (half_span * half_span)).normalized());
    add_facet(out, point(t0), point(t1), normal, profile);
  }
}

// A quarter ellipse joining two face ends: centre c, semi-axes (rx, ry), from angle a0 to a0 + pi/2.
void add_corner(std::vector<Scatterer>& out, const Vec2& c, double rx, double ry, double a0, double face_step_m,
                const FaceProfile& profile, double lambda_m) {
  if (rx <= 1e-6 || ry <= 1e-6) return;
  const double step = facet_step_on_curve(std::min(rx, ry), face_step_m, lambda_m);
  const double arc_m = 0.25 * kPi * (rx + ry);
  const int n = std::max(2, static_cast<int>(std::ceil(arc_m / step)));
  const auto point = [&](double t) { return Vec2(c.x() + rx * std::cos(t), c.y() + ry * std::sin(t)); };
  for (int i = 0; i < n; ++i) {
    const double t0 = a0 + 0.5 * kPi * i / n;
    const double t1 = a0 + 0.5 * kPi * (i + 1) / n;
    const double tm = 0.5 * (t0 + t1);
    const Vec2 normal = Vec2(std::cos(tm) / rx, std::sin(tm) / ry).normalized();
    add_facet(out, point(t0), point(t1), normal, profile);
  }
}

// The outline of a box: four bulged faces joined by quarter ellipses; the outermost points touch
// the annotated box.
void add_outline(std::vector<Scatterer>& out, double length_m, double width_m, const OutlineSpec& spec, double lambda_m) {
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  const double r = std::min({spec.corner_radius_m, 0.45 * length_m, 0.45 * width_m});
  const double sf = std::min(spec.sagitta_front_m, 0.5 * r), sr = std::min(spec.sagitta_rear_m, 0.5 * r);
  const double ss = std::min(spec.sagitta_side_m, 0.5 * r);
  add_face(out, hl, hw - r, sf, 0.0, spec.face_step_m, spec.front, lambda_m);
  add_face(out, hl, hw - r, sr, kPi, spec.face_step_m, spec.rear, lambda_m);
  add_face(out, hw, hl - r, ss, 0.5 * kPi, spec.face_step_m, spec.side, lambda_m);
  add_face(out, hw, hl - r, ss, -0.5 * kPi, spec.face_step_m, spec.side, lambda_m);
  add_corner(out, {hl - r, hw - r}, r - sf, r - ss, 0.0, spec.face_step_m, spec.front, lambda_m);
  add_corner(out, {-(hl - r), hw - r}, r - sr, r - ss, 0.5 * kPi, spec.face_step_m, spec.rear, lambda_m);
  add_corner(out, {-(hl - r), -(hw - r)}, r - sr, r - ss, kPi, spec.face_step_m, spec.rear, lambda_m);
  add_corner(out, {hl - r, -(hw - r)}, r - sf, r - ss, 1.5 * kPi, spec.face_step_m, spec.front, lambda_m);
}

// Exponent p of cos(theta)^p with half power (amplitude 1/sqrt 2) at the given angle.
double lobe_exponent_for(double half_power_deg) {
  return std::log(std::sqrt(0.5)) / std::log(std::cos(deg_to_rad(half_power_deg)));
}

Scatterer lobe(const Vec2& p_O, double height_m, double extent_m, double axis_rad, double sigma_rel,
               double half_power_deg, bool elevated = false) {
  Scatterer s;
  s.kind = ScattererKind::lobe;
  s.p_O = p_O;
  s.height_m = height_m;
  s.vertical_extent_m = extent_m;
  s.axis_rad = axis_rad;
  s.strength = std::sqrt(sigma_rel);
  s.lobe_exponent = lobe_exponent_for(half_power_deg);
  s.elevated = elevated;
  return s;
}

Scatterer isotropic(const Vec2& p_O, double height_m, double extent_m, double sigma_rel) {
  Scatterer s;
  s.kind = ScattererKind::isotropic;
  s.p_O = p_O;
  s.height_m = height_m;
  s.vertical_extent_m = extent_m;
  s.strength = std::sqrt(sigma_rel);
  return s;
}

ScattererBody car_body(double length_m, double width_m, double lambda_m) {
  ScattererBody body{{}, length_m, width_m, 1.45};
  OutlineSpec spec;
  spec.front = {0.50, 0.25, 0.20, true};   // bumper with its metal beam
  spec.rear = {0.55, 0.25, 0.17, true};
  spec.side = {0.65, 0.40, 0.10, false};   // doors: curved in elevation, little coherent height
  add_outline(body.scatterers, length_m, width_m, spec, lambda_m);
  auto& s = body.scatterers;
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  // Headlamp/tail-lamp housings and bumper corners: broad lobes just inside the box corners,
  // turned towards the front (rear) of the car.
  for (const double sx : {1.0, -1.0}) {
    for (const double sy : {1.0, -1.0}) {
      const double axis = std::atan2(sy * 0.6, sx);
      s.push_back(lobe({sx * (hl - 0.15), sy * (hw - 0.2)}, 0.7, 0.15, axis, 0.8, 40.0));
    }
  }
  // Grille and radiator behind the front bumper, number-plate recess at the rear.
  s.push_back(lobe({hl - 0.3, 0.0}, 0.55, 0.2, 0.0, 0.35, 30.0));
  s.push_back(lobe({-(hl - 0.15), 0.0}, 0.6, 0.1, kPi, 0.15, 30.0));
  // Wheel-house cavities: open sideways and downwards, seen over a wide sector.
  for (const double x : {0.304 * length_m, -0.293 * length_m}) {
    for (const double sy : {1.0, -1.0}) {
      s.push_back(lobe({x, sy * (hw - 0.06)}, 0.35, 0.25, sy * 0.5 * kPi, 0.4, 50.0));
    }
  }
  // Door mirrors.
  for (const double sy : {1.0, -1.0}) s.push_back(lobe({0.17 * length_m, sy * (hw - 0.02)}, 1.0, 0.1, sy * 0.35, 0.1, 50.0));
  // Windshield base, roof edges and rear window: weak, high, seen only at short range (paper
  // Fig. 16); not hidden by the body below them.
  for (const double fy : {-0.55, 0.0, 0.55}) {
    s.push_back(lobe({0.20 * length_m, fy * hw}, 0.95, 0.05, 0.0, 0.03, 45.0, true));
    s.push_back(lobe({-0.02 * length_m, fy * hw}, 1.40, 0.03, 0.0, 0.012, 50.0, true));
    s.push_back(lobe({-0.30 * length_m, fy * hw}, 1.05, 0.05, kPi, 0.015, 45.0, true));
  }
  // Exhaust/rear under-body edge.
  s.push_back(lobe({-(hl - 0.2), -0.4 * hw}, 0.3, 0.1, kPi, 0.1, 50.0));
  return body;
}

ScattererBody truck_body(double length_m, double width_m, double lambda_m) {
  ScattererBody body{{}, length_m, width_m, 4.0};
  OutlineSpec spec;
  spec.corner_radius_m = 0.12;
  spec.sagitta_front_m = 0.05;
  spec.sagitta_rear_m = 0.02;
  spec.sagitta_side_m = 0.02;
  spec.front = {1.0, 0.6, 0.25, true};
  spec.rear = {1.0, 0.8, 0.15, true};   // trailer doors, ribbed
  spec.side = {1.1, 0.9, 0.08, false};  // ribbed trailer walls
  add_outline(body.scatterers, length_m, width_m, spec, lambda_m);
  auto& s = body.scatterers;
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  for (const double sx : {1.0, -1.0}) {
    for (const double sy : {1.0, -1.0}) {
      s.push_back(lobe({sx * (hl - 0.08), sy * (hw - 0.08)}, 0.9, 0.3, std::atan2(sy, sx), 2.0, 35.0));
    }
  }
  // Wheel houses of five axles and the gap behind the cab.
  for (const double fx : {0.418, 0.194, -0.280, -0.339, -0.400}) {
    for (const double sy : {1.0, -1.0}) {
      s.push_back(lobe({fx * length_m, sy * (hw - 0.08)}, 0.5, 0.4, sy * 0.5 * kPi, 1.0, 30.0));
    }
  }
  for (const double sy : {1.0, -1.0}) {
    s.push_back(lobe({0.35 * length_m, sy * (hw - 0.1)}, 1.5, 0.5, sy * 0.5 * kPi, 1.2, 25.0));
  }
  // Rear under-run guard.
  s.push_back(lobe({-(hl - 0.1), 0.0}, 0.5, 0.1, kPi, 1.5, 40.0));
  return body;
}

ScattererBody guide_board_body(double length_m, double width_m, double lambda_m) {
  ScattererBody body{{}, length_m, width_m, 2.2};
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  // The board faces: flat, 1.3 m centre height, 0.5 m tall.
  const FaceProfile face_front{1.3, 0.5, 0.10, false};
  const FaceProfile face_back{1.3, 0.5, 0.05, false};
  add_face(body.scatterers, hl, hw, 0.01, 0.0, 0.1, face_front, lambda_m);
  add_face(body.scatterers, hl, hw, 0.01, kPi, 0.1, face_back, lambda_m);
  auto& s = body.scatterers;
  s.push_back(lobe({0.0, hw}, 1.3, 0.5, 0.5 * kPi, 0.15, 60.0));
  s.push_back(lobe({0.0, -hw}, 1.3, 0.5, -0.5 * kPi, 0.15, 60.0));
  for (const double y : {-0.7 * hw, 0.7 * hw}) s.push_back(isotropic({0.0, y}, 0.5, 0.6, 0.25));  // posts
  return body;
}

ScattererBody pole_body(double length_m, double width_m) {
  ScattererBody body{{}, length_m, width_m, 1.2};
  // The reference reflector: a unit point seen from every direction (paper III-B).
  body.scatterers.push_back(isotropic({0.0, 0.0}, 0.6, 0.1, 1.0));
  return body;
}

}  // namespace

double facet_sqrt_rcs_m(const Scatterer& facet, double incidence_rad, double wavelength_m) {
  const double c = std::cos(incidence_rad);
  if (c <= 0.0) return 0.0;
  const double x = kTwoPi / wavelength_m * facet.facet_length_m * std::sin(incidence_rad);
  const double si = std::abs(x) < 1e-9 ? 1.0 : std::sin(x) / x;
  return std::sqrt(4.0 * kPi) * facet.strength / wavelength_m * c * si;
}

ScattererBody make_body(const std::string& object_class, double length_m, double width_m, double facet_wavelength_m) {
  if (object_class == "passenger_car") return car_body(length_m, width_m, facet_wavelength_m);
  if (object_class == "truck_trailer") return truck_body(length_m, width_m, facet_wavelength_m);
  if (object_class == "guide_board") return guide_board_body(length_m, width_m, facet_wavelength_m);
  if (object_class == "pole") return pole_body(length_m, width_m);
  if (length_m < 0.5 && width_m < 0.5) return pole_body(length_m, width_m);
  return car_body(length_m, width_m, facet_wavelength_m);
}

std::vector<WorldScatterer> road_clutter_near(const Clutter& clutter, std::uint64_t seed, const Vec2& p_WS_W, double radius_m) {
  std::vector<WorldScatterer> out;
  if (clutter.density_per_m2 <= 0.0) return out;
  const double tile = clutter.tile_m;
  const auto lo_x = static_cast<long long>(std::floor((p_WS_W.x() - radius_m) / tile));
  const auto hi_x = static_cast<long long>(std::floor((p_WS_W.x() + radius_m) / tile));
  const auto lo_y = static_cast<long long>(std::floor((p_WS_W.y() - radius_m) / tile));
  const auto hi_y = static_cast<long long>(std::floor((p_WS_W.y() + radius_m) / tile));
  for (long long ix = lo_x; ix <= hi_x; ++ix) {
    for (long long iy = lo_y; iy <= hi_y; ++iy) {
      const auto key = (static_cast<std::uint64_t>(ix) * 0x9E3779B97F4A7C15ULL) ^
                       (static_cast<std::uint64_t>(iy) * 0xC2B2AE3D27D4EB4FULL) ^ 0x5C1A77E2ULL;
      Rng rng(seed, key);
      const int count = rng.poisson(clutter.density_per_m2 * tile * tile);
      for (int i = 0; i < count; ++i) {
        // The draws one by one: the order of a call's arguments is unspecified (GCC took y first,
        // clang x, and the same seed gave another clutter field); y first keeps the outputs made.
        const double fraction_y = rng.uniform01();
        const double fraction_x = rng.uniform01();
        const Vec2 p(tile * (static_cast<double>(ix) + fraction_x), tile * (static_cast<double>(iy) + fraction_y));
        const double rcs_db = clutter.median_rcs_rel_db + clutter.rcs_spread_db * rng.normal();
        const double height_m = rng.uniform(0.02, 0.15);
        if ((p - p_WS_W).squaredNorm() > radius_m * radius_m) continue;
        out.push_back({isotropic(Vec2::Zero(), height_m, 0.0, db_to_power(rcs_db)), p});
      }
    }
  }
  return out;
}

}  // namespace rcsim::synth
