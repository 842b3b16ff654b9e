#pragma once
// The targets of one annotated object over a whole run, drawn in the object's own frame over
// its box, recorded against simulated: the view of the paper's Fig. 3 (where on a vehicle the
// radar sees its reflection centers). x (forward) up, y (left) to the left, equal scale.
#include <string>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::replay::svg {

struct ObjectFramePoint {
  Vec2 p_OT_O = Vec2::Zero();
  bool simulated = false;
};

struct ObjectFrameSpec {
  std::string title;               // escaped when drawn
  std::vector<std::string> notes;  // lines under the title
  double length_m = 0.0, width_m = 0.0;
  std::vector<ObjectFramePoint> targets;
  int size_px = 240;  // the square plot area
};

std::string object_frame_svg(const ObjectFrameSpec& spec);

}  // namespace rcsim::replay::svg
