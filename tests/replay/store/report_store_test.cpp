// The report database (replay/store/report_store.hpp): a run is one transaction, so a run that
// fails midway leaves the earlier runs as they were; a database of another program is refused.
#include "replay/store/report_store.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {

extern const char* const kReportSchemaSql;  // the tables of version 1
extern const char* const kBenchSchemaSql;   // added in version 2

namespace {

// A report database as version 1 or 2 of rcsim wrote it, with one run stored.
void write_old_database(const std::string& path, int version) {
  SQLite::Database db(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  db.exec(kReportSchemaSql);
  if (version >= 2) db.exec(kBenchSchemaSql);
  db.exec(fmt::format("PRAGMA application_id = {}", kReportApplicationId));
  db.exec(fmt::format("PRAGMA user_version = {}", version));
  db.exec("INSERT INTO runs VALUES (1, 'old', '/x', '0000000000000000', '{}', 0.04, 1, 0, 'tracks', '{}', '0.0.1', "
          "'2026-01-01T00:00:00Z')");
  db.exec("INSERT INTO cycles VALUES (1, 0, 0, 0.0, 3.7, 0, 0, 1, 0, 0, 1.414, 0, 2, 0, 2, 0, 0, 0)");
  db.exec("INSERT INTO targets VALUES (1, 0, 0, 'recorded', 0, NULL, 10, 0, -1, 20, 10, 0, NULL, NULL, 0)");
}

// Each table's columns as (name, type, not null), in order.
std::string table_layout(SQLite::Database& db) {
  std::string text;
  SQLite::Statement tables(db, "SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  while (tables.executeStep()) {
    const std::string table = tables.getColumn(0).getString();
    SQLite::Statement info(db, "PRAGMA table_info(" + table + ")");
    text += fmt::format("{}:", table);
    while (info.executeStep()) {
      text += fmt::format(" {} {}{},", info.getColumn(1).getString(), info.getColumn(2).getString(),
                          info.getColumn(3).getInt() ? " NOT NULL" : "");
    }
    text += '\n';
  }
  return text;
}

class ReportStore : public testing::ScratchDirTest {
 protected:
  ReportStore() : ScratchDirTest("report_store") {}

  Recording write_and_read(const Recording& rec, const std::string& name) { return testing::write_and_read(rec, dir_ / name); }
};

TEST_F(ReportStore, FailedRunLeavesEarlierRunsIntact) {
  const Scene scene = testing::two_cars_scene(1.0);
  const Recording rec = write_and_read(testing::model_recording(scene, 1), "a");
  const auto path = (dir_ / "r.sqlite").string();
  ReplayOptions options;
  options.import.effects = {};
  {
    const auto db = open_report_database(path, true);
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
  }
  // A sink that fails midway, like a replay that meets a full disk.
  struct Failing final : ReplaySink {
    explicit Failing(SQLite::Database& db) : inner(db) {}
    void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions& o) override {
      inner.begin_run(r, i, s, o);
    }
    void add_cycle(const CycleComparison& c) override {
      if (++cycles == 10) throw std::runtime_error("disk full");
      inner.add_cycle(c);
    }
    void end_run(const ReplaySummary& s) override { inner.end_run(s); }
    ReportWriter inner;
    int cycles = 0;
  };
  {
    const auto db = open_report_database(path, true);
    Failing failing(*db);
    EXPECT_THROW(replay_recording(rec, options, failing), std::runtime_error);
  }
  const auto db = open_report_database(path, false);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(DISTINCT run_id) FROM cycles").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM summaries").getInt(), 1);
  EXPECT_EQ(db->execAndGet("PRAGMA integrity_check").getString(), "ok");
}

// Versions 1 and 2 are migrated in place to version 3: the same tables and columns, in the same
// order, as a database made new; the runs kept, their new columns NULL; a new run then stores.
TEST_F(ReportStore, OlderVersionsMigrateToTheLayoutOfANewDatabase) {
  const auto fresh = open_report_database((dir_ / "new.sqlite").string(), true);
  for (const int version : {1, 2}) {
    const std::string path = (dir_ / ("v" + std::to_string(version) + ".sqlite")).string();
    write_old_database(path, version);
    const auto db = open_report_database(path, false);
    EXPECT_EQ(db->execAndGet("PRAGMA user_version").getInt(), 3);
    EXPECT_EQ(table_layout(*db), table_layout(*fresh)) << "from version " << version;
    EXPECT_EQ(db->execAndGet("SELECT count(*) FROM targets WHERE run_id = 1 AND target_class IS NULL").getInt(), 1);
    EXPECT_TRUE(db->execAndGet("SELECT gospa_object_m FROM cycles WHERE run_id = 1").isNull());

    const Recording rec = write_and_read(testing::model_recording(testing::two_cars_scene(1.0), 1),
                                         "rec" + std::to_string(version));
    ReplayOptions options;
    options.import.effects = {};
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
    EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 2);
    EXPECT_EQ(db->execAndGet("SELECT count(*) FROM targets WHERE run_id = 2 AND target_class IS NULL").getInt(), 0);
    EXPECT_GT(db->execAndGet("SELECT count(*) FROM object_figures WHERE run_id = 2").getInt(), 0);
    EXPECT_EQ(db->execAndGet("PRAGMA integrity_check").getString(), "ok");
  }
}

// A database newer than this rcsim is refused, naming the file, and left as it was.
TEST_F(ReportStore, RefusesANewerVersion) {
  const std::string path = (dir_ / "v9.sqlite").string();
  write_old_database(path, 2);
  { SQLite::Database(path, SQLite::OPEN_READWRITE).exec("PRAGMA user_version = 9"); }
  try {
    open_report_database(path, false);
    ADD_FAILURE() << "a version 9 database was opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("v9.sqlite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("version 9"), std::string::npos) << e.what();
  }
  EXPECT_EQ(SQLite::Database(path).execAndGet("PRAGMA user_version").getInt(), 9);
}

TEST_F(ReportStore, RefusesAForeignDatabase) {
  const auto path = (dir_ / "other.sqlite").string();
  {
    SQLite::Database other(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    other.exec("CREATE TABLE t (x INTEGER)");
  }
  EXPECT_THROW(open_report_database(path, true), InputError);
  std::ofstream(dir_ / "junk.sqlite") << "this is not a database, just text that is long enough to matter......";
  EXPECT_THROW(open_report_database((dir_ / "junk.sqlite").string(), true), InputError);
}

}  // namespace
}  // namespace rcsim::replay
