#include "replay/calibrate/calibration_fit.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <set>

#include "common/atomic_file.hpp"
#include "common/decibel.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "model/model_library.hpp"
#include "replay/import/calibration.hpp"
#include "replay/run/simulated_source.hpp"
#include "scene/scene.hpp"

namespace rcsim::replay {

namespace {

constexpr double kErcsLowerDb = -40.0, kErcsUpperDb = 20.0;  // search range about the starting ERCS
constexpr double kLevelRangeDb = 20.0;
constexpr double kSlopeLowerDbPerM = 0.05, kSlopeUpperDbPerM = 3.0;
constexpr double kMultibounceUpperDb = 40.0;
constexpr double kPatternExponentUpper = 3.0;
constexpr double kExponentPerDb = 1.0 / 12.0;  // 6 dB step: n moves by 0.5 (about 2.6 dB at 30 deg)
constexpr double kPositionRangeM = 0.5;      // reflectors move at most this far
constexpr double kMetresPerDb = 1.0 / 60.0;  // position step per dB of step
constexpr double kDegPerDb = 2.5;            // visibility angle step per dB of step
constexpr double kCentreRangeDeg = 30.0;
constexpr std::string_view kCalibratedSentence = " Calibrated by rcsim calibrate ";

Json parse_document(std::string_view text, const std::string& label) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw InputError(label, "", e.what());
  }
}

Json builtin_document(const std::vector<EmbeddedFile>& files, const std::string& name) {
  for (const auto& f : files) {
    if (f.name == name) return parse_document(f.text, "builtin:" + name + ".json");
  }
  throw std::out_of_range("no built-in document " + name);
}


// The documents of a start calibration, keyed as CalibrationParameter::document; none for "".
std::map<std::string, Json> start_documents(const std::string& dir) {
  std::map<std::string, Json> documents;
  if (dir.empty()) return documents;
  load_calibration(dir);  // refuses a bad directory, naming the file and field
  const std::filesystem::path index_path = std::filesystem::path(dir) / kCalibrationIndexFile;
  const Json index = parse_document(read_text_file(index_path), index_path.string());
  for (const auto& [field, prefix] : {std::pair{"sensors", "sensor:"}, std::pair{"models", "model:"}}) {
    for (const auto& [name, file] : index.at(field).items()) {
      const std::filesystem::path path = std::filesystem::path(dir) / file.get<std::string>();
      documents[prefix + name] = parse_document(read_text_file(path), path.string());
    }
  }
  return documents;
}

// A parameter's search step: ERCS in dB (multiplicative), level and multibounce loss in dB, the
// slope so that the level at 20 m moves by the step, positions and angles by their scale.
double moved(const CalibrationParameter& p, double step_db, int direction) {
  double v = p.value;
  switch (p.group) {
    case ParameterGroup::ercs: v *= db_to_amplitude(direction * step_db); break;
    case ParameterGroup::level:
    case ParameterGroup::multibounce: v += direction * step_db; break;
    case ParameterGroup::slope: v += direction * step_db / 20.0; break;
    case ParameterGroup::position: v += direction * step_db * kMetresPerDb; break;
    case ParameterGroup::visibility: v += direction * step_db * kDegPerDb; break;
    case ParameterGroup::antenna: v += direction * step_db * kExponentPerDb; break;
  }
  return std::clamp(v, p.lower, p.upper);
}

bool near(double a, double b) { return std::abs(a - b) < 1e-6; }

// Index of the reflector in `list` that mirrors reflector i about the x axis (after i), or -1.
int mirror_of(const Json& list, std::size_t i, bool plane) {
  const Json& a = list[i];
  for (std::size_t j = i + 1; j < list.size(); ++j) {
    const Json& b = list[j];
    if (!plane) {
      if (near(a.value("x_m", 0.0), b.value("x_m", 0.0)) && near(a.value("y_m", 0.0), -b.value("y_m", 0.0)) &&
          !near(a.value("y_m", 0.0), 0.0)) {
        return static_cast<int>(j);
      }
      continue;
    }
    // Mirroring reverses a plane's direction: a's from mirrors b's to.
    const auto mirrored = [&](const char* pa, const char* pb) {
      return near(a.value(std::string(pa) + "_x_m", 0.0), b.value(std::string(pb) + "_x_m", 0.0)) &&
             near(a.value(std::string(pa) + "_y_m", 0.0), -b.value(std::string(pb) + "_y_m", 0.0));
    };
    if (mirrored("from", "to") && mirrored("to", "from") && !(mirrored("from", "from") && mirrored("to", "to"))) {
      return static_cast<int>(j);
    }
  }
  return -1;
}

// The recordings, imported once, and the documents under calibration; evaluates GOSPA per
// recording for the documents' current values.
class Fitter {
 public:
  // Keeps pointers into `recordings`, which must outlive the fitter.
  Fitter(const std::vector<Recording>& recordings, const CalibrationOptions& options)
      : options_(options), library_(ModelLibrary::builtin()), calibration_(std::make_shared<Calibration>()) {
    ImportOptions import = options.replay.import;
    import.calibration_dir.clear();  // the search starts from the built-ins and the recordings' files,
    const std::map<std::string, Json> start = start_documents(options.start_dir);  // or from these
    const auto starting = [&](const std::string& key, Json fallback) {
      const auto it = start.find(key);
      return it != start.end() ? it->second : std::move(fallback);
    };
    for (const Recording& rec : recordings) {
      Entry& e = entries_.emplace_back();
      e.recording = &rec;
      e.imported = import_recording(rec, library_, import);
      e.imported.calibration = calibration_;
      for (const RecordingSensor& s : e.imported.sensors) {
        Json doc = sensor_document(s.type, rec.dir.string());
        const std::string key = "sensor:" + doc.value("name", s.type);
        documents_.try_emplace(key, starting(key, std::move(doc)));
        e.documents.insert(key);
      }
      for (const ImportedObject& o : e.imported.objects) {
        const std::string key = "model:" + o.model;
        documents_.try_emplace(key, starting(key, builtin_document(embedded_object_models(), o.model)));
        e.documents.insert(key);
      }
    }
    for (const auto& [key, doc] : documents_) parse(key);
    for (const auto& [key, doc] : documents_) add_parameters(key, doc);
  }

  std::vector<CalibrationParameter>& parameters() { return parameters_; }
  const std::map<std::string, Json>& documents() const { return documents_; }
  std::size_t size() const { return entries_.size(); }
  const Recording& recording(std::size_t i) const { return *entries_[i].recording; }

  // Replaces documents (a fitted calibration) where this fitter has them.
  void use_documents(const std::map<std::string, Json>& fitted) {
    for (const auto& [key, doc] : fitted) {
      if (const auto it = documents_.find(key); it != documents_.end()) {
        it->second = doc;
        parse(key);
      }
    }
  }

  // Sets a parameter's value in its document and re-reads the document; false (and nothing
  // changed) if the document refuses the value.
  bool set(std::size_t k, double value) {
    CalibrationParameter& p = parameters_[k];
    const double kept = p.value;
    write(k, value);
    try {
      parse(p.document);
      return true;
    } catch (const InputError&) {
      write(k, kept);
      parse(p.document);
      return false;
    }
  }

  bool touches(std::size_t recording, const std::string& document) const {
    return entries_[recording].documents.count(document) > 0;
  }

  // Mean GOSPA of the model at level full against recording i (rcsim replay's figure).
  struct Figures {
    double gospa_m = 0.0;
    double log_targets_ratio = 0.0;  // ln((simulated + 1) / (recorded + 1))
    long long object_cycles_in_view = 0;  // sensor cycles with an annotated object in view, summed
  };
  double gospa_m(std::size_t i) const { return figures(i).gospa_m; }
  Figures figures(std::size_t i) const {
    const Entry& e = entries_[i];
    const std::string base_dir = e.recording->dir.string();
    const Scene scene = build_scene(e.imported, library_, base_dir);
    ReplayOptions replay = options_.replay;
    replay.seed = options_.seed;
    replay.fidelity = Fidelity::full;
    ModelSource model(scene, model_options(options_.seed, Fidelity::full));
    DiscardingSink sink;
    const ReplaySummary s = compare_with_recording(*e.recording, e.imported, scene, model, replay, sink);
    long long in_view = 0;
    for (const auto& o : s.objects) in_view += o.cycles_in_view;
    return {s.gospa_mean_m,
            std::log((static_cast<double>(s.targets_simulated) + 1.0) / (static_cast<double>(s.targets_recorded) + 1.0)),
            in_view};
  }

 private:
  struct Entry {
    const Recording* recording = nullptr;
    ImportedScene imported;
    std::set<std::string> documents;  // the ones this recording uses
  };

  void parse(const std::string& key) {
    const auto json = nlohmann::json::parse(documents_.at(key).dump());
    const std::string label = "calibration of " + key;
    if (key.starts_with("sensor:")) {
      SensorConfig c = parse_sensor_config(JsonField(json, label, ""));
      calibration_->sensors.insert_or_assign(c.name, std::move(c));
    } else {
      ObjectModel m = parse_object_model(JsonField(json, label, ""));
      calibration_->models.insert_or_assign(m.name, std::move(m));
    }
  }

  // One value set by a parameter: multiplicative (ERCS) base * value / initial, else additive
  // base + coefficient * (value - initial).
  struct Target {
    std::string pointer;
    double base = 0.0, coefficient = 1.0;
  };

  void write(std::size_t k, double value) {
    CalibrationParameter& p = parameters_[k];
    p.value = value;
    Json& doc = documents_.at(p.document);
    for (const Target& t : targets_[k]) {
      doc[Json::json_pointer(t.pointer)] =
          p.group == ParameterGroup::ercs ? t.base * value / p.initial : t.base + t.coefficient * (value - p.initial);
    }
  }

  void add(const std::string& key, std::string name, ParameterGroup group, std::vector<Target> targets, double initial,
           double lower, double upper, std::string unit) {
    CalibrationParameter p;
    p.name = std::move(name);
    p.document = key;
    p.group = group;
    p.unit = std::move(unit);
    for (const Target& t : targets) p.pointers.push_back(t.pointer);
    p.initial = p.value = initial;
    p.lower = std::min(lower, initial);
    p.upper = std::max(upper, initial);
    parameters_.push_back(std::move(p));
    targets_.push_back(std::move(targets));
  }

  bool wanted(ParameterGroup g) const {
    return std::find(options_.groups.begin(), options_.groups.end(), g) != options_.groups.end();
  }

  // A sensor field as its own parameter.
  void add_field(const std::string& key, const Json& doc, const std::string& pointer, ParameterGroup group,
                 double lower, double upper, const std::string& unit) {
    const Json::json_pointer at(pointer);
    if (!doc.contains(at) || !doc.at(at).is_number()) {
      throw InputError("--fit", std::string(parameter_group_name(group)),
                       fmt::format("the sensor profile {} has no {} to fit", doc.value("name", key), pointer));
    }
    const double v = doc.at(at).get<double>();
    std::string name = doc.value("name", key) + pointer;
    std::replace(name.begin(), name.end(), '/', '.');
    add(key, name, group, {{pointer, v, 1.0}}, v, lower, upper, unit);
  }

  void add_model_parameters(const std::string& key, const Json& doc) {
    const std::string model = doc.value("name", key);
    for (const bool plane : {false, true}) {
      const char* list_name = plane ? "plane_reflectors" : "point_reflectors";
      if (!doc.contains(list_name)) continue;
      const Json& list = doc[list_name];
      std::vector<bool> done(list.size(), false);
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (done[i]) continue;
        std::vector<std::size_t> members{i};
        if (const int j = mirror_of(list, i, plane); j >= 0 && !done[static_cast<std::size_t>(j)]) {
          members.push_back(static_cast<std::size_t>(j));
        }
        std::string names;
        for (const std::size_t m : members) {
          done[m] = true;
          if (!names.empty()) names += '+';
          names += list[m].value("name", std::to_string(m));
        }
        const std::string prefix = fmt::format("{}.{}.", model, names);
        const auto ptr = [&](std::size_t m, const std::string& field) { return fmt::format("/{}/{}/{}", list_name, m, field); };
        const auto value = [&](std::size_t m, const std::string& field) { return doc[Json::json_pointer(ptr(m, field))].get<double>(); };
        // mirrored: the second member's y-like values move the other way
        const auto targets = [&](const std::string& field, bool mirrored) {
          std::vector<Target> t;
          for (std::size_t n = 0; n < members.size(); ++n) {
            t.push_back({ptr(members[n], field), value(members[n], field), mirrored && n > 0 ? -1.0 : 1.0});
          }
          return t;
        };
        if (wanted(ParameterGroup::ercs)) {
          const double ercs = value(i, "ercs");
          add(key, prefix + "ercs", ParameterGroup::ercs, targets("ercs", false), ercs,
              ercs * db_to_amplitude(kErcsLowerDb), ercs * db_to_amplitude(kErcsUpperDb), "ercs");
        }
        if (wanted(ParameterGroup::position) && !plane) {
          const double x = value(i, "x_m"), y = value(i, "y_m");
          add(key, prefix + "x_m", ParameterGroup::position, targets("x_m", false), x, x - kPositionRangeM, x + kPositionRangeM, "m");
          add(key, prefix + "y_m", ParameterGroup::position, targets("y_m", true), y, y - kPositionRangeM, y + kPositionRangeM, "m");
        }
        if (wanted(ParameterGroup::position) && plane) {
          // Along each member's outward chord normal (away from the model origin).
          std::vector<Target> t;
          for (const std::size_t m : members) {
            const Vec2 from(value(m, "from_x_m"), value(m, "from_y_m")), to(value(m, "to_x_m"), value(m, "to_y_m"));
            Vec2 normal = Vec2(to.y() - from.y(), from.x() - to.x()).normalized();
            if (normal.dot(0.5 * (from + to)) < 0.0) normal = -normal;
            for (const char* end : {"from", "to"}) {
              t.push_back({ptr(m, std::string(end) + "_x_m"), value(m, std::string(end) + "_x_m"), normal.x()});
              t.push_back({ptr(m, std::string(end) + "_y_m"), value(m, std::string(end) + "_y_m"), normal.y()});
            }
          }
          add(key, prefix + "outward_offset_m", ParameterGroup::position, std::move(t), 0.0, -kPositionRangeM,
              kPositionRangeM, "offset_m");
        }
        if (wanted(ParameterGroup::visibility) && !plane) {
          const double c = value(i, "visibility/center_deg");
          add(key, prefix + "visibility.center_deg", ParameterGroup::visibility, targets("visibility/center_deg", true), c,
              c - kCentreRangeDeg, c + kCentreRangeDeg, "deg");
          add(key, prefix + "visibility.full_halfwidth_deg", ParameterGroup::visibility,
              targets("visibility/full_halfwidth_deg", false), value(i, "visibility/full_halfwidth_deg"), 0.0, 90.0, "deg");
          add(key, prefix + "visibility.falloff_deg", ParameterGroup::visibility, targets("visibility/falloff_deg", false),
              value(i, "visibility/falloff_deg"), 1.0, 90.0, "deg");
        }
      }
    }
  }

  void add_parameters(const std::string& key, const Json& doc) {
    if (key.starts_with("model:")) {
      add_model_parameters(key, doc);
      return;
    }
    // level and slope are eq. (1)'s: a radar-equation profile (real radars, recordings of
    // detections) has neither, and is fitted to real drives by --real-drive.
    const bool radar_equation = doc.contains("amplitude") && doc.at("amplitude").value("law", "") == "radar_equation";
    for (const ParameterGroup g : {ParameterGroup::level, ParameterGroup::slope}) {
      if (!wanted(g) || !radar_equation) continue;
      throw InputError("--fit", std::string(parameter_group_name(g)),
                       fmt::format("the sensor profile {} has the radar-equation amplitude law (amplitude.law), with no "
                                   "eq. (1) reference {} to fit (the default --fit is ercs,slope); fit a radar-equation "
                                   "profile to real drives with --real-drive (docs/sensor-profiles.md), or its objects' "
                                   "reflectors alone with --fit ercs",
                                   doc.value("name", key), g == ParameterGroup::level ? "level" : "slope"));
    }
    if (wanted(ParameterGroup::level)) {
      const double l0 = doc.at("amplitude").value("reference_level_db", 0.0);
      add_field(key, doc, "/amplitude/reference_level_db", ParameterGroup::level, l0 - kLevelRangeDb, l0 + kLevelRangeDb, "dB");
    }
    if (wanted(ParameterGroup::slope)) {
      add_field(key, doc, "/amplitude/reference_slope_db_per_m", ParameterGroup::slope, kSlopeLowerDbPerM,
                kSlopeUpperDbPerM, "dB/m");
    }
    if (wanted(ParameterGroup::multibounce)) {
      add_field(key, doc, "/multibounce/loss_per_bounce_db", ParameterGroup::multibounce, 0.0, kMultibounceUpperDb, "dB");
    }
    if (wanted(ParameterGroup::antenna)) {
      // Optional in rcsim-sensor: absent means the paper's 1, written in so that it can be varied.
      Json& writable = documents_.at(key);
      if (!writable["antenna"].contains("amplitude_pattern_exponent")) writable["antenna"]["amplitude_pattern_exponent"] = 1.0;
      add_field(key, writable, "/antenna/amplitude_pattern_exponent", ParameterGroup::antenna, 1.0, kPatternExponentUpper, "1");
    }
  }

  CalibrationOptions options_;
  ModelLibrary library_;
  std::shared_ptr<Calibration> calibration_;  // the parsed documents, seen by every imported scene
  std::vector<Entry> entries_;
  std::map<std::string, Json> documents_;
  std::vector<CalibrationParameter> parameters_;
  std::vector<std::vector<Target>> targets_;  // per parameter
};

}  // namespace

// The rcsim-sensor document a recording's sensor type names: built-in or a file.
Json sensor_document(const std::string& type, const std::string& base_dir) {
  if (is_builtin_sensor_config(type)) return builtin_document(embedded_sensor_configs(), type);
  const std::string path = resolve_relative(base_dir, type);
  Json doc = parse_document(read_text_file(path), path);
  // Read as a profile first (InputError naming the file and field), before any of its fields is
  // taken as it stands: a "name" that is a number was a json type_error and exit status 1.
  parse_sensor_config(JsonField(nlohmann::json::parse(doc.dump()), path, ""));
  return doc;
}

std::optional<ParameterGroup> parse_parameter_group(std::string_view name) {
  for (const ParameterGroup g : {ParameterGroup::ercs, ParameterGroup::position, ParameterGroup::visibility,
                                 ParameterGroup::level, ParameterGroup::slope, ParameterGroup::multibounce,
                                 ParameterGroup::antenna}) {
    if (parameter_group_name(g) == name) return g;
  }
  return std::nullopt;
}

std::string_view parameter_group_name(ParameterGroup group) {
  switch (group) {
    case ParameterGroup::ercs: return "ercs";
    case ParameterGroup::position: return "position";
    case ParameterGroup::visibility: return "visibility";
    case ParameterGroup::level: return "level";
    case ParameterGroup::slope: return "slope";
    case ParameterGroup::multibounce: return "multibounce";
    case ParameterGroup::antenna: return "antenna";
  }
  return "?";
}

bool compares_tracks(const Recording& recording) {
  return std::any_of(recording.sensors.begin(), recording.sensors.end(),
                     [](const RecordingSensor& s) { return s.reports == ListLevel::tracks; });
}

namespace {

// Whether the model at `fidelity` runs a tracker for some sensor of the recording: its profile
// reports tracks (src/sim/sensor_cycle.cpp).
bool simulates_tracker(const Recording& recording, Fidelity fidelity) {
  if (fidelity == Fidelity::no_tracking) return false;
  return std::any_of(recording.sensors.begin(), recording.sensors.end(), [&](const RecordingSensor& s) {
    return sensor_document(s.type, recording.dir.string()).value("reports", "tracks") != "detections";
  });
}

}  // namespace

void check_fittable(const Recording& recording, Fidelity fidelity) {
  const std::string dir = recording.dir.string();
  if (recording.targets.empty()) throw InputError(dir, "", "holds no recorded target: nothing to fit the model to");
  if (recording.objects.empty()) {
    throw InputError(dir, "objects.csv", "holds no annotated object: nothing to fit the model's objects to");
  }
  if (recording.cycle_count() < kMinCalibrationCycles) {
    const bool tracks = compares_tracks(recording);
    if (tracks || simulates_tracker(recording, fidelity)) {
      throw InputError(dir, "", fmt::format("{} cycles; a fit needs {} at least (a track confirms after {} hits; {})",
                                            recording.cycle_count(), kMinCalibrationCycles, kMinCalibrationCycles,
                                            tracks ? "its sensors report tracks" : "its sensors' profiles track"));
    }
  }
  if (recording.targets.size() < kMinCalibrationTargets) {
    throw InputError(dir, "targets.csv",
                     fmt::format("{} recorded target{}: too few to fit the model to (a fit needs {} at least)",
                                 recording.targets.size(), recording.targets.size() == 1 ? "" : "s", kMinCalibrationTargets));
  }
  const RecordedTarget& first = recording.targets.front();
  const bool all_same = std::all_of(recording.targets.begin(), recording.targets.end(), [&](const RecordedTarget& t) {
    return t.range_m == first.range_m && t.azimuth_rad == first.azimuth_rad && t.range_rate_mps == first.range_rate_mps &&
           t.amplitude_db == first.amplitude_db;
  });
  if (all_same && recording.targets.size() > 1) {
    throw InputError(dir, "targets.csv",
                     fmt::format("all {} recorded targets are one point (range, azimuth, range rate, amplitude): "
                                 "nothing varies to fit",
                                 recording.targets.size()));
  }
}

CalibrationResult calibrate(const std::vector<Recording>& recordings, const CalibrationOptions& options,
                            const CalibrationProgress& progress) {
  if (recordings.empty()) throw std::invalid_argument("calibrate: no recording");
  if (!(options.initial_step_db > 0.0) || !(options.final_step_db > 0.0) || options.final_step_db > options.initial_step_db) {
    throw std::invalid_argument("calibrate: steps must satisfy 0 < final_step_db <= initial_step_db");
  }
  for (const Recording& r : recordings) check_fittable(r, Fidelity::full);
  Fitter fitter(recordings, options);
  CalibrationResult result;
  const std::size_t n = fitter.size();
  using Figures = decltype(fitter.figures(0));
  std::vector<Figures> before(n), figures(n);
  for (std::size_t i = 0; i < n; ++i) {
    figures[i] = before[i] = fitter.figures(i);
    // The reflectors' parameters act only through objects a sensor sees.
    if (before[i].object_cycles_in_view == 0) {
      throw InputError(recordings[i].dir.string(), "",
                       "no annotated object is ever within a sensor's view field: nothing to fit the reflectors to");
    }
  }
  ++result.evaluations;
  // Every recording weighs the same: GOSPA relative to its starting value (a perfect start is 1).
  // GOSPA alone rewards dropping targets it would misplace by more than the cut-off (a miss costs
  // c^p / 2, a misplaced target twice that): the fit could win by reporting nothing. So moving the
  // count of simulated targets away from the recorded one (further than at the start) costs
  // |ln ratio| on top.
  const auto objective = [&](const std::vector<Figures>& f) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double g0 = before[i].gospa_m;
      sum += g0 > 1e-9 ? f[i].gospa_m / g0 : 1.0 + f[i].gospa_m;
      sum += std::max(0.0, std::abs(f[i].log_targets_ratio) - std::abs(before[i].log_targets_ratio));
    }
    return sum / static_cast<double>(n);
  };
  double best = objective(figures);
  result.objective_before = best;
  if (progress) progress(0.0, best, result.evaluations);  // the start, evaluated
  bool moved_objective = false;

  auto& parameters = fitter.parameters();
  const auto stop_asked = [&] { return options.replay.stop != nullptr && options.replay.stop->load(); };
  for (double step_db = options.initial_step_db; step_db >= options.final_step_db * (1.0 - 1e-12) && !result.partial;
       step_db *= 0.5) {
    for (int sweep = 0; sweep < options.max_sweeps_per_step && !result.partial; ++sweep) {
      bool improved = false;
      for (std::size_t k = 0; k < parameters.size() && !result.partial; ++k) {
        const double kept = parameters[k].value;
        for (const int direction : {+1, -1}) {
          if (stop_asked()) {
            result.partial = true;  // between evaluations: the best so far stands
            break;
          }
          const double trial = moved(parameters[k], step_db, direction);
          if (trial == kept || !fitter.set(k, trial)) continue;
          std::vector<Figures> g = figures;
          try {
            for (std::size_t i = 0; i < n; ++i) {
              if (fitter.touches(i, parameters[k].document)) g[i] = fitter.figures(i);
            }
          } catch (const ReplayStopped&) {
            fitter.set(k, kept);  // the trial cut short: dropped
            result.partial = true;
            break;
          }
          ++result.evaluations;
          const double f = objective(g);
          moved_objective = moved_objective || f != result.objective_before;
          if (f < best - 1e-9) {
            best = f;
            figures = std::move(g);
            improved = true;
            break;
          }
          fitter.set(k, kept);
        }
      }
      if (!improved) break;
    }
    if (progress && !result.partial) progress(step_db, best, result.evaluations);
  }
  result.objective_after = best;
  result.flat = result.evaluations >= 2 && !moved_objective;
  result.parameters = parameters;
  result.documents = fitter.documents();
  // A start calibration's documents the recordings do not use are carried over unchanged.
  for (auto& [key, doc] : start_documents(options.start_dir)) result.documents.try_emplace(key, std::move(doc));
  for (std::size_t i = 0; i < n; ++i) {
    result.recordings.push_back({fitter.recording(i).name, before[i].gospa_m, figures[i].gospa_m});
  }
  return result;
}

std::vector<RecordingFit> cross_validate(const std::vector<Recording>& recordings, const CalibrationOptions& options,
                                         const std::function<void(const RecordingFit&)>& done) {
  if (recordings.size() < 2) throw std::invalid_argument("cross-validation needs at least two recordings");
  std::vector<RecordingFit> out;
  for (std::size_t held = 0; held < recordings.size(); ++held) {
    std::vector<Recording> others;
    for (std::size_t i = 0; i < recordings.size(); ++i) {
      if (i != held) others.push_back(recordings[i]);
    }
    const CalibrationResult fitted = calibrate(others, options);
    const std::vector<Recording> held_out{recordings[held]};  // outlives the fitter, which points into it
    Fitter one(held_out, options);
    RecordingFit fit{recordings[held].name, one.gospa_m(0), 0.0};
    one.use_documents(fitted.documents);
    fit.gospa_after_m = one.gospa_m(0);
    out.push_back(fit);
    if (done) done(fit);
  }
  return out;
}

namespace {

std::string file_name_of(const std::string& document) {
  std::string name = document;
  std::replace(name.begin(), name.end(), ':', '_');
  return name + ".json";
}

Json fits_json(const std::vector<RecordingFit>& fits) {
  Json out = Json::array();
  for (const auto& f : fits) {
    out.push_back({{"recording", f.recording}, {"gospa_before_m", f.gospa_before_m}, {"gospa_after_m", f.gospa_after_m}});
  }
  return out;
}

}  // namespace

Json start_sensor_document(const std::string& dir) {
  for (auto& [key, doc] : start_documents(dir)) {
    if (key.starts_with("sensor:")) return doc;
  }
  throw InputError((std::filesystem::path(dir) / kCalibrationIndexFile).string(), "sensors",
                   "holds no sensor profile to start a --real-drive fit from");
}

void check_calibration_output(const std::string& dir) {
  check_output_folder_writable(dir);
  check_output_file(std::filesystem::path(dir) / kCalibrationIndexFile);
}

void write_calibration(const std::string& dir, const CalibrationResult& result, const CalibrationOptions& options,
                       const std::vector<Recording>& recordings, const std::vector<RecordingFit>* held_out) {
  std::filesystem::create_directories(dir);
  Json index = {{"format", kCalibrationFormat}, {"version", kCalibrationVersion}};
  index["created_by"] = "rcsim calibrate";
  index["level"] = "full";
  index["seed"] = options.seed;
  index["started_from"] = options.start_dir.empty() ? Json() : Json(options.start_dir);
  Json groups = Json::array();
  for (const ParameterGroup g : options.groups) groups.push_back(parameter_group_name(g));
  index["groups"] = groups;
  index["search"] = {{"initial_step_db", options.initial_step_db},
                     {"final_step_db", options.final_step_db},
                     {"max_sweeps_per_step", options.max_sweeps_per_step},
                     {"evaluations", result.evaluations}};
  Json fitted_on = Json::array();
  for (const Recording& r : recordings) fitted_on.push_back({{"recording", r.name}, {"checksum", fmt::format("{:016x}", r.checksum)}});
  index["fitted_on"] = fitted_on;
  index["objective"] = {{"before", result.objective_before}, {"after", result.objective_after}, {"flat", result.flat}};
  // Interrupted (Ctrl-C): the best values so far; replay --calibration says so.
  index["partial"] = result.partial;
  index["recordings"] = fits_json(result.recordings);
  index["cross_validation"] = held_out != nullptr ? fits_json(*held_out) : Json();
  Json parameters = Json::array();
  for (const auto& p : result.parameters) {
    parameters.push_back({{"name", p.name}, {"group", parameter_group_name(p.group)}, {"document", p.document},
                          {"pointers", p.pointers}, {"unit", p.unit}, {"initial", p.initial}, {"fitted", p.value}});
  }
  index["parameters"] = parameters;
  Json sensors = Json::object(), models = Json::object();
  for (const auto& [key, doc] : result.documents) {
    Json out = doc;
    std::string description = doc.value("description", "");
    // A document started from an earlier calibration says only how it was last calibrated.
    if (const auto earlier = description.find(kCalibratedSentence); earlier != std::string::npos) description.resize(earlier);
    out["description"] = description + fmt::format("{}on {} recording(s) (seed {}).", kCalibratedSentence, recordings.size(), options.seed);
    const std::string file = file_name_of(key);
    AtomicFileWriter writer((std::filesystem::path(dir) / file).string());
    writer.stream() << out.dump(2) << '\n';
    writer.commit();
    (key.starts_with("sensor:") ? sensors : models)[doc.value("name", key)] = file;
  }
  index["sensors"] = sensors;
  index["models"] = models;
  AtomicFileWriter writer((std::filesystem::path(dir) / kCalibrationIndexFile).string());
  writer.stream() << index.dump(2) << '\n';
  writer.commit();
}

}  // namespace rcsim::replay
