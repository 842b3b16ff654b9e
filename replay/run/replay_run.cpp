#include "replay/run/replay_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>

#include "common/angles.hpp"
#include "common/cpu_time.hpp"
#include "metrics/sensor_view.hpp"
#include "replay/import/streaming_import.hpp"
#include "replay/run/latency_episodes.hpp"
#include "replay/run/object_figures.hpp"
#include "replay/run/run_accumulators.hpp"
#include "replay/run/scene_geometry.hpp"
#include "replay/run/simulated_source.hpp"

namespace rcsim::replay {

namespace {

// What stays fixed over a run: the scene and what its geometry says each cycle.
struct RunContext {
  const Recording& rec;
  const ImportedScene& imported;
  const Scene& scene;
  const ReplayOptions& options;
  SceneGeometry& geometry;
};

// Per-cycle buffers, reused from cycle to cycle.
struct CycleBuffers {
  std::vector<metrics::BoxInSensor> boxes, in_field;
  std::vector<char> detectable;  // per object, by the scene geometry
  std::vector<int> pair_of_cell;  // per merge cell, its pair in cycle.merge_pairs
};

// The annotated boxes present now, as sensor `s` sees them: all of them (for association), the
// ones in its field of view and range (per-object figures), and, for the report's pictures, those
// near the sensor (an hour-long drive passes many), marked when detectable by the geometry.
void project_boxes(const RunContext& run, std::size_t s, double t_scene_s, const BodyState& ego,
                   const std::vector<BodyState>& object_states, CycleComparison& cycle, CycleBuffers& buffers) {
  constexpr double kPictureMargin_m = 20.0;
  const SensorConfig& config = run.scene.sensors[s].config;
  std::vector<metrics::BoxInSensor>& boxes = buffers.boxes;
  std::vector<metrics::BoxInSensor>& in_field = buffers.in_field;
  boxes.clear();
  in_field.clear();
  cycle.objects.clear();
  for (std::size_t o = 0; o < run.scene.objects.size(); ++o) {
    if (!run.scene.objects[o].present_at(t_scene_s)) continue;
    const metrics::BoxInSensor box = metrics::box_in_sensor(static_cast<int>(o), cycle.X_WS, ego, object_states[o],
                                                            run.imported.objects[o].length_m,
                                                            run.imported.objects[o].width_m);
    const bool in_fov = std::abs(box.azimuth_rad) <= config.fov.azimuth_half_rad &&
                        box.range_m >= config.fov.min_range_m && box.range_m <= config.fov.max_range_m;
    boxes.push_back(box);
    if (in_fov) in_field.push_back(box);
    if (box.range_m <= config.fov.max_range_m + kPictureMargin_m) {
      const Pose2& X_WO = object_states[o].X_WB;
      cycle.objects.push_back({static_cast<int>(o), X_WO.x_m, X_WO.y_m, X_WO.yaw_rad, buffers.detectable[o] != 0});
    }
  }
}

// Each target's Cartesian position, the object it belongs to (nearest box within the gate) and
// its offset in that object's frame, its class (object, stationary background, other) and the
// merge pair it is an artefact of, if any (pair_of_cell: the cycle's pair of each merge cell).
// v_WS_S: the sensor's own velocity, sensor frame (unused where the ego motion is unknown).
void classify_targets(std::vector<ComparedTarget>& targets, const std::vector<metrics::BoxInSensor>& boxes,
                      const std::vector<metrics::MergeCell>& cells, const std::vector<int>& pair_of_cell,
                      const Vec2& v_WS_S, bool ego_motion_known, const ReplayOptions& options,
                      const metrics::MergeParameters& merge) {
  for (ComparedTarget& t : targets) {
    t.p_ST_S = point_from_polar(t.range_m, t.azimuth_rad);
    // A merge artefact first: it belongs to no object, whatever box it lies near.
    const int cell = metrics::merge_artefact_of(cells, boxes, t.range_m, t.range_rate_mps, t.azimuth_rad, t.p_ST_S, merge);
    t.merge_pair = cell >= 0 ? pair_of_cell[static_cast<std::size_t>(cell)] : -1;
    const int box = cell >= 0 ? -1 : metrics::nearest_box(boxes, t.p_ST_S, options.association_gate_m);
    t.object = box >= 0 ? boxes[box].object : -1;
    t.p_OT_O = box >= 0 ? inverse_transform_point(boxes[box].X_SO, t.p_ST_S) : Vec2::Zero();
    if (cell >= 0) {
      t.target_class = metrics::TargetClass::other;
    } else if (!ego_motion_known) {
      // No ego motion to compensate the radial speed by (schemas/recording.md): every target of no
      // object is taken for the stationary background, by its position alone.
      t.target_class = t.object >= 0 ? metrics::TargetClass::object : metrics::TargetClass::stationary_background;
    } else {
      t.target_class = metrics::classify_target(t.object, t.range_rate_mps, t.azimuth_rad, v_WS_S, options.stationary_gate_mps);
    }
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

// Merge artefacts: per pair, the recorded ones matched by simulated ones of that pair within the
// match distance (cycle.merge_matched).
MergeCounts match_merge_artefacts(CycleComparison& cycle, double match_distance_m) {
  MergeCounts counts;
  cycle.merge_matched = 0;
  std::vector<Vec2> p_rec_S, p_sim_S;
  for (std::size_t p = 0; p < cycle.merge_pairs.size(); ++p) {
    p_rec_S.clear();
    p_sim_S.clear();
    for (const auto& t : cycle.recorded) {
      if (t.merge_pair == static_cast<int>(p)) p_rec_S.push_back(t.p_ST_S);
    }
    for (const auto& t : cycle.simulated) {
      if (t.merge_pair == static_cast<int>(p)) p_sim_S.push_back(t.p_ST_S);
    }
    counts.recorded += static_cast<long long>(p_rec_S.size());
    counts.simulated += static_cast<long long>(p_sim_S.size());
    cycle.merge_matched += metrics::matched_artefacts(p_rec_S, p_sim_S, match_distance_m);
  }
  return counts;
}

// The cycle's pairs of objects sharing a cell (each once), and the pair of each merge cell.
void merge_pairs_of(const std::vector<metrics::MergeCell>& cells, CycleComparison& cycle, std::vector<int>& pair_of_cell) {
  cycle.merge_pairs.clear();
  pair_of_cell.clear();
  for (const metrics::MergeCell& c : cells) {
    const std::pair<int, int> pair{c.object_a, c.object_b};
    auto it = std::find(cycle.merge_pairs.begin(), cycle.merge_pairs.end(), pair);
    if (it == cycle.merge_pairs.end()) it = cycle.merge_pairs.insert(it, pair);
    pair_of_cell.push_back(static_cast<int>(it - cycle.merge_pairs.begin()));
  }
}

// One sensor's comparison in one cycle: its boxes, the detectability episodes, both target
// lists, their matching and merge artefacts; then into the figures and the sink.
void compare_sensor_cycle(const RunContext& run, std::size_t s, double t_rec_s, double t_scene_s, const BodyState& ego,
                          const std::vector<BodyState>& object_states, const std::vector<RecordedTarget>& recorded,
                          SimulatedSource& source, CycleBuffers& buffers, CycleComparison& cycle,
                          LatencyEpisodes& latency, RunAccumulators& acc, ObjectFigures& objects, ReplaySink& sink) {
  const SensorConfig& config = run.scene.sensors[s].config;
  const metrics::MergeParameters merge{config.resolution.range_cell_m, config.resolution.range_rate_cell_mps,
                                       run.options.merge_match_distance_m, run.options.merge_margin_m};
  const Pose2& X_WV = ego.X_WB;  // the ego's body frame is the vehicle frame V
  cycle.sensor = static_cast<int>(s);
  cycle.X_WS = compose(X_WV, run.scene.sensors[s].X_VS);
  const auto& boxes = buffers.boxes;
  // Detectability by the scene's geometry: the start of latency episodes. Snapshots (frames
  // without a clock) have no episodes: nothing is confirmed over time between them.
  const bool timed = run.rec.timeline == Timeline::drive;
  buffers.detectable.assign(run.scene.objects.size(), 0);
  run.geometry.mark_detectable(s, buffers.detectable);
  if (timed) latency.update_detectable(s, buffers.detectable, t_rec_s);
  project_boxes(run, s, t_scene_s, ego, object_states, cycle, buffers);

  cycle.recorded.clear();
  cycle.simulated.clear();
  for (const RecordedTarget& t : recorded) {
    if (t.sensor == static_cast<int>(s)) cycle.recorded.push_back(compared_target(t));
  }
  source.append_targets(s, cycle.simulated);
  // An array that resolves azimuth gives the stronger reflector's beam, not a merged angle: no
  // merge artefacts to tell apart (docs/imaging-radar.md).
  static const std::vector<metrics::MergeCell> kNoMergeCells;
  const std::vector<metrics::MergeCell>& cells =
      config.resolution.resolves_azimuth() ? kNoMergeCells : run.geometry.merge_cells(s);
  merge_pairs_of(cells, cycle, buffers.pair_of_cell);
  const Vec2 v_WS_S = rotate(-cycle.X_WS.yaw_rad, ego.point_velocity_W(cycle.X_WS.translation()));
  const bool ego_known = run.rec.ego_motion_known;
  classify_targets(cycle.recorded, boxes, cells, buffers.pair_of_cell, v_WS_S, ego_known, run.options, merge);
  classify_targets(cycle.simulated, boxes, cells, buffers.pair_of_cell, v_WS_S, ego_known, run.options, merge);
  if (run.options.match_targets) match_targets(cycle, run.options.gospa);
  const MergeCounts merges = match_merge_artefacts(cycle, run.options.merge_match_distance_m);
  if (timed) latency.note_targets(s, cycle, t_rec_s);
  acc.add_cycle(cycle, merges.recorded, merges.simulated);
  objects.add_cycle(cycle, buffers.in_field);
  sink.add_cycle(cycle);
}

// A recording in memory, cycle by cycle.
class RecordingInMemory final : public RecordedCycles {
 public:
  explicit RecordingInMemory(const Recording& rec) : rec_(rec) {}
  bool next(int& cycle, double& t_rec_s, int& sensor, std::vector<RecordedTarget>& targets) override {
    if (k_ >= rec_.cycle_count()) return false;
    cycle = k_;
    t_rec_s = rec_.cycle_t_s(k_);
    sensor = rec_.cycle_sensor(k_);
    targets.clear();
    while (cursor_ < rec_.targets.size() && rec_.targets[cursor_].cycle == k_) targets.push_back(rec_.targets[cursor_++]);
    ++k_;
    return true;
  }

 private:
  const Recording& rec_;
  int k_ = 0;
  std::size_t cursor_ = 0;  // into rec.targets, which are in cycle order
};

// A recording read as the replay goes.
class RecordingStreamed final : public RecordedCycles {
 public:
  explicit RecordingStreamed(StreamingImport& input) : input_(input) {}
  bool next(int& cycle, double& t_rec_s, int& sensor, std::vector<RecordedTarget>& targets) override {
    return input_.next_cycle(cycle, t_rec_s, sensor, targets);
  }
  std::optional<std::pair<double, double>> take_moved_window() override { return input_.take_moved_window(); }

 private:
  StreamingImport& input_;
};

}  // namespace

ReplaySummary replay_recording_dir(const std::filesystem::path& dir, const ReplayOptions& options, ReplaySink& sink) {
  const ModelLibrary library = ModelLibrary::builtin();
  StreamingImport input(dir, library, options.import);  // read => smooth, as the replay goes
  RecordingStreamed cycles(input);
  ModelSource source(input.scene(), model_options(options.seed, options.fidelity));  // => simulate
  // => compare => store, cycle by cycle
  return compare_cycles(input.recording(), input.imported(), input.scene(), cycles, source, options, sink);
}

ReplaySummary replay_recording(const Recording& rec, const ReplayOptions& options, ReplaySink& sink) {
  const ModelLibrary library = ModelLibrary::builtin();
  const ImportedScene imported = import_recording(rec, library, options.import);
  const Scene scene = build_scene(imported, library, rec.dir.string());
  ModelSource source(scene, model_options(options.seed, options.fidelity));
  return compare_with_recording(rec, imported, scene, source, options, sink);
}

ReplaySummary compare_with_recording(const Recording& rec, const ImportedScene& imported, const Scene& scene,
                                     SimulatedSource& source, const ReplayOptions& options, ReplaySink& sink) {
  RecordingInMemory cycles(rec);
  return compare_cycles(rec, imported, scene, cycles, source, options, sink);
}

ReplaySummary compare_cycles(const Recording& rec, const ImportedScene& imported, const Scene& scene,
                             RecordedCycles& cycles, SimulatedSource& source, const ReplayOptions& options,
                             ReplaySink& sink) {
  const auto wall_start = std::chrono::steady_clock::now();
  sink.begin_run(rec, imported, scene, options);
  const std::size_t n_sensors = scene.sensors.size(), n_objects = scene.objects.size();
  SceneGeometry geometry(scene);
  RunContext run{rec, imported, scene, options, geometry};
  LatencyEpisodes latency(n_sensors, n_objects);
  RunAccumulators acc(rec.ego_motion_known);
  ObjectFigures objects(n_sensors, n_objects, options.object_range_bin_m);
  double simulate_cpu_s = 0.0;
  CycleComparison cycle;
  CycleBuffers buffers;
  std::vector<BodyState> object_states(n_objects);
  std::vector<RecordedTarget> recorded;
  int k = 0, only_sensor = -1;
  double t_rec_s = 0.0;
  int cycles_done = 0;
  while (cycles.next(k, t_rec_s, only_sensor, recorded)) {
    // Asked to stop (Ctrl-C): at this cycle boundary, the cycles before it handed to the sink.
    if (options.stop != nullptr && options.stop->load()) throw ReplayStopped(cycles_done, rec.cycle_count());
    ++cycles_done;
    // read the cycle => simulate => per sensor: boxes, detectability, match, figures, store
    if (const auto window = cycles.take_moved_window()) {
      source.cull_within(window->first, window->second);
      geometry.cull_within(window->first, window->second);
    }
    const double t_scene_s = t_rec_s - imported.time_offset_s;
    const double cpu_start_s = thread_cpu_s();
    source.run_at(t_scene_s, only_sensor);
    simulate_cpu_s += thread_cpu_s() - cpu_start_s;
    geometry.run_at(t_scene_s, only_sensor);
    // The annotated (smoothed) boxes and the ego at this time, as the scene gives them.
    const BodyState ego = scene.ego.state_at(t_scene_s);
    for (std::size_t o = 0; o < n_objects; ++o) {
      if (scene.objects[o].present_at(t_scene_s)) object_states[o] = scene.objects[o].trajectory.state_at(t_scene_s);
    }
    cycle.cycle = k;
    cycle.t_s = t_rec_s;
    for (std::size_t s = 0; s < n_sensors; ++s) {
      if (only_sensor >= 0 && static_cast<std::size_t>(only_sensor) != s) continue;  // another sensor's clock
      compare_sensor_cycle(run, s, t_rec_s, t_scene_s, ego, object_states, recorded, source, buffers, cycle, latency,
                           acc, objects, sink);
    }
  }

  ReplaySummary summary;
  summary.cycles = rec.cycle_count();
  summary.sensor_cycles = rec.sensor_cycle_count();
  acc.finish(summary);
  latency.finish(summary);
  objects.finish(summary);
  summary.simulate_cpu_s = simulate_cpu_s;
  summary.total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  sink.end_run(summary);
  return summary;
}

}  // namespace rcsim::replay
