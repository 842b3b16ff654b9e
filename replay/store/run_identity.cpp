#include "replay/store/run_identity.hpp"

#include <fmt/format.h>

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
