#pragma once
// Bird's-eye pictures in the style of the paper's Figs. 14-17: the ego vehicle with its sensors'
// fields of view, the annotated boxes, and the targets of the last ten cycles (stars: left
// sensor, circles: right sensor, a line for the range rate), of a recording and optionally of
// another target list (e.g. `rcsim simulate` output) drawn over it for comparison.
#include <string>

#include "io/recording.hpp"

namespace rcsim::synth {

struct SvgOptions {
  double time_s = -1.0;      // snapshot time; < 0: the last cycle
  int cycles = 10;           // how many cycles of targets up to the snapshot
  std::string compare_path;  // target list CSV (t_s, cycle, sensor, range_m, azimuth_rad, range_rate_mps)
  std::string title;
};

std::string birds_eye_svg(const Recording& recording, const SvgOptions& options);

}  // namespace rcsim::synth
