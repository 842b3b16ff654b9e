#include "replay/store/report_store.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <SQLiteCpp/VariadicBind.h>
#include <filesystem>
#include <fmt/chrono.h>
#include <thread>
#include <sqlite3.h>
#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "io/recording.hpp"
#include "replay/import/calibration.hpp"
#include "replay/run/run_kind.hpp"
#include "replay/store/report_merge_files.hpp"
#include "replay/store/report_migration.hpp"
#include "replay/store/report_schema.hpp"

namespace rcsim::replay {
namespace {

nlohmann::ordered_json sensor_profile_checksum(const std::string& sensor_type_override) {
  if (sensor_type_override.empty() || !std::filesystem::is_regular_file(sensor_type_override)) return nullptr;
  return fmt::format("{:016x}", fnv1a64(read_text_file(sensor_type_override)));
}

}  // namespace


namespace {

// A figure that was not compared, in a REAL NOT NULL column where a negative value cannot occur
// (schemas/report-database.md).
constexpr double kNotCompared = -1.0;

std::string sensor_configuration_text(const std::string& type, const std::filesystem::path& base_dir) {
  for (const auto& file : embedded_sensor_configs()) {
    if (std::filesystem::path(std::string(file.name)).stem() == type) return std::string(file.text);
  }
  return read_text_file(base_dir / type);
}

}  // namespace

nlohmann::ordered_json run_parameters_json(const ReplayOptions& options, const Effects& e) {
  return {
      {"fidelity",
       {{"level", std::string(fidelity_name(options.fidelity))}, {"documentation", "docs/fidelity.md"}}},
      {"gospa",
       {{"cutoff_m", options.gospa.cutoff_m}, {"order_p", options.gospa.order_p}, {"alpha", 2},
        {"frame", "sensor Cartesian (x along boresight)"},
        {"source", "A. S. Rahmathullah, A. F. Garcia-Fernandez, L. Svensson, Generalized optimal sub-pattern "
                   "assignment metric, FUSION 2017"}}},
      {"ospa",
       {{"cutoff_m", options.gospa.cutoff_m}, {"order_p", options.gospa.order_p},
        {"source", "D. Schuhmacher, B.-T. Vo, B.-N. Vo, A consistent metric for performance evaluation of "
                   "multi-object filters, IEEE Trans. Signal Processing 56(8), 2008"}}},
      {"assignment",
       {{"cost", "min(d, c)^p"},
        {"source", "shortest augmenting path: R. Jonker, A. Volgenant, Computing 38, 1987"}}},
      {"association", {{"gate_m", options.association_gate_m}, {"rule", "nearest annotated box within the gate"}}},
      {"target_classes",
       {{"object", "within the association gate of an annotated box"},
        {"background", "on no box; |range rate - that of a stationary point at its azimuth| <= stationary_gate_mps, "
                       "with the sensor's velocity from the ego motion"},
        {"other", "the rest"},
        {"stationary_gate_mps", options.stationary_gate_mps},
        {"source", "D. Kellner et al., Instantaneous ego-motion estimation using Doppler radar, ITSC 2013, eq. (2)"}}},
      {"object_figures",
       {{"in_view", "the box's nearest point within the sensor's azimuth half-angle and [min, max] range; "
                    "occlusion not considered"},
        {"detected", "at least one target of the object class belonging to the object"},
        {"range_bin_m", options.object_range_bin_m}}},
      {"merge_artefacts",
       {{"cells", "the sensor's merging rule over the scene's noise-free echoes: echoes within half a cell of the "
                  "strongest share its cell (eqs. (4)-(5)); a cell with echoes of two objects makes them a pair"},
        {"artefact", "a target within one cell of the cell's range and range rate, within the azimuth span of "
                     "the pair's echoes in it, farther than margin_m from both boxes; it then belongs to no object"},
        {"margin_m", options.merge_margin_m},
        {"match_distance_m", options.merge_match_distance_m},
        {"matched", "recorded and simulated artefacts of the same pair and cycle, optimal assignment, closer than "
                    "match_distance_m"},
        {"source", "paper III-C, Fig. 10"}}},
      {"latency",
       {{"episode", "starts when the scene geometry makes the object detectable (in view, not occluded, a "
                    "reflector's noise-free echo at or above the threshold, eqs. (1)-(3), (6)); ends after 10 "
                    "cycles in which it is not"},
        {"confirmed", "targets of the object (class object) in at least 3 of the last 4 cycles of the episode"},
        {"latency", "confirmation time minus the episode's start, each side alike; never confirmed: censored"}}},
      {"distribution_distances",
       {{"area_metric", "S. Ferson, W. L. Oberkampf, L. Ginzburg, CMAME 197, 2008 (= Wasserstein-1)"},
        {"kolmogorov_smirnov", "two-sample statistic sup |F_rec - F_sim|"}}},
      {"import",
       {{"smoothing", "local quadratic regression, tricube weights (W. S. Cleveland, JASA 74, 1979)"},
        {"smoothing_half_window_s", options.import.smoothing_half_window_s},
        {"max_gap_s", options.import.max_gap_s},
        {"calibration", options.import.calibration_dir.empty() ? nlohmann::ordered_json()
                                                                 : nlohmann::ordered_json(options.import.calibration_dir)},
        // What the calibration holds, so that a calibration written again into the same
        // directory makes another run (the run identity).
        {"calibration_checksum", options.import.calibration_dir.empty()
                                     ? nlohmann::ordered_json()
                                     : nlohmann::ordered_json(load_calibration(options.import.calibration_dir)->checksum)},
        {"effects", {{"clutter", e.clutter}, {"multibounce", e.multibounce}, {"occlusion", e.occlusion}}},
        // A profile file given for every sensor (--sensor): what it holds, so that a profile
        // derived again into the same file makes another run.
        {"sensor_profile_checksum", sensor_profile_checksum(options.import.sensor_type_override)}}}};
}

namespace {

std::string utc_now() {
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
}

void bind_optional(SQLite::Statement& s, int index, double value) {
  if (value < 0.0) {
    s.bind(index);  // NULL
  } else {
    s.bind(index, value);
  }
}

// The targets of one class in a list.
int count_class(const std::vector<ComparedTarget>& list, metrics::TargetClass c) {
  return static_cast<int>(std::count_if(list.begin(), list.end(), [c](const auto& t) { return t.target_class == c; }));
}

// The steps from `version` to the current one, as a new database takes them from version 1.
void upgrade_from(SQLite::Database& db, int version) {
  if (version < 2) db.exec(kBenchSchemaSql);
  if (version < 3) db.exec(kRealDriveSchemaSql);
  if (version < 4) {
    db.exec(kBlockSchemaSql);
    convert_row_tables_to_blocks(db);
    db.exec(kDropRowTablesSql);
  }
  if (version < 5) db.exec(kCampaignSchemaSql);
  if (version < 6) db.exec(kObjectRangeTargetsSql);
}

// A compared target as the store keeps it.
void to_stored(const std::vector<ComparedTarget>& list, std::vector<StoredTarget>& out) {
  out.resize(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ComparedTarget& t = list[i];
    StoredTarget& s = out[i];
    s.idx = static_cast<int>(i);
    s.track_id = std::max(-1, t.track_id);
    s.range_m = t.range_m;
    s.azimuth_rad = t.azimuth_rad;
    s.range_rate_mps = t.range_rate_mps;
    s.amplitude_db = t.amplitude_db;
    s.object = std::max(-1, t.object);
    s.match_idx = std::max(-1, t.match);
    s.merge_artefact = t.merge_pair >= 0;
    s.target_class = t.target_class;
    s.p_OT_O = t.object >= 0 ? std::optional<Vec2>(t.p_OT_O) : std::nullopt;
    s.rcs_dbsm = t.rcs_dbsm;
    s.snr_db = t.snr_db;
    s.elevation_rad = t.elevation_rad;
  }
}

}  // namespace

void create_report_schema(SQLite::Database& db) {
  db.exec(kReportSchemaSql);
  upgrade_from(db, 1);
  db.exec(fmt::format("PRAGMA application_id = {}", kReportApplicationId));
  db.exec(fmt::format("PRAGMA user_version = {}", kReportSchemaVersion));
}

// The identity and version of an open database, read in the caller's transaction (one snapshot).
SchemaState read_schema_state(SQLite::Database& db, const std::string& path) {
  const int application_id = db.execAndGet("PRAGMA application_id").getInt();
  const int user_version = db.execAndGet("PRAGMA user_version").getInt();
  const int tables = db.execAndGet("SELECT count(*) FROM sqlite_schema").getInt();
  if (application_id == 0 && user_version == 0 && tables == 0) return SchemaState::empty;
  if (application_id != kReportApplicationId) {
    throw InputError(path, "", fmt::format("not an rcsim report database (application_id {:#x}, expected {:#x})",
                                           static_cast<std::uint32_t>(application_id), kReportApplicationId));
  }
  if (user_version >= 1 && user_version < kReportSchemaVersion) return SchemaState::older;
  if (user_version != kReportSchemaVersion) {
    throw InputError(path, "", fmt::format("report schema version {}, expected {}: written by a newer rcsim",
                                           user_version, kReportSchemaVersion));
  }
  // Tagged as a report of this version, yet without a report's tables (issue 51: a bare "no such
  // table", exit 1): refused here, naming the first missing.
  for (const char* table : {"runs", "summaries", "cycle_blocks", "target_blocks", "object_state_blocks"}) {
    SQLite::Statement exists(db, "SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = ?");
    exists.bind(1, table);
    exists.executeStep();
    if (exists.getColumn(0).getInt() == 0) {
      throw InputError(path, "", fmt::format("tagged as an rcsim report (application_id {:#x}, schema version {}) but "
                                             "has no table {}: not an rcsim report database, or a damaged one",
                                             kReportApplicationId, kReportSchemaVersion, table));
    }
  }
  return SchemaState::current;
}

namespace {

// How long an opener waits for another process's write (a run's commit, a new schema): a run's
// transaction holds the lock for its whole replay (docs/hardening.md).
constexpr int kBusyTimeout_ms = 60000;

// Refuses, naming the file, what is there and is not a regular file after symbolic links: SQLite
// would write a -journal beside a device and fail with "disk I/O error".
void check_database_file(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InputError(path, "", "not a regular file (a directory, device, pipe or socket): a report database is one");
  }
}

// PRAGMA journal_mode = WAL, retried every 10 ms while another connection holds the file, for up
// to kBusyTimeout_ms (tests/end_to_end/damaged_report_test.cpp: eight replays into one new database).
void set_wal_waiting(SQLite::Database& db) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kBusyTimeout_ms);
  for (;;) {
    try {
      if (db.execAndGet("PRAGMA journal_mode").getString() != "wal") db.exec("PRAGMA journal_mode = WAL");
      return;
    } catch (const SQLite::Exception& e) {
      if ((e.getErrorCode() & 0xff) != SQLITE_BUSY || std::chrono::steady_clock::now() > deadline) throw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// The same in a read transaction of its own: one snapshot of the three values.
SchemaState read_schema_state_once(SQLite::Database& db, const std::string& path) {
  SQLite::Transaction snapshot(db, SQLite::TransactionBehavior::DEFERRED);
  const SchemaState state = read_schema_state(db, path);
  snapshot.commit();
  return state;
}

}  // namespace

void ReportDatabase::finish_journal() noexcept {
  try {
    if (sqlite3_db_readonly(getHandle(), "main") != 0) return;
    setBusyTimeout(0);  // another connection open: it switches when it closes; nobody waits here
    exec("PRAGMA journal_mode = DELETE");
  } catch (...) {
    // SQLITE_BUSY (another reader or writer) or a failing file system: the file stays in WAL mode,
    // as consistent as before.
  }
}

std::unique_ptr<ReportDatabase> open_report_database(const std::string& path, bool create) {
  const bool existed = std::filesystem::exists(path);
  if (!create && !existed) throw InputError(path, "", "no such report database");
  if (const auto parent = std::filesystem::path(path).parent_path(); !existed && !parent.empty() &&
                                                                    !std::filesystem::is_directory(parent)) {
    throw InputError(path, "", "cannot create the report database: no directory " + parent.string());
  }
  check_database_file(path);
  std::unique_ptr<ReportDatabase> db;
  try {
    db = std::make_unique<ReportDatabase>(path, create ? SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE
                                                         : SQLite::OPEN_READWRITE);
    db->setBusyTimeout(kBusyTimeout_ms);
    if (const SchemaState state = read_schema_state_once(*db, path); state != SchemaState::current) {
      if (state == SchemaState::empty && !create) {
        throw InputError(path, "", "the database is empty: no replay has been stored in it");
      }
      // Creating or migrating the schema is one write transaction that reads the state again under
      // the write lock: concurrent openers of a new database wait for the first, then find its schema.
      SQLite::Transaction transaction(*db, SQLite::TransactionBehavior::IMMEDIATE);
      const int user_version = db->execAndGet("PRAGMA user_version").getInt();
      if (read_schema_state(*db, path) == SchemaState::empty) {
        create_report_schema(*db);
      } else if (user_version < kReportSchemaVersion) {
        // v1 -> v2: the bench tables; v2 -> v3: the real-drive columns and tables; v3 -> v4: the
        // blocks; v4 -> v5: the campaign and its criteria; v5 -> v6: object_ranges' targets.
        try {
          upgrade_from(*db, user_version);
        } catch (const std::runtime_error& e) {
          if (dynamic_cast<const SQLite::Exception*>(&e) != nullptr) throw;
          throw InputError(path, "", fmt::format("cannot migrate report schema version {} to {}: {}", user_version,
                                                 kReportSchemaVersion, e.what()));
        }
        db->exec(fmt::format("PRAGMA user_version = {}", kReportSchemaVersion));
      }
      transaction.commit();
    }
    // Persistent, outside any transaction: readers never block the writer.
    // Switching a new file to WAL needs it alone, and SQLite can answer SQLITE_BUSY at once, without
    // its busy handler, while another opener of the same new file holds it: wait as the handler would.
    set_wal_waiting(*db);
    db->exec("PRAGMA foreign_keys = ON");
    // In WAL mode NORMAL keeps the database consistent on a crash or power loss; only the last
    // committed run may be lost on power loss, never an earlier one.
    db->exec("PRAGMA synchronous = NORMAL");
  } catch (const SQLite::Exception& e) {
    // A database this call created and could not give a schema (a full disk) is left as nothing.
    db.reset();
    std::error_code ignored;
    if (create && !existed && std::filesystem::file_size(path, ignored) == 0) {
      for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::filesystem::remove(path + suffix, ignored);
    }
    throw InputError(path, "", std::string("cannot use as a report database: ") + e.what());
  }
  return db;
}

void discard_if_unused(std::unique_ptr<ReportDatabase>& db, const std::string& path) {
  if (db == nullptr) return;
  try {
    const auto rows = [&](const char* table) {
      return db->tableExists(table) ? db->execAndGet(fmt::format("SELECT count(*) FROM {}", table)).getInt64() : 0;
    };
    if (rows("runs") + rows("bench_runs") + rows("campaign") > 0) return;
  } catch (const SQLite::Exception&) {
    return;  // not readable now: left as it is
  }
  db.reset();
  std::error_code ignored;
  for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::filesystem::remove(path + suffix, ignored);
}

std::unique_ptr<ReportDatabase> open_report_database_read_only(const std::string& path) {
  auto db = std::make_unique<ReportDatabase>(path, SQLite::OPEN_READONLY);
  db->setBusyTimeout(5000);
  // Another application's database (or an empty one) is named as such, not met with an SQL error
  // on a table it lacks (docs/sql.md; issue 51). An older schema is read as it is.
  if (read_schema_state_once(*db, path) == SchemaState::empty) {
    throw InputError(path, "", "the database is empty: not an rcsim report database");
  }
  return db;
}

std::unique_ptr<ReportDatabase> open_report_database_for_reading(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "", "no such report database");
  check_database_file(path);
  // A file this process may write and that holds an older schema is migrated, as a writer would;
  // one of the current schema is read as it is: a read never switches it to WAL (issue 51).
  if (::access(path.c_str(), W_OK) == 0) {
    std::unique_ptr<ReportDatabase> db;
    try {
      db = std::make_unique<ReportDatabase>(path, SQLite::OPEN_READWRITE);
      db->setBusyTimeout(kBusyTimeout_ms);
      if (read_schema_state_once(*db, path) == SchemaState::current) return db;
    } catch (const SQLite::Exception& e) {
      throw InputError(path, "", std::string("cannot use as a report database: ") + e.what());
    }
    db.reset();
    return open_report_database(path, false);
  }
  std::unique_ptr<ReportDatabase> db;
  try {
    // Without write access SQLite cannot make the WAL's -shm beside it: read the file as immutable.
    db = std::make_unique<ReportDatabase>(merge_files::read_only_uri(path), SQLite::OPEN_READONLY | SQLite::OPEN_URI);
    db->setBusyTimeout(kBusyTimeout_ms);
    const SchemaState state = read_schema_state_once(*db, path);
    if (state == SchemaState::empty) throw InputError(path, "", "the database is empty: no replay has been stored in it");
    if (state == SchemaState::older) {
      throw InputError(path, "", fmt::format("an older report schema, which needs migrating to version {}, and the "
                                             "file is read-only: make it writable, or copy it somewhere writable",
                                             kReportSchemaVersion));
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(path, "", std::string("cannot read as a report database: ") + e.what());
  }
  return db;
}

ReportWriter::ReportWriter(SQLite::Database& db, StoreLevel store) : db_(db), store_(store) {}

ReportWriter::~ReportWriter() = default;  // an uncommitted transaction rolls back

void ReportWriter::begin_run(const Recording& rec, const ImportedScene& imported, const Scene& scene,
                             const ReplayOptions& options) {
  transaction_.emplace(db_);
  SQLite::Statement run(db_,
                        "INSERT INTO runs (recording_name, recording_dir, recording_checksum, recording_source, "
                        "cycle_time_s, cycles, seed, level, parameters, rcsim_version, created_utc, store) "
                        "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  run.bind(1, rec.name);
  run.bind(2, std::filesystem::absolute(rec.dir).lexically_normal().string());
  run.bind(3, fmt::format("{:016x}", rec.checksum));
  run.bind(4, rec.source.dump());
  run.bind(5, rec.cycle_time_s);
  run.bind(6, rec.cycle_count());
  run.bind(7, static_cast<std::int64_t>(options.seed));
  run.bind(8, run_level_of(rec));  // what the recording reports: tracks, detections or mixed
  run.bind(9, run_parameters_json(options, imported.effects).dump());  // the effects actually simulated
  run.bind(10, RCSIM_VERSION);
  run.bind(11, utc_now());
  run.bind(12, std::string(store_level_name(store_)));
  run.exec();
  run_id_ = db_.getLastInsertRowid();

  SQLite::Statement sensor(db_, "INSERT INTO run_sensors VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < imported.sensors.size(); ++i) {
    const RecordingSensor& s = imported.sensors[i];  // with the type actually simulated
    sensor.bind(1, run_id_);
    sensor.bind(2, static_cast<int>(i));
    sensor.bind(3, s.id);
    sensor.bind(4, s.type);
    sensor.bind(5, s.x_m);
    sensor.bind(6, s.y_m);
    sensor.bind(7, s.yaw_rad);
    sensor.bind(8, scene.sensors[i].config.fov.azimuth_half_rad);
    sensor.bind(9, scene.sensors[i].config.fov.max_range_m);
    sensor.bind(10, sensor_configuration_text(s.type, rec.dir));
    sensor.exec();
    sensor.reset();
  }
  SQLite::Statement object(db_, "INSERT INTO run_objects VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < imported.objects.size(); ++i) {
    const ImportedObject& o = imported.objects[i];
    object.bind(1, run_id_);
    object.bind(2, static_cast<int>(i));
    object.bind(3, o.id);
    object.bind(4, o.model);
    object.bind(5, o.length_m);
    object.bind(6, o.width_m);
    object.bind(7, static_cast<std::int64_t>(scene.objects[i].model.reflector_count()));
    object.exec();
    object.reset();
  }
  rows_ = std::make_unique<RunRowWriter>(db_, run_id_, store_, options.gospa.cutoff_m, options.gospa.order_p);
  insert_merge_pair_ = std::make_unique<SQLite::Statement>(db_, "INSERT INTO merge_pairs VALUES (?, ?, ?, ?, ?)");
}

void ReportWriter::add_cycle(const CycleComparison& c) {
  StoredCycle row;
  row.cycle = c.cycle;
  row.sensor = c.sensor;
  row.t_s = c.t_s;
  row.X_WS = c.X_WS;
  row.n_recorded = static_cast<int>(c.recorded.size());
  row.n_simulated = static_cast<int>(c.simulated.size());
  row.n_assigned = c.gospa.assigned;
  row.gospa_m = c.gospa.gospa_m;
  row.gospa_localisation_mp = c.gospa.localisation_mp;
  row.gospa_missed_mp = c.gospa.missed_mp;
  row.gospa_false_mp = c.gospa.false_mp;
  row.ospa_m = c.gospa.ospa_m;
  for (const auto& t : c.recorded) row.merge_recorded += t.merge_pair >= 0;
  for (const auto& t : c.simulated) row.merge_simulated += t.merge_pair >= 0;
  row.merge_matched = c.merge_matched;
  row.classes = StoredCycle::Classes{count_class(c.recorded, metrics::TargetClass::object),
                                     count_class(c.simulated, metrics::TargetClass::object),
                                     count_class(c.recorded, metrics::TargetClass::stationary_background),
                                     count_class(c.simulated, metrics::TargetClass::stationary_background),
                                     c.gospa_object.gospa_m, c.gospa_object.ospa_m};
  if (store_ == StoreLevel::full) {
    to_stored(c.recorded, recorded_);
    to_stored(c.simulated, simulated_);
  }
  rows_->add_cycle(row, recorded_, simulated_);
  for (const auto& [a, b] : c.merge_pairs) {
    SQLite::Statement& m = *insert_merge_pair_;
    m.bind(1, run_id_);
    m.bind(2, c.cycle);
    m.bind(3, c.sensor);
    m.bind(4, a);
    m.bind(5, b);
    m.exec();
    m.reset();
  }
  if (c.sensor == 0 && store_ == StoreLevel::full) {  // the boxes are the same for every sensor of a cycle
    boxes_.clear();
    for (const ObjectInCycle& object : c.objects) {
      boxes_.push_back({c.cycle, object.object, Pose2{object.x_m, object.y_m, object.yaw_rad}});
    }
    rows_->add_object_states(c.cycle, boxes_);
  }
}

void ReportWriter::insert_object_figures(const ReplaySummary& r) {
  SQLite::Statement object(db_, "INSERT INTO object_figures VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  for (const ObjectFigureRow& row : r.objects) {
    SQLite::bind(object, run_id_, row.sensor, row.object, row.cycles_in_view, row.cycles_detected_recorded,
                 row.cycles_detected_simulated, static_cast<std::int64_t>(row.targets_recorded),
                 static_cast<std::int64_t>(row.targets_simulated));
    object.exec();
    object.reset();
  }
  SQLite::Statement range(db_, "INSERT INTO object_ranges VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const ObjectRangeRow& row : r.object_ranges) {
    SQLite::bind(range, run_id_, row.sensor, row.object, row.range_from_m, row.range_to_m, row.cycles_in_view,
                 row.cycles_detected_recorded, row.cycles_detected_simulated,
                 static_cast<std::int64_t>(row.targets_recorded), static_cast<std::int64_t>(row.targets_simulated));
    range.exec();
    range.reset();
  }
}

void ReportWriter::insert_latencies(const ReplaySummary& r) {
  SQLite::Statement latency(db_, "INSERT INTO latencies VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const LatencyRow& row : r.latencies) {
    latency.bind(1, run_id_);
    latency.bind(2, row.sensor);
    latency.bind(3, row.object);
    latency.bind(4, row.episode);
    latency.bind(5, row.detectable_from_s);
    bind_optional(latency, 6, row.first_recorded_s);
    bind_optional(latency, 7, row.first_simulated_s);
    bind_optional(latency, 8, row.first_recorded_s < 0.0 ? -1.0 : row.first_recorded_s - row.detectable_from_s);
    bind_optional(latency, 9, row.first_simulated_s < 0.0 ? -1.0 : row.first_simulated_s - row.detectable_from_s);
    latency.exec();
    latency.reset();
  }
}

void ReportWriter::insert_distances(const ReplaySummary& r) {
  SQLite::Statement distance(db_, "INSERT INTO distribution_distances VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (const QuantityDistance& d : r.distances) {
    distance.bind(1, run_id_);
    distance.bind(2, d.quantity);
    distance.bind(3, d.unit);
    if (std::isnan(d.distance.wasserstein1)) {
      distance.bind(4);
      distance.bind(5);
    } else {
      distance.bind(4, d.distance.wasserstein1);
      distance.bind(5, d.distance.kolmogorov_smirnov);
    }
    distance.bind(6, d.distance.n_recorded);
    distance.bind(7, d.distance.n_simulated);
    distance.exec();
    distance.reset();
  }
}

void ReportWriter::insert_summary(const ReplaySummary& r) {
  SQLite::Statement summary(db_, "INSERT INTO summaries VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
                                 "?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  int i = 1;
  summary.bind(i++, run_id_);
  summary.bind(i++, r.cycles);
  summary.bind(i++, static_cast<std::int64_t>(r.targets_recorded));
  summary.bind(i++, static_cast<std::int64_t>(r.targets_simulated));
  summary.bind(i++, static_cast<std::int64_t>(r.targets_matched));
  summary.bind(i++, r.gospa_mean_m);
  summary.bind(i++, r.ospa_mean_m);
  summary.bind(i++, r.gospa_localisation_mean_mp);
  summary.bind(i++, r.gospa_missed_mean_mp);
  summary.bind(i++, r.gospa_false_mean_mp);
  summary.bind(i++, static_cast<std::int64_t>(r.merge_artefacts_recorded));
  summary.bind(i++, static_cast<std::int64_t>(r.merge_artefacts_simulated));
  summary.bind(i++, static_cast<std::int64_t>(r.merge_artefacts_matched));
  bind_optional(summary, i++, r.latency_recorded_s);
  bind_optional(summary, i++, r.latency_simulated_s);
  summary.bind(i++, r.latency_pairs);
  summary.bind(i++, r.residual_range_rms_m);
  summary.bind(i++, r.residual_azimuth_rms_rad);
  // -1: not compared (a recording whose ego motion is unknown); the column is NOT NULL since v1.
  summary.bind(i++, std::isnan(r.residual_range_rate_rms_mps) ? kNotCompared : r.residual_range_rate_rms_mps);
  summary.bind(i++, r.residual_amplitude_mean_db);
  summary.bind(i++, r.simulate_cpu_s);
  summary.bind(i++, r.total_wall_s);
  summary.bind(i++, r.gospa_object_mean_m);
  summary.bind(i++, r.ospa_object_mean_m);
  for (const long long* counts : {r.classes.object, r.classes.background, r.classes.other}) {
    summary.bind(i++, static_cast<std::int64_t>(counts[0]));
    summary.bind(i++, static_cast<std::int64_t>(counts[1]));
  }
  if (r.latency_pairs > 0) {
    summary.bind(i++, r.latency_difference_mean_s);
  } else {
    summary.bind(i++);
  }
  summary.bind(i++, r.latency_episodes);
  summary.bind(i++, r.latency_unconfirmed_recorded);
  summary.bind(i++, r.latency_unconfirmed_simulated);
  summary.exec();
}

// The run's closing tables, then COMMIT: the whole run or nothing.
void ReportWriter::end_run(const ReplaySummary& r) {
  rows_->finish();
  insert_latencies(r);
  insert_distances(r);
  insert_object_figures(r);
  insert_summary(r);
  rows_.reset();
  insert_merge_pair_.reset();
  transaction_->commit();
  transaction_.reset();
}

}  // namespace rcsim::replay
