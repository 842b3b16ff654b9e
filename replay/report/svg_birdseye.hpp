#pragma once
// The bird's-eye picture of one cycle (like paper Figs. 14-17): annotated boxes, the sensors
// with their field-of-view wedges, recorded and simulated targets, their assignment, merge
// artefacts, and the targets of the last few cycles as fading traces. The shape tells the origin
// (recorded: dot, simulated: diamond), the colour the class: targets of annotated objects blue
// (recorded) and orange (simulated), the stationary background grey, other targets teal. Everything is given in
// the ego vehicle frame V of the pictured cycle; the picture shows x (forward) up and y (left)
// to the left, at equal scale.
#include <string>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::replay::svg {

struct BirdsEyeBox {
  std::string label;  // object id and class (escaped when drawn)
  Pose2 X_VO;         // box centre and heading
  double length_m = 0.0, width_m = 0.0;
  bool in_merge_pair = false;  // shares a range-speed cell with another box in this cycle
};

struct BirdsEyeSensor {
  std::string label;
  Pose2 X_VS;
  double azimuth_half_rad = 0.0, max_range_m = 0.0;
};

struct BirdsEyeTarget {
  Vec2 p_V = Vec2::Zero();
  bool simulated = false;
  int age = 0;  // cycles before the pictured one (0: the pictured cycle)
  bool merge_artefact = false;
  // object | background | other (metrics/target_class.hpp); empty: unknown, drawn as an object.
  std::string target_class;
};

struct BirdsEyeLink {  // an assigned recorded-simulated pair of the pictured cycle
  Vec2 p_recorded_V = Vec2::Zero(), p_simulated_V = Vec2::Zero();
};

struct BirdsEyeSpec {
  std::string title;
  std::vector<std::string> notes;  // lines under the title
  int trace_cycles = 0;  // how many earlier cycles the traces cover
  int size_px = 500;     // width of the plot area (its height: as the view's length needs, up to 2 x)
  std::vector<BirdsEyeBox> boxes;
  std::vector<BirdsEyeSensor> sensors;
  std::vector<BirdsEyeTarget> targets;
  std::vector<BirdsEyeLink> links;
  std::string recorded_label = "recorded target", simulated_label = "simulated target";  // legend
  bool class_legend = false;  // a legend row for the target classes (their colours)
  bool standalone = false;  // a file of its own: carries its own text styles (the report's page has them)
};

std::string birdseye_svg(const BirdsEyeSpec& spec);

}  // namespace rcsim::replay::svg
