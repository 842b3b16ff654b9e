#include "replay/profile/sensor_clocks.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numbers>
#include <optional>

#include "common/input_error.hpp"
#include "replay/calibrate/real_drive_fit.hpp"
#include "replay/profile/detection_pool.hpp"
#include "replay/profile/frame_matching.hpp"

namespace rcsim::replay::profile {
namespace {

constexpr int kMinMatchedSteps = 10;

// The time between each cycle k and k + 1 that the static world's shift shows, where it does.
std::vector<std::optional<double>> matched_steps(const Recording& one_sensor) {
  const DetectionPool pool = pool_detections({&one_sensor});
  // Redetections are not wanted here: no threshold, no view limit.
  const ViewLimits everywhere{std::numbers::pi, 1e9};
  std::vector<std::optional<double>> steps(static_cast<std::size_t>(one_sensor.cycle_count() - 1));
  for (const FramePair& pair : match_consecutive_cycles(pool, 0.0, everywhere)) {
    steps[static_cast<std::size_t>(pair.cycle)] = pair.dt_s;
  }
  return steps;
}

SensorClock clock_of(const Recording& keyframed, int s) {
  const Recording one_sensor = restrict_to_sensor(keyframed, s);
  SensorClock clock;
  clock.sensor = keyframed.sensors[static_cast<std::size_t>(s)].id;
  const std::vector<std::optional<double>> steps = matched_steps(one_sensor);
  std::vector<double> matched_s;
  for (const auto& step : steps) {
    if (step) matched_s.push_back(*step);
  }
  clock.steps = static_cast<int>(steps.size());
  clock.steps_matched = static_cast<int>(matched_s.size());
  const std::string where = fmt::format("sensor '{}'", clock.sensor);
  if (clock.steps_matched < kMinMatchedSteps) {
    throw InputError(keyframed.dir.string(), where,
                     fmt::format("{} of {} steps between cycles timed by the static world: its clock needs {}",
                                 clock.steps_matched, clock.steps, kMinMatchedSteps));
  }
  const std::optional<double> period_s = fundamental_period(matched_s);
  if (!period_s) {
    throw InputError(keyframed.dir.string(), where, "the timed steps are whole multiples of no one period");
  }
  clock.period_s = *period_s;
  // Whole periods per step: the static world's where it timed the step, else the keyframes'.
  std::vector<long long> periods_before(steps.size() + 1, 0);
  double residual_sq = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double dt_s = steps[k] ? *steps[k] : keyframed.cycle_t_s(static_cast<int>(k) + 1) - keyframed.cycle_t_s(static_cast<int>(k));
    const long long n = std::max(1LL, std::llround(dt_s / clock.period_s));
    if (steps[k]) residual_sq += (dt_s - static_cast<double>(n) * clock.period_s) * (dt_s - static_cast<double>(n) * clock.period_s);
    clock.steps_skipping += n >= 2;
    periods_before[k + 1] = periods_before[k] + n;
  }
  clock.step_residual_rms_s = std::sqrt(residual_sq / clock.steps_matched);
  // The clock's phase: the keyframes' times lie about the frames' on both sides, the offsets' mean 0.
  const int cycles = keyframed.cycle_count();
  double phase_s = 0.0;
  for (int k = 0; k < cycles; ++k) phase_s += keyframed.cycle_t_s(k) - clock.period_s * static_cast<double>(periods_before[static_cast<std::size_t>(k)]);
  phase_s /= cycles;
  double offset_sq = 0.0;
  clock.offset_min_s = INFINITY, clock.offset_max_s = -INFINITY;
  for (int k = 0; k < cycles; ++k) {
    const double t_s = phase_s + clock.period_s * static_cast<double>(periods_before[static_cast<std::size_t>(k)]);
    const double offset_s = keyframed.cycle_t_s(k) - t_s;
    clock.t_s.push_back(t_s);
    clock.offset_min_s = std::min(clock.offset_min_s, offset_s);
    clock.offset_max_s = std::max(clock.offset_max_s, offset_s);
    offset_sq += offset_s * offset_s;
  }
  clock.offset_rms_s = std::sqrt(offset_sq / cycles);
  return clock;
}

}  // namespace

std::vector<SensorClock> estimate_sensor_clocks(const Recording& keyframed) {
  const std::string name = keyframed.dir.string();
  if (keyframed.clock == Clock::per_sensor) throw InputError(name, "clock", "the sensors are on their own clocks already");
  if (keyframed.timeline == Timeline::snapshots) {
    throw InputError(name, "timeline", "single frames (snapshots): no frame follows another to time the steps by");
  }
  if (!keyframed.ego_motion_known) {
    throw InputError(name, "ego_motion_known", "no ego motion: the static world's shift times a step only at a known speed");
  }
  std::vector<SensorClock> clocks;
  for (int s = 0; s < static_cast<int>(keyframed.sensors.size()); ++s) clocks.push_back(clock_of(keyframed, s));
  return clocks;
}

Recording on_estimated_clocks(const Recording& keyframed, const std::vector<SensorClock>& clocks) {
  Recording out = keyframed;
  out.clock = Clock::per_sensor;
  const int cycles = keyframed.cycle_count();
  // Every (keyframe, sensor) cycle in time order, each sensor's in the order of its frames.
  struct Frame {
    double t_s;
    int keyframe, sensor;
  };
  std::vector<Frame> frames;
  for (int k = 0; k < cycles; ++k) {
    for (std::size_t s = 0; s < clocks.size(); ++s) frames.push_back({clocks[s].t_s[static_cast<std::size_t>(k)], k, static_cast<int>(s)});
  }
  std::stable_sort(frames.begin(), frames.end(), [](const Frame& a, const Frame& b) { return a.t_s < b.t_s; });
  std::map<std::pair<int, int>, int> cycle_of;  // (keyframe, sensor) -> cycle
  out.cycles.clear();
  for (const Frame& f : frames) {
    cycle_of[{f.keyframe, f.sensor}] = static_cast<int>(out.cycles.size());
    out.cycles.push_back({f.t_s, f.sensor});
  }
  for (std::size_t s = 0; s < clocks.size(); ++s) out.sensors[s].cycle_time_s = clocks[s].period_s;
  out.targets.clear();
  for (RecordedTarget t : keyframed.targets) {
    t.cycle = cycle_of.at({t.cycle, t.sensor});
    t.t_s = out.cycles[static_cast<std::size_t>(t.cycle)].t_s;
    out.targets.push_back(t);
  }
  std::stable_sort(out.targets.begin(), out.targets.end(), [](const RecordedTarget& a, const RecordedTarget& b) { return a.cycle < b.cycle; });
  nlohmann::json sensors = nlohmann::json::array();
  for (const SensorClock& c : clocks) {
    sensors.push_back({{"id", c.sensor}, {"period_s", c.period_s}, {"steps", c.steps}, {"steps_timed", c.steps_matched},
                       {"steps_skipping_frames", c.steps_skipping}, {"step_residual_rms_s", c.step_residual_rms_s},
                       {"keyframe_minus_frame_s", {{"min", c.offset_min_s}, {"max", c.offset_max_s}, {"rms", c.offset_rms_s}}}});
  }
  out.source["sensor_clocks"] = {
      {"method", "estimated (rcsim import --sensor-clocks estimated): each step between a radar's consecutive frames timed by "
                 "the static world's shift at the ego's speed, the steps whole multiples of the radar's least-squares period, "
                 "the frames on that regular clock; its phase puts the keyframes about the frames on both sides (the offsets' "
                 "mean 0), as a keyframe picks the frame nearest in time"},
      {"sensors", std::move(sensors)}};
  return out;
}

}  // namespace rcsim::replay::profile
