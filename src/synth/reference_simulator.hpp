#pragma once
// The signal-level reference (`rcsim synth`): a scene => a recording (`rcsim-recording`, v1) that
// looks like a measurement campaign. Per cycle and sensor:
//   scene at t   => bodies of scatterers, placed                      (scatterers)
//   placed bodies => echoes at the sensor                              (propagation)
//   echoes       => detections                                        (signal_chain)
//   detections   => confirmed tracks = the target list                (synth_tracker)
// and per object an imperfect annotation of its box (annotation).
#include <cstdint>
#include <string>
#include <vector>

#include "common/rng.hpp"
#include "io/recording.hpp"
#include "scene/scene.hpp"
#include "synth/propagation.hpp"
#include "synth/scatterers.hpp"
#include "synth/sensor_design.hpp"
#include "synth/signal_chain.hpp"
#include "synth/synth_config.hpp"
#include "synth/synth_tracker.hpp"

namespace rcsim::synth {

struct SensorCycle {
  std::vector<Echo> echoes;
  std::vector<Detection> detections;
  std::vector<ReportedTarget> targets;
};

class ReferenceSimulator {
 public:
  // Each sensor is the design adapted to its own profile (sensor_design.hpp); a profile that
  // cannot be synthesised is refused by name (std::invalid_argument).
  ReferenceSimulator(const Scene& scene, const SynthConfig& design, std::uint64_t seed);

  int cycle_count() const { return scene_.cycle_count(); }
  std::size_t sensor_count() const { return scene_.sensors.size(); }
  // Runs cycle k (cycles must be run in order: the trackers carry state).
  void run_cycle(int cycle);
  // The same at an arbitrary time (replays use the recorded cycle times); times increasing.
  void run_at(double t_s, int only_sensor = -1);  // only_sensor >= 0: that sensor's cycle alone
  // The state of one sensor after the last run_cycle.
  const SensorCycle& sensor_cycle(std::size_t sensor) const { return last_[sensor]; }
  // The echoes of one sensor at time t (no processing), for tests and the benchmark.
  std::vector<Echo> echoes_at(std::size_t sensor, double t_s) const;
  const Scene& scene() const { return scene_; }
  // The radar one sensor is synthesised as.
  const SynthConfig& sensor_config(std::size_t sensor) const { return configs_[sensor]; }

 private:
  std::vector<PlacedBody> placed_bodies(const std::vector<ScattererBody>& bodies, double t_s) const;
  SensorState sensor_state(std::size_t sensor, double t_s) const;

  const Scene& scene_;
  std::uint64_t seed_;
  std::vector<SynthConfig> configs_;   // per sensor
  std::vector<Propagator> propagators_;  // per sensor
  // Per scene object, one set per facet wavelength among the sensors; body_set_[sensor] picks one.
  std::vector<std::vector<ScattererBody>> body_sets_;
  std::vector<std::size_t> body_set_;
  std::vector<SignalChain> chains_;    // per sensor
  std::vector<SynthTracker> trackers_;
  std::vector<Rng> noise_rngs_;
  std::vector<SensorCycle> last_;
};

struct RecordingInfo {
  std::string name;         // the recording's name (the output directory's name)
  std::string description;  // one line for people (the scene's description)
  std::string scene_file;   // the scene file's name, for provenance
};

// Runs the whole scene and returns the recording: ego log, annotated boxes, target lists (tracks,
// or raw detections for sensors whose profile reports those). Refuses (std::invalid_argument)
// what require_one_recording refuses: sensors of other cycle times than the scene's, mixed levels.
Recording make_recording(const Scene& scene, const SynthConfig& design, std::uint64_t seed, const RecordingInfo& info);

// Imperfect manual annotation of one object's box at one instant (objects.csv rows).
class Annotator {
 public:
  Annotator(const Annotation& config, std::uint64_t seed, std::size_t object_count);
  AnnotatedBox annotate(std::size_t object, double t_s, const BodyState& truth);

 private:
  Annotation config_;
  Rng rng_;
  struct Bias {
    double dx_m, dy_m, dyaw_rad;
  };
  std::vector<Bias> biases_;
};

}  // namespace rcsim::synth
