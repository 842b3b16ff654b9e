#pragma once
// The road as a radar sees it, from the labelled boxes of a dataset that gives them in the radar's
// own frame (Astyx, View-of-Delft): each box stands on the road, so its bottom (centre height
// minus half its height) lies on the road plane. In a frame pitched by theta above a level road h
// below the sensor, a road point x ahead lies at z = tan(theta) x - h / cos(theta) (the road
// rises with range for a radar looking down). A least-squares line through the box bottoms gives
// the mounting's height above the road and its pitch (docs/importers.md).
#include <optional>
#include <string>

#include "io/recording.hpp"

namespace rcsim::replay {

struct GroundPlaneFit {
  double z_m = 0.0;        // the sensor's height above the road
  double pitch_rad = 0.0;  // its boresight's pitch, positive down
  int boxes = 0;           // the boxes the fit used
  double residual_rms_m = 0.0;
};

// The fit through the objects' boxes of `rec` whose attributes give their centre's height `z_m`
// and `height_m` in the sensor's frame (one box each: snapshots), against their horizontal
// distance from the sensor at the origin. None with fewer than 10 such boxes, or where the fit is
// no mounting (height outside 0.1-5 m, pitch beyond 10 degrees): the road is not plane enough.
std::optional<GroundPlaneFit> fit_ground_plane(const Recording& rec);

// "the road 1.59 m below the radar, pitched 2.53 deg down (a plane through 2300 box bottoms, 0.52 m rms)".
std::string describe(const GroundPlaneFit& fit);

}  // namespace rcsim::replay
