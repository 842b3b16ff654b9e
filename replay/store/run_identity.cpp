#include "replay/store/run_identity.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "common/json_reader.hpp"
#include "io/recording.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay {

std::string RunIdentity::key() const {
  std::uint64_t hash = fnv1a64(recording_checksum);
  for (const std::string& field : {std::to_string(seed), store, sensor_types, parameters}) {
    hash = fnv1a64(std::string_view("\0", 1), hash);  // a separator no field contains
    hash = fnv1a64(field, hash);
  }
  return fmt::format("{:016x}", hash);
}

std::map<std::int64_t, RunIdentity> stored_run_identities(SQLite::Database& db) {
  std::map<std::int64_t, RunIdentity> out;
  SQLite::Statement runs(db, "SELECT run_id, recording_checksum, seed, store, parameters FROM runs");
  while (runs.executeStep()) {
    RunIdentity& id = out[runs.getColumn(0).getInt64()];
    id.recording_checksum = runs.getColumn(1).getString();
    id.seed = runs.getColumn(2).getInt64();
    id.store = runs.getColumn(3).getString();
    id.parameters = runs.getColumn(4).getString();
  }
  SQLite::Statement sensors(db, "SELECT run_id, type FROM run_sensors ORDER BY run_id, sensor");
  while (sensors.executeStep()) {
    const auto it = out.find(sensors.getColumn(0).getInt64());
    if (it == out.end()) continue;
    it->second.sensor_types += sensors.getColumn(1).getString() + '\n';
  }
  return out;
}

namespace {

// "srr24 x2" for one profile on every sensor, else the profiles in sensor order.
std::string sensors_text(const std::vector<std::string>& types) {
  if (types.empty()) return "no sensor";
  if (std::all_of(types.begin(), types.end(), [&](const std::string& t) { return t == types.front(); })) {
    return types.size() == 1 ? types.front() : fmt::format("{} x{}", types.front(), types.size());
  }
  return fmt::format("{}", fmt::join(types, ", "));
}

// "all effects", "no effects" or the effects switched off ("no clutter, no occlusion").
std::string effects_text(const nlohmann::ordered_json& effects) {
  std::vector<std::string> off;
  for (const char* name : {"clutter", "multibounce", "occlusion"}) {
    if (effects.contains(name) && effects[name].is_boolean() && !effects[name].get<bool>()) off.push_back(std::string("no ") + name);
  }
  if (off.empty()) return "all effects";
  if (off.size() == 3) return "no effects";
  return fmt::format("{}", fmt::join(off, ", "));
}

std::string string_at(const nlohmann::ordered_json& json, const char* object, const char* key) {
  if (!json.contains(object) || !json[object].is_object()) return "";
  const auto& o = json[object];
  return o.contains(key) && o[key].is_string() ? o[key].get<std::string>() : "";
}

}  // namespace

std::string RunLabel::text() const {
  const std::string calibrated =
      calibration.empty() ? "no calibration"
                          : fmt::format("calibration {}{}", calibration,
                                        calibration_checksum.empty() ? "" : " #" + calibration_checksum.substr(0, 8));
  return fmt::format("{}, fidelity {}, {}, {}, seed {}", sensors, fidelity, effects, calibrated, seed);
}

std::map<std::int64_t, RunLabel> read_run_labels(SQLite::Database& db, std::optional<std::int64_t> only_run) {
  std::map<std::int64_t, RunLabel> out;
  std::map<std::int64_t, std::vector<std::string>> types;
  const char* const where = only_run ? " WHERE run_id = ?" : "";
  SQLite::Statement sensors(db, fmt::format("SELECT run_id, type FROM run_sensors{} ORDER BY run_id, sensor", where));
  SQLite::Statement runs(db, fmt::format("SELECT run_id, seed, level, parameters FROM runs{}", where));
  if (only_run) {
    sensors.bind(1, *only_run);
    runs.bind(1, *only_run);
  }
  while (sensors.executeStep()) types[sensors.getColumn(0).getInt64()].push_back(sensors.getColumn(1).getString());
  while (runs.executeStep()) {
    const std::int64_t run_id = runs.getColumn(0).getInt64();
    RunLabel& label = out[run_id];
    label.sensors = sensors_text(types[run_id]);
    label.seed = runs.getColumn(1).getInt64();
    label.level = runs.getColumn(2).getString();
    const nlohmann::ordered_json parameters = parse_stored_json(runs.getColumn(3).getString());
    label.fidelity = string_at(parameters, "fidelity", "level");
    if (label.fidelity.empty()) label.fidelity = "full";
    label.calibration = string_at(parameters, "import", "calibration");
    label.calibration_checksum = string_at(parameters, "import", "calibration_checksum");
    const bool has_effects = parameters.contains("import") && parameters["import"].is_object() &&
                             parameters["import"].contains("effects");
    label.effects = has_effects ? effects_text(parameters["import"]["effects"]) : "all effects";
  }
  return out;
}

std::vector<std::string> stored_recording_dirs(SQLite::Database& db) {
  std::vector<std::string> out;
  if (!db.tableExists("runs")) return out;  // a shard report created, its schema not yet written
  SQLite::Statement runs(db, "SELECT recording_dir FROM runs ORDER BY run_id");
  while (runs.executeStep()) out.push_back(runs.getColumn(0).getString());
  return out;
}

RunIdentity planned_run_identity(std::uint64_t recording_checksum, const ImportedScene& header_import,
                                 const ReplayOptions& options, StoreLevel store) {
  RunIdentity id;
  id.recording_checksum = fmt::format("{:016x}", recording_checksum);
  id.seed = static_cast<std::int64_t>(options.seed);
  id.store = std::string(store_level_name(store));
  for (const RecordingSensor& s : header_import.sensors) id.sensor_types += s.type + '\n';
  id.parameters = run_parameters_json(options, header_import.effects).dump();
  return id;
}

}  // namespace rcsim::replay
