#pragma once
// What makes two runs the same run (schemas/report-database.md, "Run identity"): the recording's
// checksum, the seed, the store level, the sensor configurations simulated and the parameters.
// Two runs of the same identity have the same figures (same inputs and seed, byte-identical
// output), so a restarted campaign shard skips a run already stored, and `rcsim merge` reports a
// second copy as a duplicate instead of counting it twice. The rcsim version is not part of it.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "replay/import/importer.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

struct RunIdentity {
  std::string recording_checksum;  // 16 lower-case hex digits, as runs.recording_checksum
  std::int64_t seed = 0;
  std::string store;               // full | summary
  std::string sensor_types;        // run_sensors.type in sensor order, one per line
  std::string parameters;          // runs.parameters, as stored

  // FNV-1a 64 over the fields, 16 hex digits: short enough to print and to index.
  std::string key() const;
  friend bool operator==(const RunIdentity&, const RunIdentity&) = default;
};

// The identity of every run stored in the database, by run id.
std::map<std::int64_t, RunIdentity> stored_run_identities(SQLite::Database& db);

// What tells one run from another on a line or a page (rcsim replay, rcsim report): the sensor
// profiles simulated, the fidelity, the effects, the calibration (its directory and checksum) and
// the seed, read from a stored run.
struct RunLabel {
  std::string sensors;      // "srr24 x2" or "srr24, aimotive_lrr", in sensor order
  std::string level;        // runs.level: tracks | detections | mixed
  std::string fidelity;     // full, no_tracking, ...
  std::string effects;      // "all effects", "no clutter, no occlusion"
  std::string calibration;  // the --calibration directory, "" for none
  std::string calibration_checksum;  // 16 hex digits, "" for none or a run stored before it was kept
  std::int64_t seed = 0;

  // "srr24 x2, fidelity full, all effects, no calibration, seed 1".
  std::string text() const;
};

// The label of every run stored, or of the one run given, by run id.
std::map<std::int64_t, RunLabel> read_run_labels(SQLite::Database& db, std::optional<std::int64_t> only_run = std::nullopt);

// The recording directory of every run stored, as given to the replay (`rcsim campaign status`
// finds a plan's recordings in its shard reports by them, without reading the recordings); none
// in a database without the table runs.
std::vector<std::string> stored_recording_dirs(SQLite::Database& db);

// The identity the run of a recording will have, known before it runs: from its header, the
// checksum of its files (recording_checksum), the header's import (import_header: the sensor
// types and effects simulated) and the options.
RunIdentity planned_run_identity(std::uint64_t recording_checksum, const ImportedScene& header_import,
                                 const ReplayOptions& options, StoreLevel store);

}  // namespace rcsim::replay
