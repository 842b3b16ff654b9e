#include "replay/run/replay_run.hpp"

#include <chrono>
#include <cmath>

#include "common/angles.hpp"
#include "common/cpu_time.hpp"
#include "metrics/sensor_view.hpp"
#include "replay/run/simulated_source.hpp"

namespace rcsim::replay {

namespace {

Vec2 cartesian_S(double range_m, double azimuth_rad) {
  return {range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad)};
}

// An episode of detectability ends after this many cycles without a detectable echo (longer than
// any track survives without hits).
constexpr int kEpisodeGapCycles = 10;

// The largest range at which an object's strongest reflector still passes the detection
// threshold on boresight: L0 − s R + 20 log10(ERCS_max) = threshold (paper eq. (1)).
double detectable_range_m(const SensorConfig& config, const ObjectModel& model) {
  const AmplitudeLaw& law = config.amplitude;
  const double margin_db = law.reference_level_db + 20.0 * std::log10(model.max_ercs()) - law.detection_threshold_db;
  return std::min(config.fov.max_range_m, std::max(0.0, margin_db / law.reference_slope_db_per_m));
}

struct Accumulators {
  double gospa_sum = 0.0, ospa_sum = 0.0, localisation_sum = 0.0, missed_sum = 0.0, false_sum = 0.0;
  long long sensor_cycles = 0;
  double range_sq = 0.0, azimuth_sq = 0.0, rate_sq = 0.0, amplitude_sum = 0.0;
  std::vector<float> range[2], azimuth[2], rate[2], amplitude[2], count[2];  // [recorded, simulated]
};

void classify_targets(std::vector<ComparedTarget>& targets, const std::vector<metrics::BoxInSensor>& boxes,
                      const std::vector<metrics::BoxInSensor>& in_view, const std::vector<metrics::MergePair>& pairs,
                      const ReplayOptions& options, const metrics::MergeParameters& merge) {
  for (ComparedTarget& t : targets) {
    t.p_S = cartesian_S(t.range_m, t.azimuth_rad);
    const int box = metrics::nearest_box(boxes, t.p_S, options.association_gate_m);
    t.object = box >= 0 ? boxes[box].object : -1;
    t.merge_pair = metrics::merge_artefact_of(in_view, pairs, t.range_m, t.azimuth_rad, t.p_S, merge);
  }
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
  std::vector<std::vector<double>> detectable_m(n_sensors, std::vector<double>(n_objects));
  for (std::size_t s = 0; s < n_sensors; ++s) {
    for (std::size_t o = 0; o < n_objects; ++o) detectable_m[s][o] = detectable_range_m(scene.sensors[s].config, scene.objects[o].model);
  }
  // Per (sensor, object): the open episode (detectable_from_s < 0: none) and the cycles since the
  // object was last detectable.
  std::vector<LatencyRow> latency(n_sensors * n_objects);
  std::vector<int> undetectable_cycles(n_sensors * n_objects, kEpisodeGapCycles);
  std::vector<int> episodes(n_sensors * n_objects, 0);
  std::vector<char> detectable_now(n_objects);
  for (std::size_t s = 0; s < n_sensors; ++s) {
    for (std::size_t o = 0; o < n_objects; ++o) {
      latency[s * n_objects + o] = {static_cast<int>(s), static_cast<int>(o), 0, -1.0, -1.0, -1.0};
    }
  }
  ReplaySummary summary;
  const auto close_episode = [&](std::size_t key) {
    LatencyRow& row = latency[key];
    if (row.detectable_from_s >= 0.0) summary.latencies.push_back(row);
    row.detectable_from_s = row.first_recorded_s = row.first_simulated_s = -1.0;
  };

  Accumulators acc;
  double simulate_cpu_s = 0.0;
  std::size_t cursor = 0;  // into rec.targets, which are in cycle order
  CycleComparison cycle;
  std::vector<metrics::BoxInSensor> boxes, in_view;
  std::vector<BodyState> object_states(n_objects);
  for (int k = 0; k < rec.cycle_count(); ++k) {
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
    const std::size_t cycle_end = [&] {
      std::size_t end = cursor;
      while (end < rec.targets.size() && rec.targets[end].cycle == k) ++end;
      return end;
    }();

    for (std::size_t s = 0; s < n_sensors; ++s) {
      const SensorConfig& config = scene.sensors[s].config;
      const metrics::MergeParameters merge{config.resolution.range_cell_m, config.resolution.range_rate_cell_mps,
                                           options.merge_contour_margin_m};
      cycle.cycle = k;
      cycle.sensor = static_cast<int>(s);
      cycle.t_s = t_rec_s;
      cycle.X_WS = compose(ego.X_WB, scene.sensors[s].X_VS);
      cycle.recorded.clear();
      cycle.simulated.clear();
      cycle.objects.clear();
      boxes.clear();
      in_view.clear();
      for (std::size_t o = 0; o < n_objects; ++o) {
        const SceneObject& object = scene.objects[o];
        if (!object.present_at(t_scene_s)) continue;
        const metrics::BoxInSensor box = metrics::box_in_sensor(static_cast<int>(o), cycle.X_WS, ego, object_states[o],
                                                                imported.objects[o].length_m,
                                                                imported.objects[o].width_m);
        const bool visible = std::abs(box.azimuth_rad) <= config.fov.azimuth_half_rad &&
                             box.range_m >= config.fov.min_range_m && box.range_m <= detectable_m[s][o];
        boxes.push_back(box);
        if (visible) in_view.push_back(box);
        // Boxes for the report's pictures: those near the sensors (an hour-long drive passes many).
        constexpr double kPictureMargin_m = 20.0;
        if (box.range_m <= config.fov.max_range_m + kPictureMargin_m) {
          const Pose2& X_WO = object_states[o].X_WB;
          cycle.objects.push_back({static_cast<int>(o), X_WO.x_m, X_WO.y_m, X_WO.yaw_rad, visible});
        }
      }
      // Detectability: the source detects the object (for the model a detection whose strongest
      // member is one of its reflectors, paper III-C/D), before the tracker; then the episodes.
      std::fill(detectable_now.begin(), detectable_now.end(), 0);
      source.mark_detected_objects(s, boxes, options.association_gate_m, detectable_now);
      for (std::size_t o = 0; o < n_objects; ++o) {
        const std::size_t key = s * n_objects + o;
        if (detectable_now[o]) {
          if (latency[key].detectable_from_s < 0.0) {
            latency[key].detectable_from_s = t_rec_s;
            latency[key].episode = episodes[key]++;
          }
          undetectable_cycles[key] = 0;
        } else if (++undetectable_cycles[key] == kEpisodeGapCycles) {
          close_episode(key);
        }
      }
      for (std::size_t i = cursor; i < cycle_end; ++i) {
        if (rec.targets[i].sensor == static_cast<int>(s)) cycle.recorded.push_back(compared_target(rec.targets[i]));
      }
      source.append_targets(s, cycle.simulated);
      const std::vector<metrics::MergePair> pairs = metrics::merge_pairs(in_view, merge);
      cycle.merge_pairs.clear();
      for (const auto& p : pairs) cycle.merge_pairs.emplace_back(in_view[p.box_a].object, in_view[p.box_b].object);
      classify_targets(cycle.recorded, boxes, in_view, pairs, options, merge);
      classify_targets(cycle.simulated, boxes, in_view, pairs, options, merge);

      std::vector<Vec2> p_rec, p_sim;
      for (const auto& t : cycle.recorded) p_rec.push_back(t.p_S);
      for (const auto& t : cycle.simulated) p_sim.push_back(t.p_S);
      cycle.gospa = metrics::gospa(p_rec, p_sim, options.gospa);
      for (std::size_t i = 0; i < cycle.recorded.size(); ++i) {
        const int j = cycle.gospa.simulated_of_recorded[i];
        cycle.recorded[i].match = j;
        if (j < 0) continue;
        cycle.simulated[j].match = static_cast<int>(i);
        const ComparedTarget& a = cycle.recorded[i];
        const ComparedTarget& b = cycle.simulated[j];
        acc.range_sq += std::pow(b.range_m - a.range_m, 2);
        acc.azimuth_sq += std::pow(angle_difference_rad(b.azimuth_rad, a.azimuth_rad), 2);
        acc.rate_sq += std::pow(b.range_rate_mps - a.range_rate_mps, 2);
        acc.amplitude_sum += b.amplitude_db - a.amplitude_db;
        ++summary.targets_matched;
      }

      // Merge artefacts: matched per pair as many as both lists have.
      cycle.merge_matched = 0;
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        int in_rec = 0, in_sim = 0;
        for (const auto& t : cycle.recorded) in_rec += t.merge_pair == static_cast<int>(p);
        for (const auto& t : cycle.simulated) in_sim += t.merge_pair == static_cast<int>(p);
        summary.merge_artefacts_recorded += in_rec;
        summary.merge_artefacts_simulated += in_sim;
        cycle.merge_matched += std::min(in_rec, in_sim);
      }
      summary.merge_artefacts_matched += cycle.merge_matched;

      // Confirmation latency: the first target of each object once it became detectable.
      for (int origin = 0; origin < 2; ++origin) {
        for (const auto& t : origin == 0 ? cycle.recorded : cycle.simulated) {
          if (t.object < 0) continue;
          LatencyRow& row = latency[s * n_objects + static_cast<std::size_t>(t.object)];
          double& first = origin == 0 ? row.first_recorded_s : row.first_simulated_s;
          if (row.detectable_from_s >= 0.0 && first < 0.0) first = t_rec_s;
        }
      }

      summary.targets_recorded += static_cast<long long>(cycle.recorded.size());
      summary.targets_simulated += static_cast<long long>(cycle.simulated.size());
      acc.gospa_sum += cycle.gospa.gospa_m;
      acc.ospa_sum += cycle.gospa.ospa_m;
      acc.localisation_sum += cycle.gospa.localisation_mp;
      acc.missed_sum += cycle.gospa.missed_mp;
      acc.false_sum += cycle.gospa.false_mp;
      ++acc.sensor_cycles;
      for (int origin = 0; origin < 2; ++origin) {
        const auto& list = origin == 0 ? cycle.recorded : cycle.simulated;
        for (const auto& t : list) {
          acc.range[origin].push_back(static_cast<float>(t.range_m));
          acc.azimuth[origin].push_back(static_cast<float>(t.azimuth_rad));
          acc.rate[origin].push_back(static_cast<float>(t.range_rate_mps));
          acc.amplitude[origin].push_back(static_cast<float>(t.amplitude_db));
        }
        acc.count[origin].push_back(static_cast<float>(list.size()));
      }
      sink.add_cycle(cycle);
    }
    cursor = cycle_end;
  }

  summary.cycles = rec.cycle_count();
  const double n = std::max<double>(1.0, static_cast<double>(acc.sensor_cycles));
  summary.gospa_mean_m = acc.gospa_sum / n;
  summary.ospa_mean_m = acc.ospa_sum / n;
  summary.gospa_localisation_mean_mp = acc.localisation_sum / n;
  summary.gospa_missed_mean_mp = acc.missed_sum / n;
  summary.gospa_false_mean_mp = acc.false_sum / n;
  const double m = std::max<double>(1.0, static_cast<double>(summary.targets_matched));
  summary.residual_range_rms_m = std::sqrt(acc.range_sq / m);
  summary.residual_azimuth_rms_rad = std::sqrt(acc.azimuth_sq / m);
  summary.residual_range_rate_rms_mps = std::sqrt(acc.rate_sq / m);
  summary.residual_amplitude_mean_db = acc.amplitude_sum / m;

  for (std::size_t key = 0; key < latency.size(); ++key) close_episode(key);
  double rec_sum = 0.0, sim_sum = 0.0;
  for (const LatencyRow& row : summary.latencies) {
    if (row.first_recorded_s >= 0.0 && row.first_simulated_s >= 0.0) {
      rec_sum += row.first_recorded_s - row.detectable_from_s;
      sim_sum += row.first_simulated_s - row.detectable_from_s;
      ++summary.latency_pairs;
    }
  }
  if (summary.latency_pairs > 0) {
    summary.latency_recorded_s = rec_sum / summary.latency_pairs;
    summary.latency_simulated_s = sim_sum / summary.latency_pairs;
  }

  const auto distance = [](std::vector<float>& a, std::vector<float>& b) {
    return metrics::distribution_distance(std::vector<double>(a.begin(), a.end()), std::vector<double>(b.begin(), b.end()));
  };
  summary.distances.push_back({"range", "m", distance(acc.range[0], acc.range[1])});
  summary.distances.push_back({"azimuth", "rad", distance(acc.azimuth[0], acc.azimuth[1])});
  summary.distances.push_back({"range_rate", "m/s", distance(acc.rate[0], acc.rate[1])});
  summary.distances.push_back({"amplitude", "dB", distance(acc.amplitude[0], acc.amplitude[1])});
  summary.distances.push_back({"targets_per_cycle", "1", distance(acc.count[0], acc.count[1])});

  summary.simulate_cpu_s = simulate_cpu_s;
  summary.total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  sink.end_run(summary);
  return summary;
}

}  // namespace rcsim::replay
