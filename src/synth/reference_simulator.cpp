#include "synth/reference_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angles.hpp"

namespace rcsim::synth {
namespace {

// Random streams, all from the one seed: noise per sensor, annotation, clutter tiles (scatterers).
constexpr std::uint64_t kNoiseStream = 1000;
constexpr std::uint64_t kAnnotationStream = 7;

// Road clutter lies low: beyond the sensor's range the two-ray path cancels it (Lloyd's mirror).
double clutter_radius_m(const SynthConfig& config) { return config.antenna.max_range_m + 5.0; }

// A detection as the target list reports it when the sensor reports raw detections: no track id.
ReportedTarget as_reported(const Detection& d) { return {-1, d.range_m, d.azimuth_rad, d.range_rate_mps, d.amplitude_db}; }

}  // namespace

ReferenceSimulator::ReferenceSimulator(const Scene& scene, const SynthConfig& design, std::uint64_t seed)
    : scene_(scene), seed_(seed), configs_(sensor_designs(scene, design)) {
  for (const auto& object : scene_.objects) {
    if (object.model.polyline_points > 0) {
      throw std::invalid_argument("object \"" + object.id + "\" is a polyline (" + object.model_name +
                                  "), which the signal-level reference does not model (docs/static-world.md)");
    }
  }
  std::vector<double> set_wavelengths_m;
  for (std::size_t s = 0; s < scene_.sensors.size(); ++s) {
    const SynthConfig& config = configs_[s];
    // Sensors of one design share its calibrated chain (copied) and its bodies.
    std::size_t same = 0;
    while (same < s && !(configs_[same] == config)) ++same;
    chains_.push_back(same < s ? chains_[same] : SignalChain(config));
    propagators_.emplace_back(config);
    const double lambda_m = config.propagation.facet_wavelength_m;
    const auto set = std::find(set_wavelengths_m.begin(), set_wavelengths_m.end(), lambda_m);
    body_set_.push_back(static_cast<std::size_t>(set - set_wavelengths_m.begin()));
    if (set == set_wavelengths_m.end()) {
      set_wavelengths_m.push_back(lambda_m);
      auto& bodies = body_sets_.emplace_back();
      for (const auto& object : scene_.objects) {
        bodies.push_back(make_body(object.model_name, object.model.length_m, object.model.width_m, lambda_m));
      }
    }
    trackers_.emplace_back(config.tracker, scene_.sensor_cycle_time_s(s));
    noise_rngs_.emplace_back(seed_, kNoiseStream + s);
  }
  last_.resize(scene_.sensors.size());
}

std::vector<PlacedBody> ReferenceSimulator::placed_bodies(const std::vector<ScattererBody>& bodies, double t_s) const {
  std::vector<PlacedBody> placed;
  for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
    if (!scene_.objects[i].present_at(t_s)) continue;
    placed.push_back({&bodies[i], scene_.objects[i].trajectory.state_at(t_s)});
  }
  return placed;
}

SensorState ReferenceSimulator::sensor_state(std::size_t sensor, double t_s) const {
  const BodyState ego = scene_.ego.state_at(t_s);
  SensorState state;
  const Pose2& X_WV = ego.X_WB;  // the ego's body frame is the vehicle frame V
  state.X_WS = compose(X_WV, scene_.sensors[sensor].X_VS);
  state.v_WS_W = ego.point_velocity_W(state.X_WS.translation());
  return state;
}

std::vector<Echo> ReferenceSimulator::echoes_at(std::size_t sensor, double t_s) const {
  const SensorState state = sensor_state(sensor, t_s);
  const SynthConfig& config = configs_[sensor];
  std::vector<WorldScatterer> clutter;
  if (scene_.effects.clutter) clutter = road_clutter_near(config.clutter, seed_, state.X_WS.translation(), clutter_radius_m(config));
  return propagators_[sensor].echoes(state, placed_bodies(body_sets_[body_set_[sensor]], t_s), clutter);
}

void ReferenceSimulator::run_cycle(int cycle) { run_at(scene_.cycle_time_at(cycle)); }

void ReferenceSimulator::run_at(double t_s, int only_sensor) {
  for (std::size_t s = 0; s < scene_.sensors.size(); ++s) {
    if (only_sensor >= 0 && static_cast<std::size_t>(only_sensor) != s) continue;
    SensorCycle& out = last_[s];
    out.echoes = echoes_at(s, t_s);                                  // scene => echoes
    out.detections = chains_[s].process(out.echoes, noise_rngs_[s]);  // echoes => detections
    if (configs_[s].reports_detections) {                              // detections => target list
      out.targets.clear();
      for (const Detection& d : out.detections) out.targets.push_back(as_reported(d));
    } else {
      out.targets = trackers_[s].step(out.detections);
    }
  }
}

Annotator::Annotator(const Annotation& config, std::uint64_t seed, std::size_t object_count)
    : config_(config), rng_(seed, kAnnotationStream) {
  for (std::size_t i = 0; i < object_count; ++i) {
    biases_.push_back({config_.position_bias_sigma_m * rng_.normal(), config_.position_bias_sigma_m * rng_.normal(),
                       config_.yaw_bias_sigma_rad * rng_.normal()});
  }
}

AnnotatedBox Annotator::annotate(std::size_t object, double t_s, const BodyState& truth) {
  const Bias& b = biases_[object];
  AnnotatedBox box;
  box.t_s = t_s;
  box.x_m = truth.X_WB.x_m + b.dx_m + config_.position_jitter_sigma_m * rng_.normal();
  box.y_m = truth.X_WB.y_m + b.dy_m + config_.position_jitter_sigma_m * rng_.normal();
  box.yaw_rad = wrap_angle_rad(truth.X_WB.yaw_rad + b.dyaw_rad + config_.yaw_jitter_sigma_rad * rng_.normal());
  box.speed_mps = truth.heading_speed_mps() + config_.speed_sigma_mps * rng_.normal();
  return box;
}

Recording make_recording(const Scene& scene, const SynthConfig& design, std::uint64_t seed, const RecordingInfo& info) {
  require_one_recording(scene, design);  // one cycle clock, one level: or refused naming the sensors
  ReferenceSimulator simulator(scene, design, seed);
  Recording rec;
  rec.name = info.name;
  rec.description = info.description;
  rec.cycle_time_s = scene.cycle_time_s;
  // Per sensor, the radar it was synthesised as.
  nlohmann::json signal_chains = nlohmann::json::object();
  // The annotator labels what the farthest-reaching sensor sees.
  Annotation annotation = design.annotation;
  annotation.max_range_m = 0.0;
  for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
    const MountedSensor& sensor = scene.sensors[s];
    const SynthConfig& config = simulator.sensor_config(s);
    RecordingSensor& recorded = rec.sensors.emplace_back();
    recorded.id = sensor.id;
    recorded.type = sensor.config.name;
    recorded.x_m = sensor.X_VS.x_m;
    recorded.y_m = sensor.X_VS.y_m;
    recorded.yaw_rad = sensor.X_VS.yaw_rad;
    recorded.z_m = sensor.z_m;
    recorded.pitch_rad = sensor.pitch_rad;
    recorded.reports = config.reports_detections ? ListLevel::detections : ListLevel::tracks;
    const Derived derived = derive(config);
    signal_chains[sensor.id] = {{"carrier_hz", config.waveform.carrier_hz},
                                {"bandwidth_hz", config.waveform.bandwidth_hz},
                                {"chirps", config.waveform.chirps},
                                {"samples_per_chirp", config.waveform.samples_per_chirp},
                                {"chirp_period_s", config.waveform.chirp_period_s},
                                {"range_bin_m", std::round(derived.range_bin_m * 1e4) / 1e4},
                                {"range_rate_bin_mps", std::round(derived.range_rate_bin_mps * 1e4) / 1e4},
                                {"max_range_m", config.antenna.max_range_m},
                                {"azimuth_half_fov_deg", config.antenna.azimuth_half_fov_deg}};
    annotation.max_range_m = std::max(annotation.max_range_m, config.annotation.max_range_m);
  }
  rec.source = {{"generator", "rcsim synth"},
                {"rcsim_version", RCSIM_VERSION},
                {"scene", info.scene_file},
                {"seed", seed},
                {"effects",
                 {{"clutter", scene.effects.clutter},
                  {"multibounce", scene.effects.multibounce},
                  {"occlusion", scene.effects.occlusion}}},
                {"signal_chain", signal_chains}};

  Annotator annotator(annotation, seed, scene.objects.size());
  std::vector<std::vector<AnnotatedBox>> boxes(scene.objects.size());
  for (int k = 0; k < simulator.cycle_count(); ++k) {
    const double t_s = scene.cycle_time_at(k);
    const BodyState ego = scene.ego.state_at(t_s);
    rec.ego.push_back(ego_sample(t_s, ego));
    // The annotator labels the objects near the ego (within annotation.max_range_m).
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      if (!scene.objects[i].present_at(t_s)) continue;
      const BodyState truth = scene.objects[i].trajectory.state_at(t_s);
      if ((truth.X_WB.translation() - ego.X_WB.translation()).norm() > annotation.max_range_m) continue;
      boxes[i].push_back(annotator.annotate(i, t_s, truth));
    }
    simulator.run_cycle(k);
    for (std::size_t s = 0; s < simulator.sensor_count(); ++s) {
      for (const auto& target : simulator.sensor_cycle(s).targets) {
        rec.targets.push_back({t_s, k, static_cast<int>(s), target.id, target.range_m, target.azimuth_rad,
                               target.range_rate_mps, target.amplitude_db});
      }
    }
  }
  // Objects never annotated (never present or never near) are not listed.
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (boxes[i].empty()) continue;
    const auto& o = scene.objects[i];
    rec.objects.push_back({o.id, o.model_name, o.model.length_m, o.model.width_m});
    rec.boxes.push_back(std::move(boxes[i]));
  }
  return rec;
}

}  // namespace rcsim::synth
