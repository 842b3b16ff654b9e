#include "replay/run/replay_run.hpp"

#include <chrono>
#include <cmath>
#include <span>

#include "common/angles.hpp"
#include "common/cpu_time.hpp"
#include "metrics/sensor_view.hpp"
#include "sim/amplitude.hpp"
#include "replay/run/latency_episodes.hpp"
#include "replay/run/object_figures.hpp"
#include "replay/run/run_accumulators.hpp"
#include "replay/run/simulated_source.hpp"

namespace rcsim::replay {

namespace {

Vec2 cartesian_S(double range_m, double azimuth_rad) {
  return {range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad)};
}

// The largest range at which an object's strongest reflector still passes the detection
// threshold on boresight (paper eq. (1)), within the view range.
double detectable_range_m(const SensorConfig& config, const ObjectModel& model) {
  return std::min(config.fov.max_range_m, std::max(0.0, detection_range_bound_m(config.amplitude, model.max_ercs())));
}

// What stays fixed over a run: the scene, its sensors' detectable ranges per object.
struct RunContext {
  const Recording& rec;
  const ImportedScene& imported;
  const Scene& scene;
  const ReplayOptions& options;
  std::vector<std::vector<double>> detectable_m;  // [sensor][object]
};

// Per-cycle buffers, reused from cycle to cycle.
struct CycleBuffers {
  std::vector<metrics::BoxInSensor> boxes, in_view, in_field;
  std::vector<char> detected;  // per object
};

// The annotated boxes present now, as sensor `s` sees them: all of them (for association), the
// ones in its field of view and range (per-object figures), those of them within the model's
// detectable range (merge artefacts), and, for the report's pictures, those near the sensor (an
// hour-long drive passes many).
void project_boxes(const RunContext& run, std::size_t s, double t_scene_s, const BodyState& ego,
                   const std::vector<BodyState>& object_states, CycleComparison& cycle, CycleBuffers& buffers) {
  constexpr double kPictureMargin_m = 20.0;
  const SensorConfig& config = run.scene.sensors[s].config;
  std::vector<metrics::BoxInSensor>& boxes = buffers.boxes;
  std::vector<metrics::BoxInSensor>& in_view = buffers.in_view;
  std::vector<metrics::BoxInSensor>& in_field = buffers.in_field;
  boxes.clear();
  in_view.clear();
  in_field.clear();
  cycle.objects.clear();
  for (std::size_t o = 0; o < run.scene.objects.size(); ++o) {
    if (!run.scene.objects[o].present_at(t_scene_s)) continue;
    const metrics::BoxInSensor box = metrics::box_in_sensor(static_cast<int>(o), cycle.X_WS, ego, object_states[o],
                                                            run.imported.objects[o].length_m,
                                                            run.imported.objects[o].width_m);
    const bool in_fov = std::abs(box.azimuth_rad) <= config.fov.azimuth_half_rad &&
                        box.range_m >= config.fov.min_range_m && box.range_m <= config.fov.max_range_m;
    const bool visible = in_fov && box.range_m <= run.detectable_m[s][o];
    boxes.push_back(box);
    if (in_fov) in_field.push_back(box);
    if (visible) in_view.push_back(box);
    if (box.range_m <= config.fov.max_range_m + kPictureMargin_m) {
      const Pose2& X_WO = object_states[o].X_WB;
      cycle.objects.push_back({static_cast<int>(o), X_WO.x_m, X_WO.y_m, X_WO.yaw_rad, visible});
    }
  }
}

// Each target's Cartesian position, the object it belongs to (nearest box within the gate) and
// its offset in that object's frame, its class (object, stationary background, other) and the
// merge pair it is an artefact of, if any. v_WS_S: the sensor's own velocity, sensor frame.
void classify_targets(std::vector<ComparedTarget>& targets, const std::vector<metrics::BoxInSensor>& boxes,
                      const std::vector<metrics::BoxInSensor>& in_view, const std::vector<metrics::MergePair>& pairs,
                      const Vec2& v_WS_S, const ReplayOptions& options, const metrics::MergeParameters& merge) {
  for (ComparedTarget& t : targets) {
    t.p_ST_S = cartesian_S(t.range_m, t.azimuth_rad);
    const int box = metrics::nearest_box(boxes, t.p_ST_S, options.association_gate_m);
    t.object = box >= 0 ? boxes[box].object : -1;
    t.p_OT_O = box >= 0 ? inverse_transform_point(boxes[box].X_SO, t.p_ST_S) : Vec2::Zero();
    t.target_class =
        metrics::classify_target(t.object, t.range_rate_mps, t.azimuth_rad, v_WS_S, options.stationary_gate_mps);
    t.merge_pair = metrics::merge_artefact_of(in_view, pairs, t.range_m, t.azimuth_rad, t.p_ST_S, merge);
  }
}

// GOSPA between the two lists (sensor Cartesian) and each target's assigned partner; GOSPA
// between their object targets alone.
void match_targets(CycleComparison& cycle, const metrics::GospaParameters& parameters) {
  std::vector<Vec2> p_rec_S, p_sim_S, p_rec_object_S, p_sim_object_S;
  for (const auto& t : cycle.recorded) {
    p_rec_S.push_back(t.p_ST_S);
    if (t.target_class == metrics::TargetClass::object) p_rec_object_S.push_back(t.p_ST_S);
  }
  for (const auto& t : cycle.simulated) {
    p_sim_S.push_back(t.p_ST_S);
    if (t.target_class == metrics::TargetClass::object) p_sim_object_S.push_back(t.p_ST_S);
  }
  cycle.gospa = metrics::gospa(p_rec_S, p_sim_S, parameters);
  cycle.gospa_object = metrics::gospa(p_rec_object_S, p_sim_object_S, parameters);
  for (std::size_t i = 0; i < cycle.recorded.size(); ++i) {
    const int j = cycle.gospa.simulated_of_recorded[i];
    cycle.recorded[i].match = j;
    if (j >= 0) cycle.simulated[static_cast<std::size_t>(j)].match = static_cast<int>(i);
  }
}

struct MergeCounts {
  long long recorded = 0, simulated = 0;
};

// Merge artefacts: per pair, matched as many as both lists have (cycle.merge_matched).
MergeCounts match_merge_artefacts(CycleComparison& cycle, std::size_t pair_count) {
  MergeCounts counts;
  cycle.merge_matched = 0;
  for (std::size_t p = 0; p < pair_count; ++p) {
    int in_rec = 0, in_sim = 0;
    for (const auto& t : cycle.recorded) in_rec += t.merge_pair == static_cast<int>(p);
    for (const auto& t : cycle.simulated) in_sim += t.merge_pair == static_cast<int>(p);
    counts.recorded += in_rec;
    counts.simulated += in_sim;
    cycle.merge_matched += std::min(in_rec, in_sim);
  }
  return counts;
}

// One sensor's comparison in one cycle: its boxes, the detectability episodes, both target
// lists, their matching and merge artefacts; then into the figures and the sink.
void compare_sensor_cycle(const RunContext& run, std::size_t s, double t_rec_s, double t_scene_s, const BodyState& ego,
                          const std::vector<BodyState>& object_states, std::span<const RecordedTarget> recorded,
                          SimulatedSource& source, CycleBuffers& buffers, CycleComparison& cycle,
                          LatencyEpisodes& latency, RunAccumulators& acc, ObjectFigures& objects, ReplaySink& sink) {
  const SensorConfig& config = run.scene.sensors[s].config;
  const metrics::MergeParameters merge{config.resolution.range_cell_m, config.resolution.range_rate_cell_mps,
                                       run.options.merge_contour_margin_m};
  const Pose2& X_WV = ego.X_WB;  // the ego's body frame is the vehicle frame V
  cycle.sensor = static_cast<int>(s);
  cycle.X_WS = compose(X_WV, run.scene.sensors[s].X_VS);
  const auto& boxes = buffers.boxes;
  const auto& in_view = buffers.in_view;
  project_boxes(run, s, t_scene_s, ego, object_states, cycle, buffers);
  // Detectability: the source detects the object before its tracker (paper III-C/D).
  buffers.detected.assign(run.scene.objects.size(), 0);
  source.mark_detected_objects(s, boxes, run.options.association_gate_m, buffers.detected);
  latency.update_detected(s, buffers.detected, t_rec_s);

  cycle.recorded.clear();
  cycle.simulated.clear();
  for (const RecordedTarget& t : recorded) {
    if (t.sensor == static_cast<int>(s)) cycle.recorded.push_back(compared_target(t));
  }
  source.append_targets(s, cycle.simulated);
  const std::vector<metrics::MergePair> pairs = metrics::merge_pairs(in_view, merge);
  cycle.merge_pairs.clear();
  for (const auto& p : pairs) cycle.merge_pairs.emplace_back(in_view[p.box_a].object, in_view[p.box_b].object);
  const Vec2 v_WS_S = rotate(-cycle.X_WS.yaw_rad, ego.point_velocity_W(cycle.X_WS.translation()));
  classify_targets(cycle.recorded, boxes, in_view, pairs, v_WS_S, run.options, merge);
  classify_targets(cycle.simulated, boxes, in_view, pairs, v_WS_S, run.options, merge);
  match_targets(cycle, run.options.gospa);
  const MergeCounts merges = match_merge_artefacts(cycle, pairs.size());
  latency.note_first_targets(s, cycle, t_rec_s);
  acc.add_cycle(cycle, merges.recorded, merges.simulated);
  objects.add_cycle(cycle, buffers.in_field);
  sink.add_cycle(cycle);
}

}  // namespace

ReplaySummary replay_recording(const Recording& rec, const ReplayOptions& options, ReplaySink& sink) {
  const ModelLibrary library = ModelLibrary::builtin();
  const ImportedScene imported = import_recording(rec, library, options.import);
  const Scene scene = build_scene(imported, library, rec.dir.string());
  ModelSource source(scene, model_options(options.seed, options.fidelity));
  return compare_with_recording(rec, imported, scene, source, options, sink);
}

ReplaySummary compare_with_recording(const Recording& rec, const ImportedScene& imported, const Scene& scene,
                                     SimulatedSource& source, const ReplayOptions& options, ReplaySink& sink) {
  const auto wall_start = std::chrono::steady_clock::now();
  sink.begin_run(rec, imported, scene, options);
  const std::size_t n_sensors = scene.sensors.size(), n_objects = scene.objects.size();
  RunContext run{rec, imported, scene, options, std::vector<std::vector<double>>(n_sensors, std::vector<double>(n_objects))};
  for (std::size_t s = 0; s < n_sensors; ++s) {
    for (std::size_t o = 0; o < n_objects; ++o) run.detectable_m[s][o] = detectable_range_m(scene.sensors[s].config, scene.objects[o].model);
  }
  LatencyEpisodes latency(n_sensors, n_objects);
  RunAccumulators acc;
  ObjectFigures objects(n_sensors, n_objects, options.object_range_bin_m);
  double simulate_cpu_s = 0.0;
  std::size_t cursor = 0;  // into rec.targets, which are in cycle order
  CycleComparison cycle;
  CycleBuffers buffers;
  std::vector<BodyState> object_states(n_objects);
  for (int k = 0; k < rec.cycle_count(); ++k) {
    // read the cycle => simulate => per sensor: boxes, detectability, match, figures, store
    const double t_rec_s = rec.ego[k].t_s;
    const double t_scene_s = t_rec_s - imported.time_offset_s;
    const double cpu_start_s = thread_cpu_s();
    source.run_at(t_scene_s);
    simulate_cpu_s += thread_cpu_s() - cpu_start_s;
    // The annotated (smoothed) boxes and the ego at this time, as the scene gives them.
    const BodyState ego = scene.ego.state_at(t_scene_s);
    for (std::size_t o = 0; o < n_objects; ++o) {
      if (scene.objects[o].present_at(t_scene_s)) object_states[o] = scene.objects[o].trajectory.state_at(t_scene_s);
    }
    std::size_t cycle_end = cursor;
    while (cycle_end < rec.targets.size() && rec.targets[cycle_end].cycle == k) ++cycle_end;
    const std::span<const RecordedTarget> recorded(rec.targets.data() + cursor, cycle_end - cursor);
    cycle.cycle = k;
    cycle.t_s = t_rec_s;
    for (std::size_t s = 0; s < n_sensors; ++s) {
      compare_sensor_cycle(run, s, t_rec_s, t_scene_s, ego, object_states, recorded, source, buffers, cycle, latency,
                           acc, objects, sink);
    }
    cursor = cycle_end;
  }

  ReplaySummary summary;
  summary.cycles = rec.cycle_count();
  acc.finish(summary);
  latency.finish(summary);
  objects.finish(summary);
  summary.simulate_cpu_s = simulate_cpu_s;
  summary.total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  sink.end_run(summary);
  return summary;
}

}  // namespace rcsim::replay
