#include "replay/profile/profile_derivation.hpp"

#include <fmt/format.h>

#include <algorithm>

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
  if (value.is_number_float()) return fmt::format("{:g}", value.get<double>());
  return value.is_string() ? value.get<std::string>() : value.dump();
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

}  // namespace

ProfileDerivation derive_profile(const std::vector<const Recording*>& recordings, const DeriveOptions& options) {
  const DetectionPool pool = pool_detections(recordings);
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
  add(derive_resolution(pool, cells, out.figures));
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
  doc["name"] = options.name;
  doc["description"] = fmt::format("derived by rcsim profile derive from {} detections in {} sensor cycles of {} recording(s) "
                                   "(first: {}); base {}",
                                   pool.detections, pool.cycles.size(), recordings.size(), recordings.front()->name, out.base);
  doc.erase("background");

  // The stationary background, with the derived profile in place of the recordings' type.
  SensorConfig config = parse_sensor_config(JsonField(doc, options.name, ""));
  std::vector<Recording> probes;
  for (const Recording* r : recordings) {
    probes.push_back(*r);
    for (RecordingSensor& s : probes.back().sensors) s.type = base.type;
  }
  std::vector<const Recording*> probe_pointers;
  for (const Recording& r : probes) probe_pointers.push_back(&r);
  config.name = base.document.value("name", "");
  ReplayOptions replay_options;
  replay_options.seed = options.seed;
  replay_options.fidelity = Fidelity::no_tracking;
  const StationaryBackground background = fit_stationary_background(probe_pointers, replay_options, config);
  if (background.targets_per_cycle > 0.0) {
    doc["background"] = stationary_background_to_json(background);
    out.values.push_back({"background.targets_per_cycle", round_to(background.targets_per_cycle, 0.1), ValueSource::derived,
                          fmt::format("the recorded targets replay classes as stationary background, over {} x {} bins of range "
                                      "and azimuth",
                                      background.range_bins(), background.azimuth_bins()),
                          static_cast<long long>(std::llround(background.targets_per_cycle * static_cast<double>(pool.cycles.size())))});
  }
  parse_sensor_config(JsonField(doc, options.name, ""));  // what is written is a profile replay reads as it is
  return out;
}

}  // namespace rcsim::replay::profile
