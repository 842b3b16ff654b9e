#include "replay/calibrate/real_drive_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/quantile.hpp"
#include "replay/calibrate/calibration_fit.hpp"
#include "replay/run/simulated_source.hpp"

namespace rcsim::replay {

Recording restrict_to_sensor(const Recording& recording, int sensor) {
  Recording out = recording;
  out.sensors = {recording.sensors.at(static_cast<std::size_t>(sensor))};
  out.targets.clear();
  // Sensors on their own clocks: that sensor's cycles alone, renumbered.
  std::vector<int> kept_as(recording.cycles.size(), -1);
  if (recording.clock == Clock::per_sensor) {
    out.cycles.clear();
    for (std::size_t k = 0; k < recording.cycles.size(); ++k) {
      if (recording.cycles[k].sensor != sensor) continue;
      kept_as[k] = static_cast<int>(out.cycles.size());
      out.cycles.push_back({recording.cycles[k].t_s, 0});
    }
  }
  for (const RecordedTarget& t : recording.targets) {
    if (t.sensor != sensor) continue;
    out.targets.push_back(t);
    out.targets.back().sensor = 0;
    if (recording.clock == Clock::per_sensor) out.targets.back().cycle = kept_as[static_cast<std::size_t>(t.cycle)];
  }
  out.name = recording.name + "/" + recording.sensors[static_cast<std::size_t>(sensor)].id;
  return out;
}

namespace {

// A recording's every object has a box (read_recording refuses one without, and the importer
// starts each object's trajectory at its first box): an object boxed only in cycles that a cut
// left out goes with them.
void drop_unboxed_objects(Recording& recording) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < recording.objects.size(); ++i) {
    if (recording.boxes[i].empty()) continue;
    if (kept != i) {
      recording.objects[kept] = std::move(recording.objects[i]);
      recording.boxes[kept] = std::move(recording.boxes[i]);
    }
    ++kept;
  }
  recording.objects.resize(kept);
  recording.boxes.resize(kept);
}

}  // namespace

Recording restrict_to_cycles(const Recording& recording, int first, int end) {
  if (!(0 <= first && first < end && end <= recording.cycle_count())) throw std::out_of_range("restrict_to_cycles: no such cycles");
  Recording out = recording;
  if (recording.clock == Clock::per_sensor) {
    // The cycles, and the ego log's rows around them (the rows just before and after included).
    out.cycles.assign(recording.cycles.begin() + first, recording.cycles.begin() + end);
    const double t0_s = out.cycles.front().t_s, t1_s = out.cycles.back().t_s;
    const auto& ego = recording.ego;
    auto from = std::upper_bound(ego.begin(), ego.end(), t0_s, [](double t, const EgoSample& e) { return t < e.t_s; });
    if (from != ego.begin()) --from;
    auto until = std::lower_bound(ego.begin(), ego.end(), t1_s, [](const EgoSample& e, double t) { return e.t_s < t; });
    if (until != ego.end()) ++until;
    out.ego.assign(from, until);
  } else {
    out.ego.assign(recording.ego.begin() + first, recording.ego.begin() + end);
  }
  const double from_s = recording.cycle_t_s(first) - 0.5 * recording.cycle_time_s;
  const double until_s = recording.cycle_t_s(end - 1) + 0.5 * recording.cycle_time_s;
  for (auto& boxes : out.boxes) {
    std::erase_if(boxes, [&](const AnnotatedBox& b) { return b.t_s < from_s || b.t_s > until_s; });
  }
  drop_unboxed_objects(out);
  out.targets.clear();
  for (const RecordedTarget& t : recording.targets) {
    if (t.cycle < first || t.cycle >= end) continue;
    out.targets.push_back(t);
    out.targets.back().cycle -= first;
  }
  out.name = fmt::format("{}[{}:{}]", recording.name, first, end);
  return out;
}

Recording without_cycle(const Recording& recording, int held) {
  if (!(0 <= held && held < recording.cycle_count()) || recording.cycle_count() < 2) {
    throw std::out_of_range("without_cycle: no such cycle, or no other");
  }
  Recording out = recording;
  if (recording.clock == Clock::per_sensor) {
    out.cycles.erase(out.cycles.begin() + held);  // the ego log is a trajectory in time: kept whole
  } else {
    out.ego.erase(out.ego.begin() + held);
  }
  // A box belongs to the cycle nearest its time (a snapshot's box: its frame's).
  std::vector<double> cycle_t_s;
  for (int k = 0; k < recording.cycle_count(); ++k) cycle_t_s.push_back(recording.cycle_t_s(k));
  const auto nearest_cycle = [&](double t_s) {
    const auto after = std::lower_bound(cycle_t_s.begin(), cycle_t_s.end(), t_s);
    if (after == cycle_t_s.end()) return static_cast<int>(cycle_t_s.size()) - 1;
    if (after == cycle_t_s.begin() || *after - t_s < t_s - *(after - 1)) return static_cast<int>(after - cycle_t_s.begin());
    return static_cast<int>(after - cycle_t_s.begin()) - 1;
  };
  for (auto& boxes : out.boxes) {
    std::erase_if(boxes, [&](const AnnotatedBox& b) { return nearest_cycle(b.t_s) == held; });
  }
  drop_unboxed_objects(out);
  out.targets.clear();
  for (const RecordedTarget& t : recording.targets) {
    if (t.cycle == held) continue;
    out.targets.push_back(t);
    if (t.cycle > held) --out.targets.back().cycle;
  }
  out.name = fmt::format("{}[-{}]", recording.name, held);
  return out;
}

RealDriveFigures real_drive_figures(const Recording& recording, const ReplaySummary& summary) {
  RealDriveFigures f;
  std::map<int, std::pair<long long, long long>> per_object;  // recorded, simulated over sensors
  for (const ObjectFigureRow& o : summary.objects) {
    f.object_targets_recorded += o.targets_recorded;
    f.object_targets_simulated += o.targets_simulated;
    per_object[o.object].first += o.targets_recorded;
    per_object[o.object].second += o.targets_simulated;
    const double difference = static_cast<double>(o.cycles_detected_simulated - o.cycles_detected_recorded) / o.cycles_in_view;
    if (std::abs(difference) > std::abs(f.max_detection_rate_difference)) {
      f.max_detection_rate_difference = difference;
      f.max_detection_rate_object = fmt::format("{}@{}", recording.objects[static_cast<std::size_t>(o.object)].id,
                                                recording.sensors[static_cast<std::size_t>(o.sensor)].id);
    }
  }
  f.object_count_ratio = f.object_targets_recorded > 0
                             ? static_cast<double>(f.object_targets_simulated) / static_cast<double>(f.object_targets_recorded)
                             : 0.0;
  for (const auto& [object, counts] : per_object) {
    if (counts.first < 30) continue;
    const double ratio = static_cast<double>(counts.second) / static_cast<double>(counts.first);
    ++f.objects_counted;
    if (ratio >= 0.67 && ratio <= 1.5) ++f.objects_within_ratio_goal;
    if (std::abs(std::log(std::max(ratio, 1e-9))) > std::abs(std::log(std::max(f.worst_object_ratio, 1e-9)))) {
      f.worst_object_ratio = ratio;
      f.worst_object = recording.objects[static_cast<std::size_t>(object)].id;
    }
  }
  std::map<double, std::array<long long, 3>> bins;  // in view, detected recorded, detected simulated
  for (const ObjectRangeRow& r : summary.object_ranges) {
    auto& b = bins[r.range_from_m];
    b[0] += r.cycles_in_view, b[1] += r.cycles_detected_recorded, b[2] += r.cycles_detected_simulated;
  }
  for (const auto& [from_m, b] : bins) {
    if (b[0] < 10) continue;
    f.max_pd_bin_difference = std::max(f.max_pd_bin_difference, std::abs(static_cast<double>(b[2] - b[1]) / static_cast<double>(b[0])));
  }
  f.object_pairs = summary.object_pairs_matched;
  f.residual_range_rms_m = summary.residual_object_range_rms_m;
  f.residual_azimuth_rms_rad = summary.residual_object_azimuth_rms_rad;
  const double sensor_cycles = std::max(1.0, static_cast<double>(summary.sensor_cycles));
  f.background_per_cycle_recorded = static_cast<double>(summary.classes.background[0]) / sensor_cycles;
  f.background_per_cycle_simulated = static_cast<double>(summary.classes.background[1]) / sensor_cycles;
  for (const QuantityDistance& d : summary.distances) {
    if (d.quantity == "background_range") f.background_range_ks = d.distance.kolmogorov_smirnov;
  }
  return f;
}

nlohmann::ordered_json figures_to_json(const RealDriveFigures& f) {
  return {{"object_targets_recorded", f.object_targets_recorded},
          {"object_targets_simulated", f.object_targets_simulated},
          {"object_count_ratio", f.object_count_ratio},
          {"objects_counted", f.objects_counted},
          {"objects_within_ratio_goal", f.objects_within_ratio_goal},
          {"worst_object", f.worst_object},
          {"worst_object_ratio", f.worst_object_ratio},
          {"max_detection_rate_difference", f.max_detection_rate_difference},
          {"max_detection_rate_object", f.max_detection_rate_object},
          {"max_pd_bin_difference", f.max_pd_bin_difference},
          {"object_pairs", f.object_pairs},
          {"residual_range_rms_m", f.residual_range_rms_m},
          {"residual_azimuth_rms_rad", f.residual_azimuth_rms_rad},
          {"background_per_cycle_recorded", f.background_per_cycle_recorded},
          {"background_per_cycle_simulated", f.background_per_cycle_simulated},
          {"background_range_ks", f.background_range_ks}};
}

ReplaySummary replay_with_sensor(const Recording& recording, const ReplayOptions& options, const SensorConfig& config) {
  DiscardingSink sink;
  return replay_with_sensor(recording, options, config, sink);
}

ReplaySummary replay_with_sensor(const Recording& recording, const ReplayOptions& options, const SensorConfig& config,
                                 ReplaySink& sink) {
  ReplayOptions o = options;
  o.object_range_bin_m = 20.0;
  const ModelLibrary library = ModelLibrary::builtin();
  ImportedScene imported = import_recording(recording, library, o.import);
  auto calibration = std::make_shared<Calibration>();
  calibration->sensors[config.name] = config;
  imported.calibration = calibration;
  const Scene scene = build_scene(imported, library, recording.dir.string());
  ModelSource source(scene, model_options(o.seed, o.fidelity));
  return compare_with_recording(recording, imported, scene, source, o, sink);
}

namespace {

// Collects the recorded targets of class stationary background.
// Of each recorded background target what the fit reads (a whole ComparedTarget is 120 bytes:
// 400 Astyx frames' 772,000 background targets held 90-180 MB).
struct BackgroundTarget {
  double range_m = 0.0, azimuth_rad = 0.0, amplitude_db = 0.0;
};

class BackgroundSink final : public ReplaySink {
 public:
  void begin_run(const Recording&, const ImportedScene&, const Scene&, const ReplayOptions&) override {}
  void add_cycle(const CycleComparison& cycle) override {
    ++sensor_cycles;
    for (const ComparedTarget& t : cycle.recorded) {
      if (t.target_class == metrics::TargetClass::stationary_background) targets.push_back({t.range_m, t.azimuth_rad, t.amplitude_db});
    }
  }
  void end_run(const ReplaySummary&) override {}
  long long sensor_cycles = 0;
  std::vector<BackgroundTarget> targets;
};

constexpr double kBackgroundRangeBinM = 10.0;
constexpr int kBackgroundAzimuthBins = 12;

std::array<double, kAmplitudeQuantiles> deciles(std::vector<double> values) {
  std::array<double, kAmplitudeQuantiles> q{};
  std::sort(values.begin(), values.end());
  for (int k = 0; k < kAmplitudeQuantiles; ++k) q[static_cast<std::size_t>(k)] = quantile_of_sorted(values, 0.1 * k);
  return q;
}

// The recordings' sensor type, which they must share.
std::string shared_sensor_type(const std::vector<const Recording*>& recordings) {
  std::string type;
  for (const Recording* r : recordings) {
    for (const RecordingSensor& s : r->sensors) {
      if (!type.empty() && s.type != type) {
        throw InputError(r->dir.string(), "recording.json",
                         fmt::format("sensor {} is a {}, not a {}: a real-drive fit takes recordings of one sensor type", s.id,
                                     s.type, type));
      }
      type = s.type;
    }
  }
  if (type.empty()) throw std::invalid_argument("a real-drive fit needs a recording with sensors");
  return type;
}

// Lower is better: the log of the count ratio over all object targets, half the mean log ratio
// of the objects with at least 30 targets, and the mean |detection rate difference|.
double objective(const std::vector<const Recording*>& recordings, const ReplayOptions& options, const SensorConfig& config) {
  double total = 0.0;
  ReplayOptions counts_only = options;
  counts_only.match_targets = false;
  for (const Recording* r : recordings) {
    const ReplaySummary s = replay_with_sensor(*r, counts_only, config);
    long long recorded = 0, simulated = 0;
    double rate_difference = 0.0;
    std::map<int, std::pair<long long, long long>> per_object;
    for (const ObjectFigureRow& o : s.objects) {
      recorded += o.targets_recorded, simulated += o.targets_simulated;
      per_object[o.object].first += o.targets_recorded, per_object[o.object].second += o.targets_simulated;
      rate_difference += std::abs(static_cast<double>(o.cycles_detected_simulated - o.cycles_detected_recorded)) / o.cycles_in_view;
    }
    double object_logs = 0.0;
    int counted = 0;
    for (const auto& [object, c] : per_object) {
      if (c.first < 30) continue;
      object_logs += std::abs(std::log((static_cast<double>(c.second) + 1.0) / (static_cast<double>(c.first) + 1.0)));
      ++counted;
    }
    total += std::abs(std::log((static_cast<double>(simulated) + 1.0) / (static_cast<double>(recorded) + 1.0))) +
             0.5 * object_logs / std::max(1, counted) + rate_difference / static_cast<double>(std::max<std::size_t>(1, s.objects.size()));
  }
  return total / static_cast<double>(recordings.size());
}

}  // namespace

StationaryBackground fit_stationary_background(const std::vector<const Recording*>& recordings,
                                               const ReplayOptions& options, const SensorConfig& config) {
  BackgroundSink sink;
  std::string names;
  ReplayOptions classes_only = options;
  classes_only.match_targets = false;
  for (const Recording* r : recordings) {
    replay_with_sensor(*r, classes_only, config, sink);
    names += (names.empty() ? "" : ", ") + r->name;
  }
  StationaryBackground b;
  b.fitted_on = names;
  // Nothing of the stationary world seen (issue 51: all-zero range rates while the ego moves gave
  // an empty background, which then failed as "cannot create std::vector larger than max_size()").
  const auto nothing_to_fit = [&](const std::string& why) {
    throw InputError(recordings.front()->dir.string(), "",
                     fmt::format("{}: the stationary background cannot be fitted (recorded range rates that no "
                                 "stationary point gives at the ego's speed, all zero while it moves?)",
                                 why));
  };
  if (sink.sensor_cycles == 0) nothing_to_fit("no sensor cycle was replayed");
  if (sink.targets.empty()) nothing_to_fit("no recorded target is stationary background");
  for (double edge = 0.0; edge < config.fov.max_range_m; edge += kBackgroundRangeBinM) b.range_edges_m.push_back(edge);
  b.range_edges_m.push_back(config.fov.max_range_m);
  for (int k = 0; k <= kBackgroundAzimuthBins; ++k) {
    b.azimuth_edges_rad.push_back(config.fov.azimuth_half_rad * (2.0 * k / kBackgroundAzimuthBins - 1.0));
  }
  b.weights.assign(b.range_bins() * b.azimuth_bins(), 0.0);
  std::vector<std::vector<double>> amplitudes(b.range_bins());
  std::vector<double> all_amplitudes;
  long long counted = 0;
  for (const BackgroundTarget& t : sink.targets) {
    const auto bin = [](const std::vector<double>& edges, double x) {
      return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin()) - 1;
    };
    if (t.range_m < b.range_edges_m.front() || t.range_m >= b.range_edges_m.back()) continue;
    if (t.azimuth_rad < b.azimuth_edges_rad.front() || t.azimuth_rad >= b.azimuth_edges_rad.back()) continue;
    const std::size_t r = bin(b.range_edges_m, t.range_m), a = bin(b.azimuth_edges_rad, t.azimuth_rad);
    b.weights[r * b.azimuth_bins() + a] += 1.0;
    amplitudes[r].push_back(t.amplitude_db);
    all_amplitudes.push_back(t.amplitude_db);
    ++counted;
  }
  if (counted == 0) nothing_to_fit(fmt::format("none of the {} stationary-background targets lies in the sensor's view field", sink.targets.size()));
  for (double& w : b.weights) w /= static_cast<double>(counted);
  b.targets_per_cycle = static_cast<double>(counted) / static_cast<double>(sink.sensor_cycles);
  // A range bin with few targets takes the deciles of all of them.
  for (auto& a : amplitudes) b.amplitude_deciles_db.push_back(deciles(a.size() >= 10 ? a : all_amplitudes));
  return b;
}

namespace {

// The values searched, from the profile's own: a level offset, the diffuse return, the occlusion
// loss and, where the amplitude is on the radar's own scale, the range exponent.
std::vector<SearchParameter> search_parameters(const SensorConfig& c) {
  const double diffuse = c.extended_objects.diffuse_relative_ercs_per_sqrt_m;
  const double loss_db = std::isinf(c.occlusion.loss_db) ? 10.0 : std::clamp(c.occlusion.loss_db, 0.0, 40.0);
  std::vector<SearchParameter> p{
      {"amplitude.reference_rcs_dbsm", c.amplitude.reference_rcs_dbsm, c.amplitude.reference_rcs_dbsm - 24.0,
       c.amplitude.reference_rcs_dbsm + 24.0, 4.0, 0.25},
      {"extended_objects.diffuse_relative_ercs_per_sqrt_m", diffuse, 0.0, std::max(4.0 * diffuse, 0.5), std::max(0.5 * diffuse, 0.05), 0.01},
      {"occlusion.loss_db", loss_db, 0.0, 40.0, 6.0, 1.0}};
  if (c.amplitude.unit == AmplitudeUnit::relative_db) {
    p.push_back({"amplitude.range_exponent", std::clamp(c.amplitude.range_exponent, 0.0, 4.0), 0.0, 4.0, 0.5, 0.05});
  }
  return p;
}

void set_value(SensorConfig& c, const std::string& field, double value) {
  if (field == "amplitude.reference_rcs_dbsm") c.amplitude.reference_rcs_dbsm = value;
  if (field == "extended_objects.diffuse_relative_ercs_per_sqrt_m") c.extended_objects.diffuse_relative_ercs_per_sqrt_m = value;
  if (field == "occlusion.loss_db") c.occlusion.loss_db = value;
  if (field == "amplitude.range_exponent") c.amplitude.range_exponent = value;
}

}  // namespace

RealDriveFit fit_real_drive(const std::vector<const Recording*>& recordings, const ReplayOptions& options,
                            const RealDriveSearch& search) {
  const std::string type = shared_sensor_type(recordings);
  const Recording& first = *recordings.front();
  Json doc = search.start.is_null() ? sensor_document(type, first.dir.string()) : search.start;
  doc.erase("background");
  SensorConfig config = parse_sensor_config(JsonField(doc, type, ""));
  if (config.amplitude.kind != AmplitudeLawKind::radar_equation) {
    throw InputError(first.dir.string(), "sensor " + type,
                     "amplitude.law: a real-drive fit (--real-drive) needs a sensor with the radar equation; a recording "
                     "with a profile of eq. (1) (a simulated or synthetic one) is fitted without --real-drive; for a real "
                     "drive derive a profile from the recordings (rcsim profile derive) or start from a built-in one "
                     "(rcsim models --sensors --export aimotive_lrr -o radar.json) and name the file as the sensors' type");
  }
  // The background first: the profile's values are then fitted with it in place.
  ReplayOptions stoppable = options;
  stoppable.stop = search.stop;  // Ctrl-C ends a replay at its next cycle (here: ReplayStopped, nothing fitted yet)
  config.background = fit_stationary_background(recordings, stoppable, config);
  doc["background"] = stationary_background_to_json(config.background);
  const std::vector<SearchParameter> parameters = search_parameters(config);
  // Whatever the search finds must be a profile that reads back: the background and every bound
  // within the profile's limits (schemas/limits.md), checked before an hour is spent.
  for (const SearchParameter& p : parameters) {
    for (const double bound : {p.lower, p.upper}) {
      Json probe = doc;
      probe[field_pointer(p.name)] = bound;
      parse_sensor_config(JsonField(probe, type + " (fitted)", ""));
    }
  }
  const auto objective_of = [&](const std::vector<double>& x) {
    SensorConfig c = config;
    for (std::size_t i = 0; i < x.size(); ++i) set_value(c, parameters[i].name, x[i]);
    try {
      return objective(recordings, stoppable, c);
    } catch (const ReplayStopped&) {
      return static_cast<double>(INFINITY);  // the search sees the stop and drops this evaluation
    }
  };
  const SearchResult r = compass_search(parameters, objective_of, search.max_evaluations, search.stop, search.progress);
  RealDriveFit best;
  best.objective = r.objective, best.evaluations = r.evaluations, best.converged = r.converged, best.partial = r.stopped;
  best.flat = r.flat;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const SearchParameter& p = parameters[i];
    best.values.push_back({p.name, p.start, r.best[i], p.lower, p.upper, r.on_bound[i]});
    doc[field_pointer(p.name)] = r.best[i];
    if (p.name == "amplitude.reference_rcs_dbsm") best.reference_rcs_dbsm = r.best[i];
    if (p.name == "extended_objects.diffuse_relative_ercs_per_sqrt_m") best.diffuse_relative_ercs_per_sqrt_m = r.best[i];
    if (p.name == "occlusion.loss_db") best.occlusion_loss_db = r.best[i];
  }
  best.sensor_document = doc;
  return best;
}

void check_hold_out(const Recording& recording) {
  // Tracks confirm after kMinCalibrationCycles hits: each half needs some; detections need a cycle
  // to fit on and one to measure on.
  const bool tracks = compares_tracks(recording);
  const int fewest = tracks ? kMinCalibrationCycles : 2;
  if (recording.cycle_count() < fewest) {
    throw InputError(recording.dir.string(), "",
                     fmt::format("{} cycle(s): a hold-out needs at least {} to fit on some and measure on the others{}",
                                 recording.cycle_count(), fewest, tracks ? " (its sensors report tracks)" : ""));
  }
}

std::vector<HoldOut> hold_outs(const Recording& recording, const ReplayOptions& options, const RealDriveSearch& search) {
  check_hold_out(recording);
  std::vector<HoldOut> out;
  const auto run = [&](std::string name, const Recording& train, const Recording& test) {
    HoldOut h;
    h.name = std::move(name);
    h.fit = fit_real_drive({&train}, options, search);
    const SensorConfig fitted = parse_sensor_config(JsonField(h.fit.sensor_document, h.name, ""));
    h.in_sample = real_drive_figures(train, replay_with_sensor(train, options, fitted));
    h.held_out = real_drive_figures(test, replay_with_sensor(test, options, fitted));
    out.push_back(std::move(h));
  };
  if (recording.sensors.size() == 2) {
    const Recording sensor_a = restrict_to_sensor(recording, 0), sensor_b = restrict_to_sensor(recording, 1);
    run(fmt::format("{} -> {}", recording.sensors[0].id, recording.sensors[1].id), sensor_a, sensor_b);
    run(fmt::format("{} -> {}", recording.sensors[1].id, recording.sensors[0].id), sensor_b, sensor_a);
  }
  if (recording.timeline == Timeline::snapshots && recording.cycle_count() <= kMaxFramesLeftOut) {
    // Single frames, few: each left out in turn, fitted on the others.
    for (int k = 0; k < recording.cycle_count(); ++k) {
      run(fmt::format("frame {} of {} held out", k, recording.cycle_count()), without_cycle(recording, k),
          restrict_to_cycles(recording, k, k + 1));
    }
    return out;
  }
  const int half = recording.cycle_count() / 2;
  const Recording first = restrict_to_cycles(recording, 0, half), second = restrict_to_cycles(recording, half, recording.cycle_count());
  run(recording.timeline == Timeline::snapshots ? "first half of the frames -> second half" : "first half -> second half", first, second);
  return out;
}

}  // namespace rcsim::replay
