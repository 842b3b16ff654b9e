#pragma once
// Objects as dense scatterers along their contour (docs/synth.md, "Objects"): the annotated box
// becomes a rounded outline with bulged faces, sampled into small flat facets with a
// physical-optics response, plus lobed point scatterers for the features a contour lacks (lamp
// and bumper corners, wheel-house cavities, windshield base and roof edge) and isotropic ones
// (posts, poles, road clutter). Only the box size and the class name are used: nothing of the
// reflection-center object models.
#include <cstdint>
#include <string>
#include <vector>

#include "common/pose2.hpp"
#include "synth/synth_config.hpp"

namespace rcsim::synth {

enum class ScattererKind {
  facet,      // flat strip: two-way physical optics, cos(theta) * si(k ds sin theta)
  lobe,       // point with an amplitude lobe cos(theta)^p about its axis, zero behind
  isotropic,  // point seen alike from every direction
};

struct Scatterer {
  ScattererKind kind = ScattererKind::isotropic;
  Vec2 p_O = Vec2::Zero();        // in the object frame (box centre, x forward)
  double height_m = 0.5;          // centre height above the road
  double vertical_extent_m = 0.0;  // coherent vertical span (averages the two-ray lobing)
  double axis_rad = 0.0;          // facet normal or lobe axis, object frame
  // facet: reflectivity * length * effective height [m^2]; lobe/isotropic: peak sqrt(sigma/sigma_ref)
  double strength = 1.0;
  double facet_length_m = 0.0;
  double lobe_exponent = 0.0;
  bool elevated = false;   // above the body (windshield, roof): not hidden by its own box
  bool mirrors = false;    // a face that can bounce energy back and forth with the ego's front
};

// A scatterer fixed in the world (road clutter): its position in the world frame.
struct WorldScatterer {
  Scatterer scatterer;  // its p_O is unused (zero)
  Vec2 p_WC_W = Vec2::Zero();  // world position of the clutter point C
};

// A body as the sensor sees it: scatterers in the object frame, and the box for occlusion.
struct ScattererBody {
  std::vector<Scatterer> scatterers;
  double length_m = 0.0;
  double width_m = 0.0;
  double height_m = 1.5;  // occluder height
};

// The scatterers of one object of the given class ("passenger_car", "truck_trailer",
// "guide_board", "pole"; any other class is treated as a generic vehicle body of its box). Curved
// faces are cut into facets fine enough for the given wavelength (Propagation::facet_wavelength_m).
ScattererBody make_body(const std::string& object_class, double length_m, double width_m,
                        double facet_wavelength_m = Propagation{}.facet_wavelength_m);

// Road clutter near a world point: static isotropic scatterers on the road surface, drawn per
// tile from Rng(seed, tile) so that a tile's content does not depend on the order of the visits.
std::vector<WorldScatterer> road_clutter_near(const Clutter& clutter, std::uint64_t seed, const Vec2& p_WS_W,
                                         double radius_m);

// Two-way physical-optics amplitude of a facet, sqrt(sigma) in m, at incidence theta from its
// normal: sqrt(4 pi) * A / lambda * cos(theta) * si(k ds sin(theta)), A = strength (Knott, Radar
// Cross Section, flat-plate PO); zero from behind.
double facet_sqrt_rcs_m(const Scatterer& facet, double incidence_rad, double wavelength_m);

}  // namespace rcsim::synth
