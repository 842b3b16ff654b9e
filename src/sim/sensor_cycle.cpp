#include "sim/sensor_cycle.hpp"

#include <stdexcept>

#include "sim/amplitude.hpp"
#include "sim/background.hpp"
#include "sim/beamforming.hpp"
#include "sim/detection.hpp"
#include "sim/doppler_aliasing.hpp"
#include "sim/effects.hpp"
#include "sim/measurement_noise.hpp"
#include "sim/monopulse.hpp"
#include "sim/resolution_cells.hpp"
#include "sim/spectral_leakage.hpp"
#include "sim/visibility.hpp"

namespace rcsim {

SensorModel::SensorModel(const MountedSensor& mount_in, const Effects& effects_in, const SimulationOptions& options_in,
                         std::span<const SceneObject> objects)
    : mount(mount_in),
      antenna(mount_in.config.antenna),
      cell_gate_amplitude(db_to_amplitude(detection_floor_db(mount_in.config))),
      effects(effects_in),
      options(options_in),
      // The ideal target list shows every echo: only the view culling (exact) applies there.
      culling(options_in.culling && !objects.empty()
                  ? make_culling_bounds(mount_in.config, effects_in, objects, options_in.level != ListLevel::ideal,
                                        // a pitched 3D view is no level wedge: cull by range only
                                        !(mount_in.config.fov.measures_elevation() && mount_in.pitch_rad != 0.0))
                  : CullingBounds{}) {}

SensorCycleState::SensorCycleState(const SensorModel& model, std::size_t reflector_capacity, double cycle_time_s, std::uint64_t seed,
                                   std::uint64_t stream)
    : tracker(model.mount.config.tracker, cycle_time_s), rng(seed, stream) {
  // Every reflector with its multibounce copies, and with diffuse face pieces up to
  // max_pieces_per_face more per reflector (a bound: only planes have them).
  const SensorConfig& config = model.mount.config;
  const std::size_t pieces = config.extended_objects.diffuse_relative_ercs_per_sqrt_m > 0.0
                                 ? static_cast<std::size_t>(config.extended_objects.max_pieces_per_face)
                                 : 0;
  const std::size_t capacity = reflector_capacity * (1 + pieces) * static_cast<std::size_t>(config.multibounce.max_order);
  // Clutter and background: a Poisson draw exceeds four times its mean + 64 about never.
  const auto drawn = static_cast<std::size_t>(4.0 * (config.clutter.false_detections_per_cycle + config.background.targets_per_cycle)) + 64;
  ideal.reserve(capacity);
  may_occlude.reserve(model.culling.radius_m.size());
  echoes.reserve(capacity);
  cell_buffers.reserve(capacity);
  cells.reserve(capacity);
  detections.reserve(capacity + drawn);
  reported.reserve(reports_detections(model)
                       ? capacity + drawn  // every detection is reported
                       : static_cast<std::size_t>(model.mount.config.tracker.max_tracks));
}

bool reports_detections(const SensorModel& model) {
  return model.options.fidelity == Fidelity::no_tracking || model.mount.config.reports == ListLevel::detections;
}

void run_sensor_cycle(const SensorModel& model, const SceneObjects& scene_objects, const SceneSnapshot& snapshot,
                      SensorCycleState& state) {
  const auto objects = scene_objects.objects;
  if (snapshot.objects.size() != objects.size() || snapshot.visited.size() != objects.size()) {
    throw std::logic_error("run_sensor_cycle: the snapshot does not match the scene's objects");
  }
  const SensorConfig& config = model.mount.config;
  Rng* rng = model.options.noise ? &state.rng : nullptr;
  state.kinematics = sensor_kinematics(snapshot.ego, model.mount.X_VS);
  state.kinematics.z_WS_m = model.mount.z_m;  // the road is level: the mounting's height is the world's
  state.kinematics.pitch_rad = model.mount.pitch_rad;
  state.kinematics.t_s = snapshot.t_s;

  // objects, sensor pose => ideal target list of visible reflection centers     (paper II-B, IV-2/3)
  IdealTargetFilter filter;
  filter.planes = model.options.fidelity != Fidelity::points_only;
  filter.culling = model.options.culling ? &model.culling : nullptr;
  filter.may_occlude = &state.may_occlude;
  filter.diffuse_relative_ercs_per_sqrt_m = config.extended_objects.diffuse_relative_ercs_per_sqrt_m;
  filter.diffuse_piece = {config.resolution.range_cell_m, config.resolution.azimuth_cell_rad,
                         config.extended_objects.max_pieces_per_face};
  filter.diffuse_on_box = config.extended_objects.surface == ExtendedObjects::Surface::box;
  filter.box_side_inset_m = config.extended_objects.box_side_inset_m;
  compute_ideal_targets(config.fov, state.kinematics, objects, snapshot.objects, snapshot.visited_indices, state.ideal,
                        filter);
  // ideal targets => those not hidden (or weakened) behind another object (only those near the view)
  if (model.effects.occlusion) {
    const bool culled = model.options.culling && state.may_occlude.size() == objects.size();
    apply_occlusion(config.occlusion, state.kinematics, objects, snapshot.objects,
                    culled ? state.may_occlude : snapshot.visited, state.ideal);
  }
  if (model.effects.multibounce) add_multibounce_targets(config.multibounce, state.ideal);
  // ideal targets => echoes: amplitude and weighted sum/delta pointers          (eqs. (1)-(3), (6))
  compute_echoes(config.amplitude, model.antenna, state.ideal, state.echoes);
  if (model.options.level == ListLevel::ideal) return;
  // echoes => resolution cells, strongest first, upper amplitude bound          (eqs. (4)-(5))
  form_resolution_cells(config.resolution, model.cell_gate_amplitude, state.echoes, state.cell_buffers, state.cells);
  // cells => cells whose RCS fluctuates from cycle to cycle (Swerling 1, 3)      (III-B, detection.hpp)
  if (rng != nullptr) apply_fluctuation(config.detection.fluctuation, *rng, state.cells);
  // cells => detections: pointer noise, monopulse angle, resulting amplitude    (eqs. (7)-(8))
  //   (an array that resolves azimuth: each beam cell's own angle, docs/imaging-radar.md)
  if (config.resolution.resolves_azimuth()) {
    estimate_beam_angles(config.array.azimuth_sigma_rad, pointer_noise_amplitude(config), state.cells, state.ideal, rng,
                         state.detections);
  } else if (model.options.fidelity == Fidelity::no_monopulse) {
    estimate_ideal_angles(model.options.angle_noise_sigma_rad, state.cells, state.ideal, rng, state.detections);
  } else {
    estimate_monopulse_angles(model.antenna, pointer_noise_amplitude(config), state.cells, state.ideal, rng, state.detections);
  }
  // detections => plus their leakage into the cells beside theirs (the FFTs' window)   (imaging-radar.md)
  add_spectral_leakage(config.resolution, config.amplitude.detection_threshold_db, state.detections);
  // detections => the local maxima of the range/range-rate map (CFAR peak search) (detection.hpp)
  if (config.detection.local_maxima_only) keep_local_maxima(config.resolution, state.detections, state.local_maxima);
  // detections => the strongest beam of each range-Doppler cell, where the radar reports one  (imaging-radar.md)
  if (config.detection.strongest_beam_per_cell) keep_strongest_beam_per_cell(config.resolution, state.detections, state.beam_order);
  // detections => those whose measured amplitude passes the threshold           (III-B)
  apply_detection_threshold(config.amplitude.detection_threshold_db, state.detections);
  // detections => with range and range-rate noise of amplitude-dependent variance (III-A)
  if (rng != nullptr) add_measurement_noise(config.noise, config.amplitude.detection_threshold_db, *rng, state.detections);
  // detections => plus sporadic false detections                                 (VI)
  if (model.effects.clutter && rng != nullptr) add_clutter(config, state.kinematics, *rng, state.detections);
  // detections => plus the fitted stationary background of the sensor's environment (VI)
  if (rng != nullptr) add_stationary_background(config.background, state.kinematics, *rng, state.detections);
  // detections => radial speeds wrapped into the unambiguous interval (Doppler aliasing)   (imaging-radar.md)
  alias_range_rates(config.resolution, state.detections);
  if (model.options.level == ListLevel::detections) return;
  // detections => tracked target list, reported after four measurements         (III-E)
  //   (a sensor that reports its detections, or fidelity no_tracking: the detections as they are)
  if (reports_detections(model)) {
    report_detections_directly(state.detections, state.reported);
  } else {
    state.tracker.step(state.detections, state.reported);
  }
}

}  // namespace rcsim
