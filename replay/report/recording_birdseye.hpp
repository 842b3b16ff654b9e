#pragma once
// A bird's-eye picture of a recording at one cycle (rcsim synth --svg), drawn by the report's
// renderer (svg_birdseye.hpp): the annotated boxes of that cycle, the sensors with their view
// fields, the recording's targets of the last few cycles as fading traces, and optionally
// another target list (rcsim simulate output) drawn against them.
#include <string>

#include "io/recording.hpp"
#include "replay/report/svg_birdseye.hpp"

namespace rcsim::replay::svg {

struct RecordingPictureOptions {
  double time_s = -1.0;      // the pictured cycle: the last at or before it; < 0: the last cycle
  int cycles = 10;           // cycles of targets up to the pictured one
  std::string compare_path;  // target list CSV (cycle, sensor, range_m, azimuth_rad, ...), or none
  std::string title;
  std::string recorded_label = "recording's target", compared_label = "compared target";
};

// The picture's contents; text is escaped when rendered. A compare list naming an unknown
// sensor, or malformed, is an InputError naming its file and line.
BirdsEyeSpec recording_birdseye(const Recording& recording, const RecordingPictureOptions& options);

inline std::string recording_birdseye_svg(const Recording& recording, const RecordingPictureOptions& options) {
  return birdseye_svg(recording_birdseye(recording, options));
}

}  // namespace rcsim::replay::svg
