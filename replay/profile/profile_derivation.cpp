#include "replay/profile/profile_derivation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "replay/calibrate/real_drive_fit.hpp"
#include "replay/profile/derivation_stages.hpp"
#include "replay/profile/detection_pool.hpp"
#include "scene/scene.hpp"
#include "sensor/sensor_config.hpp"
#include "sensor/stationary_background.hpp"

namespace rcsim::replay::profile {

const char* value_source_name(ValueSource source) {
  switch (source) {
    case ValueSource::derived: return "derived";
    case ValueSource::recording: return "recording";
    case ValueSource::base: return "base";
  }
  return "derived";
}

std::string value_text(const nlohmann::json& value) {
  if (value.is_null()) return "none";
  if (value.is_number_float()) return fmt::format("{:g}", value.get<double>());
  return value.is_string() ? value.get<std::string>() : value.dump();
}

std::string source_text(const DerivedValue& value) {
  return value.weak ? fmt::format("{}, weak", value_source_name(value.source)) : value_source_name(value.source);
}

std::string interval_text(const DerivedValue& value) {
  return value.has_interval() ? fmt::format("[{:.4g}, {:.4g}]", value.low, value.high) : "";
}

namespace {

using Json = nlohmann::ordered_json;

// The base profile's document and the `type` that names it for a replay.
struct Base {
  Json document;
  std::string type;
};

Base load_base(const std::string& name, const Recording& first) {
  if (is_builtin_sensor_config(name)) return {Json::parse(builtin_sensor_text(name)), name};
  const std::filesystem::path path = looks_like_path(name) ? std::filesystem::path(name) : std::filesystem::path();
  if (path.empty()) throw InputError("--base", "", unknown_sensor_message(name));
  // The recordings' own type is relative to the recording; --base to the working directory.
  const std::filesystem::path resolved = std::filesystem::exists(path) ? path : first.dir / path;
  if (!std::filesystem::exists(resolved)) throw InputError(name, "", "sensor configuration file not found (--base)");
  const Json document = parse_json_file(resolved.string());
  parse_sensor_config(JsonField(document, resolved.string(), ""));  // refuses a broken base, naming its field
  return {document, std::filesystem::absolute(resolved).string()};
}

// The values the recordings' headers give.
std::vector<DerivedValue> header_values(const DetectionPool& pool) {
  std::vector<DerivedValue> values{{"reports", "detections", ValueSource::recording, "the recordings' sensors report raw detections", 0}};
  values.push_back({"amplitude.unit", pool.amplitude_unit == AmplitudeUnit::snr_db ? "snr_db" : "relative_db", ValueSource::recording,
                    "the recordings' amplitude_unit", 0});
  if (pool.range_rate_interval_mps) {
    values.push_back({"resolution.unambiguous_range_rate_mps",
                      {pool.range_rate_interval_mps->min_mps, pool.range_rate_interval_mps->max_mps}, ValueSource::recording,
                      "the recordings' range_rate_interval_mps", 0});
  }
  return values;
}

// A law derived from the SNR and the cross-sections is the radar equation's; a base on eq. (1)
// (srr24's) takes it with its own fields dropped and the reference cross-section an ERCS of 1
// stands for: 1 m^2 (0 dBsm) until calibrate fits the reflectors.
void adopt_radar_equation(Json& doc, std::vector<DerivedValue>& values) {
  const auto derived = std::find_if(values.begin(), values.end(), [](const DerivedValue& v) {
    return v.field == "amplitude.range_exponent" && v.source == ValueSource::derived;
  });
  Json& amplitude = doc["amplitude"];
  if (derived == values.end() || amplitude.value("law", "paper_eq1") == "radar_equation") return;
  amplitude["law"] = "radar_equation";
  amplitude.erase("reference_level_db");
  amplitude.erase("reference_slope_db_per_m");
  const std::string why = "the base's law is eq. (1); the derived law is the radar equation";
  values.push_back({"amplitude.law", "radar_equation", ValueSource::derived, why, derived->support});
  if (!amplitude.contains("reference_rcs_dbsm")) {
    amplitude["reference_rcs_dbsm"] = 0.0;
    values.push_back({"amplitude.reference_rcs_dbsm", 0.0, ValueSource::base,
                      why + ": an ERCS of 1 stands for 1 m^2 (rcsim calibrate --real-drive fits the reflectors)", 0});
  }
}

// What the pooled detections show of a value the base gives: the range of their radial speeds
// and of their ranges.
struct DataExtent {
  double min_range_rate_mps = INFINITY, max_range_rate_mps = -INFINITY;
  double nearest_m = INFINITY, farthest_m = 0.0;
};
DataExtent data_extent(const DetectionPool& pool) {
  DataExtent e;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) {
      e.min_range_rate_mps = std::min(e.min_range_rate_mps, d.range_rate_mps);
      e.max_range_rate_mps = std::max(e.max_range_rate_mps, d.range_rate_mps);
      e.nearest_m = std::min(e.nearest_m, d.range_m);
      e.farthest_m = std::max(e.farthest_m, d.range_m);
    }
  }
  return e;
}

const DerivedValue* find_value(const std::vector<DerivedValue>& values, const std::string& field) {
  const auto it = std::find_if(values.begin(), values.end(), [&](const DerivedValue& v) { return v.field == field; });
  return it == values.end() ? nullptr : &*it;
}

// A base value the data contradict is replaced, said so, never kept silently: a Doppler interval
// the recordings' radial speeds run beyond (an aliasing radar reports within its interval) is
// dropped, a minimum range beyond the nearest detection is the nearest detection's.
// A relative scale's levels move with its derived threshold (docs/amplitude.md): the base's radar
// on this radar's scale. The noise floor (amplitude.noise_floor_db) keeps the base's margin below
// the threshold, and a law level the data cannot show (a relative scale's, left to calibrate) moves
// by as much as the threshold did: a radar's RCS with its threshold near -55 dB, on the base's
// noise at 0 dB and its law's 73 dB, detected every simulated cell, and calibrate's +-24 dB could
// not reach the scale. A radar reports what passed its threshold, so the detections cannot show
// the noise itself: the margins are the base's. Nothing changes where the threshold is the base's
// (an Astyx derivation stays as it was).
void move_base_levels_to_the_scale(Json& doc, const Json& base, std::vector<DerivedValue>& values) {
  Json& amplitude = doc["amplitude"];
  if (amplitude.value("unit", "snr_db") != "relative_db") {
    amplitude.erase("noise_floor_db");
    return;
  }
  const Json& base_amplitude = base.at("amplitude");
  const double base_threshold_db = base_amplitude.value("detection_threshold_db", 6.0);
  const double base_floor_db = base_amplitude.value("noise_floor_db", 0.0);
  constexpr double kFallbackMargin_db = 10.0;  // a base whose threshold is not above its noise
  const double margin_db = base_threshold_db > base_floor_db ? base_threshold_db - base_floor_db : kFallbackMargin_db;
  const double threshold_db = amplitude.at("detection_threshold_db").get<double>();
  const double shift_db = threshold_db - base_threshold_db;
  for (const char* level : {"snr_at_1m_for_1m2_db", "reference_level_db"}) {
    const std::string field = std::string("amplitude.") + level;
    const auto row = std::find_if(values.begin(), values.end(), [&](const DerivedValue& v) { return v.field == field; });
    if (shift_db == 0.0 || !amplitude.contains(level) || (row != values.end() && row->source != ValueSource::base)) continue;
    const double moved_db = round_to(amplitude.at(level).get<double>() + shift_db, 0.1);
    amplitude[level] = moved_db;
    const std::string evidence = fmt::format("the base's {:.1f} dB moved by {:+.1f} dB with the threshold onto this radar's scale "
                                             "(rcsim calibrate --real-drive fits the level)",
                                             base_amplitude.value(level, 0.0), shift_db);
    if (row != values.end()) {
      row->value = moved_db, row->evidence = evidence;
    } else {
      values.push_back({field, moved_db, ValueSource::base, evidence, 0});
    }
  }
  const double floor_db = round_to(threshold_db - margin_db, 0.1);
  if (floor_db == 0.0 && !base_amplitude.contains("noise_floor_db")) return;
  amplitude["noise_floor_db"] = floor_db;
  values.push_back({"amplitude.noise_floor_db", floor_db, ValueSource::base,
                    fmt::format("the base's threshold lies {:.1f} dB above its noise; kept so below the derived threshold "
                                "{:.1f} dB (the detections show what passed the threshold, not the noise)",
                                margin_db, threshold_db),
                    0});
}

void replace_contradicted_base_values(Json& doc, const DetectionPool& pool, std::vector<DerivedValue>& values) {
  const DataExtent e = data_extent(pool);
  const auto interval_pointer = "/resolution/unambiguous_range_rate_mps"_json_pointer;
  if (!find_value(values, "resolution.unambiguous_range_rate_mps") && doc.contains(interval_pointer)) {
    const double lo = doc.at(interval_pointer).at(0).get<double>(), hi = doc.at(interval_pointer).at(1).get<double>();
    // A radial speed on the interval's edge is in it: a CSV's last decimal.
    constexpr double kEdgeMps = 1e-3;
    if (e.min_range_rate_mps < lo - kEdgeMps || e.max_range_rate_mps > hi + kEdgeMps) {
      doc["resolution"].erase("unambiguous_range_rate_mps");
      values.push_back(with_interval({"resolution.unambiguous_range_rate_mps", nullptr, ValueSource::derived,
                                      fmt::format("the base's interval [{:.4g}, {:.4g}] m/s dropped (no Doppler aliasing): the "
                                                  "recordings' radial speeds run from {:.2f} to {:.2f} m/s, beyond it, and their "
                                                  "header gives none",
                                                  lo, hi, e.min_range_rate_mps, e.max_range_rate_mps),
                                      pool.detections},
                                     e.min_range_rate_mps, e.max_range_rate_mps, false));
    } else {
      values.push_back({"resolution.unambiguous_range_rate_mps", doc.at(interval_pointer), ValueSource::base,
                        fmt::format("the base's; the recordings' header gives none, and their radial speeds ({:.2f} to {:.2f} m/s) "
                                    "lie within it",
                                    e.min_range_rate_mps, e.max_range_rate_mps),
                        0});
    }
  }
  const auto min_range_pointer = "/field_of_view/min_range_m"_json_pointer;
  const DerivedValue* min_range = find_value(values, "field_of_view.min_range_m");
  if (min_range && min_range->source == ValueSource::base && doc.contains(min_range_pointer) &&
      doc.at(min_range_pointer).get<double>() > e.nearest_m) {
    const double base_m = doc.at(min_range_pointer).get<double>(), nearest_m = std::floor(e.nearest_m * 10.0) / 10.0;
    doc["field_of_view"]["min_range_m"] = nearest_m;
    DerivedValue& v = values[static_cast<std::size_t>(min_range - values.data())];
    v = with_interval({"field_of_view.min_range_m", nearest_m, ValueSource::derived,
                       fmt::format("the base's {:.2f} m replaced: the nearest detection lies at {:.2f} m, nearer ({})", base_m, e.nearest_m,
                                   v.evidence),
                       pool.detections},
                      nearest_m, e.nearest_m, true);
  }
}

// Every value of the profile that no stage derived and no header gave: the base's, listed so
// (the structure of the model, what calibrate fits, what no stage reads).
void list_base_leaves(const Json& node, const std::string& prefix, std::vector<DerivedValue>& values) {
  for (const auto& [key, child] : node.items()) {
    const std::string field = prefix.empty() ? key : prefix + "." + key;
    if (prefix.empty() && (key == "format" || key == "version" || key == "name" || key == "description" || key == "background")) continue;
    if (child.is_object()) {
      list_base_leaves(child, field, values);
    } else if (!find_value(values, field)) {
      values.push_back({field, child, ValueSource::base, "not derived: the base's (no stage reads it; rcsim calibrate --real-drive fits the "
                        "level, occlusion and diffuse return)", 0});
    }
  }
}

}  // namespace

ProfileDerivation derive_profile(const std::vector<const Recording*>& recordings, const DeriveOptions& options) {
  DetectionPool pool = pool_detections(recordings);
  const Base base = load_base(options.base.empty() ? pool.sensor_type : options.base, *recordings.front());

  ProfileDerivation out;
  out.base = options.base.empty() ? pool.sensor_type : options.base;
  out.detections = pool.detections;
  out.sensor_cycles = static_cast<long long>(pool.cycles.size());
  out.values = header_values(pool);
  const auto add = [&](std::vector<DerivedValue> more) { out.values.insert(out.values.end(), more.begin(), more.end()); };
  const auto derived_number = [&](const std::string& field) {
    const auto it = std::find_if(out.values.begin(), out.values.end(), [&](const DerivedValue& v) { return v.field == field; });
    return it->value.get<double>();
  };
  add(derive_view_field(pool, out.figures));
  add(derive_amplitude(pool, base.document, derived_number("field_of_view.azimuth_half_deg"), out.figures));
  const double threshold_db = derived_number("amplitude.detection_threshold_db");
  Cells cells;
  add(derive_resolution(pool, base.document, cells, out.figures));
  const ViewLimits view{deg_to_rad(derived_number("field_of_view.azimuth_half_deg")), derived_number("field_of_view.max_range_m")};
  const std::vector<FramePair> frame_pairs = match_consecutive_cycles(pool, threshold_db, view);
  add(derive_noise(pool, cells, threshold_db, frame_pairs, out.figures));
  add(derive_fluctuation(frame_pairs, pool.snapshots, out.figures));

  // The profile: the base with every derived value in place; a value the data cannot show is the
  // base's (dropped where the base has none either).
  Json& doc = out.profile = base.document;
  std::vector<DerivedValue> kept;
  for (DerivedValue& v : out.values) {
    const auto pointer = field_pointer(v.field);
    if (v.source == ValueSource::base) {
      if (!doc.contains(pointer)) continue;
      v.value = doc.at(pointer);
    } else {
      doc[pointer] = v.value;
    }
    kept.push_back(std::move(v));
  }
  out.values = std::move(kept);
  adopt_radar_equation(doc, out.values);
  move_base_levels_to_the_scale(doc, base.document, out.values);
  replace_contradicted_base_values(doc, pool, out.values);
  doc.erase("background");
  list_base_leaves(doc, "", out.values);
  doc["name"] = options.name;
  std::vector<std::string> from_base, weak;
  for (const DerivedValue& v : out.values) {
    if (v.source == ValueSource::base) from_base.push_back(v.field);
    if (v.weak) weak.push_back(v.field);
  }
  doc["description"] = fmt::format("derived by rcsim profile derive from {} detections in {} sensor cycles of {} recording(s) "
                                   "(first: {}); base {}; taken from the base: {}; derived but weakly shown by the data: {}",
                                   pool.detections, pool.cycles.size(), recordings.size(), recordings.front()->name, out.base,
                                   from_base.empty() ? "none" : fmt::format("{}", fmt::join(from_base, ", ")),
                                   weak.empty() ? "none" : fmt::format("{}", fmt::join(weak, ", ")));

  // The pool is read: its memory is the background replay's (derive in bounded memory).
  const std::size_t sensor_cycles = pool.cycles.size();
  pool = DetectionPool{};
  // The stationary background, with the derived profile in place of the recordings' type.
  SensorConfig config = parse_sensor_config(JsonField(doc, options.name, ""));
  // A recording whose sensors are of another type than the base is copied with the base's type
  // (the replay takes the profile by type); one of the base's type is replayed as it is (a copy
  // of 400 Astyx frames was 100 MB).
  std::vector<Recording> probes;
  std::vector<const Recording*> probe_pointers;
  for (const Recording* r : recordings) {
    const bool of_base_type = std::all_of(r->sensors.begin(), r->sensors.end(), [&](const RecordingSensor& s) { return s.type == base.type; });
    if (of_base_type) continue;
    probes.push_back(*r);
    for (RecordingSensor& s : probes.back().sensors) s.type = base.type;
  }
  for (std::size_t k = 0, copied = 0; k < recordings.size(); ++k) {
    const Recording* r = recordings[k];
    const bool of_base_type = std::all_of(r->sensors.begin(), r->sensors.end(), [&](const RecordingSensor& s) { return s.type == base.type; });
    probe_pointers.push_back(of_base_type ? r : &probes[copied++]);
  }
  config.name = base.document.value("name", "");
  ReplayOptions replay_options;
  replay_options.seed = options.seed;
  replay_options.fidelity = Fidelity::no_tracking;
  const StationaryBackground background = fit_stationary_background(probe_pointers, replay_options, config);
  if (background.targets_per_cycle > 0.0) {
    doc["background"] = stationary_background_to_json(background);
    // Its interval: the count's Poisson spread, +-2 sqrt(N) over the cycles; weak in fewer than 10 cycles.
    const double cycles = static_cast<double>(sensor_cycles);
    const double total = background.targets_per_cycle * cycles, half = 2.0 * std::sqrt(total) / cycles;
    const bool few_cycles = sensor_cycles < 10;
    out.values.push_back(with_interval({"background.targets_per_cycle", round_to(background.targets_per_cycle, 0.1), ValueSource::derived,
                                        fmt::format("the recorded targets replay classes as stationary background, over {} x {} bins of "
                                                    "range and azimuth{}",
                                                    background.range_bins(), background.azimuth_bins(),
                                                    few_cycles ? "; weak: fewer than 10 cycles" : ""),
                                        static_cast<long long>(std::llround(total))},
                                       std::max(0.0, background.targets_per_cycle - half), background.targets_per_cycle + half, few_cycles));
  }
  parse_sensor_config(JsonField(doc, options.name, ""));  // what is written is a profile replay reads as it is
  return out;
}

}  // namespace rcsim::replay::profile
