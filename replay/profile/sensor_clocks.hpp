#pragma once
// Each radar's own clock read off its recording (`rcsim import --sensor-clocks estimated`): a
// dataset that stamps every radar frame with the keyframe it was picked for (the aiMotive
// dataset: 15 Hz keyframes, radars at about 18 Hz, unsynchronised) hides when each frame was
// measured. The static world's shift between a radar's consecutive frames shows the time between
// them (frame_matching.hpp); the steps are whole multiples of the radar's period (a frame between
// two keyframes is not in the data), so the frames lie on a regular clock at the least-squares
// period, and the recording is rewritten with every sensor on its own clock (recording v4).
#include <string>
#include <vector>

#include "io/recording.hpp"

namespace rcsim::replay::profile {

struct SensorClock {
  std::string sensor;
  double period_s = 0.0;              // least-squares period of the matched steps
  int steps = 0, steps_matched = 0;   // steps between consecutive cycles; those the static world timed
  int steps_skipping = 0;             // steps of two or more periods: frames the keyframes skipped
  double step_residual_rms_s = 0.0;   // matched step minus its whole number of periods, RMS
  // Per cycle, the frame's time on the recording's clock; the keyframe time minus it (the
  // stamping's error the estimate removes), its mean 0 by the choice of the clock's phase.
  std::vector<double> t_s;
  double offset_min_s = 0.0, offset_max_s = 0.0, offset_rms_s = 0.0;
};

// Every sensor's clock; InputError (naming the recording) where one cannot be read: a recording
// already on its own clocks, single frames, fewer than 10 matched steps of a sensor, or steps that
// fit no one period.
std::vector<SensorClock> estimate_sensor_clocks(const Recording& keyframed);

// The recording with each sensor on its estimated clock: cycles.csv from the clocks, the targets
// stamped with their frame's time, the ego rows and boxes kept at the keyframes as an ego log and
// annotation of their own rate; `source.sensor_clocks` says how and how well.
Recording on_estimated_clocks(const Recording& keyframed, const std::vector<SensorClock>& clocks);

}  // namespace rcsim::replay::profile
