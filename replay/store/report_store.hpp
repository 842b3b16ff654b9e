#pragma once
// The SQLite report database (`rcsim-report` v6, schemas/report-database.md): many replay runs
// in one file. A run is written in one transaction, so a replay that fails or is killed midway
// leaves the database and its earlier runs as they were. Every value is bound to a prepared
// statement; no text is ever pasted into SQL.
#include <SQLiteCpp/SQLiteCpp.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "replay/run/replay_run.hpp"
#include "replay/store/report_database.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

inline constexpr std::int32_t kReportApplicationId = 0x52435352;  // "RCSR"
// 2 added the bench tables, 3 the real-drive figures, 4 the blocks and the store level, 5 the
// campaign and its criteria, 6 the targets per range bin of object_ranges; 1 to 5 are migrated
// on opening.
inline constexpr int kReportSchemaVersion = 6;

// Opens (creating if needed) a report database; refuses a file that is not one, or one of
// another schema version, naming the file. A version 1 to 5 database is migrated to version 6
// in one transaction: tables and columns are added (the runs' new columns NULL, their store
// `full`), and (from 1 to 3) the rows of `cycles`, `targets` and `object_states` are converted
// into blocks.
std::unique_ptr<ReportDatabase> open_report_database(const std::string& path, bool create);

// Closes `db` and removes the report database at `path` with its -wal and -shm, if it holds no
// run, bench or campaign: what a command that created it and was then refused calls, so that it
// leaves no file behind. Call it only for a database this process created.
void discard_if_unused(std::unique_ptr<ReportDatabase>& db, const std::string& path);

// Opens a report database to read it: as open_report_database(path, false) when this process may
// write the file, else read-only (a read-only copy of an older schema is refused, saying why).
std::unique_ptr<ReportDatabase> open_report_database_for_reading(const std::string& path);

// Opens a report database read-only as it stands, waiting up to 5 s for a writer's lock (a
// shard's report while its runs go on); no schema check, no migration.
std::unique_ptr<ReportDatabase> open_report_database_read_only(const std::string& path);

// What an open database holds: nothing yet, a report of an older schema (1 to 5, migrated on
// opening for writing), or one of this version. Refuses, naming the file, anything else (another
// application's database, a newer schema). Read in the caller's transaction.
enum class SchemaState { empty, older, current };
SchemaState read_schema_state(SQLite::Database& db, const std::string& path);

// Writes a new report's schema (its tables, application_id and user_version) into an empty
// database, within the caller's transaction (`rcsim merge` fills it in the same one).
void create_report_schema(SQLite::Database& db);

// The run's `parameters` (schemas/report-database.md): the metric and import parameters with their
// sources, and the effects actually simulated.
nlohmann::ordered_json run_parameters_json(const ReplayOptions& options, const Effects& effects);

// Stores one replay run as it streams in.
class ReportWriter final : public ReplaySink {
 public:
  explicit ReportWriter(SQLite::Database& db, StoreLevel store = StoreLevel::full);
  ~ReportWriter() override;

  void begin_run(const Recording& recording, const ImportedScene& scene, const Scene& simulated_scene,
                 const ReplayOptions& options) override;
  void add_cycle(const CycleComparison& cycle) override;
  void end_run(const ReplaySummary& summary) override;

  std::int64_t run_id() const { return run_id_; }

 private:
  void insert_latencies(const ReplaySummary& summary);
  void insert_distances(const ReplaySummary& summary);
  void insert_object_figures(const ReplaySummary& summary);
  void insert_summary(const ReplaySummary& summary);

  SQLite::Database& db_;
  StoreLevel store_;
  std::optional<SQLite::Transaction> transaction_;
  std::int64_t run_id_ = 0;
  std::unique_ptr<RunRowWriter> rows_;
  std::unique_ptr<SQLite::Statement> insert_merge_pair_;
  std::vector<StoredTarget> recorded_, simulated_;  // reused, cycle by cycle
  std::vector<StoredObjectState> boxes_;
};

}  // namespace rcsim::replay
