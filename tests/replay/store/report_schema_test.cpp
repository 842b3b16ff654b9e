// The report database's schema (replay/store/report_schema.cpp): the steps of versions 1 to 6
// applied in turn make the tables of a new report; the row tables of version 1 live only until
// the v4 conversion; the tables are STRICT and their CHECKs refuse what the schema does not allow;
// the v6 targets per range bin may be NULL (not known); deleting a run deletes its rows everywhere.
#include "replay/store/report_schema.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "replay/store/report_migration.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"


namespace rcsim::report_schema_test {

using namespace replay;

std::set<std::string> table_names(SQLite::Database& db) {
  std::set<std::string> out;
  SQLite::Statement q(db, "SELECT name FROM sqlite_schema WHERE type = 'table'");
  while (q.executeStep()) out.insert(q.getColumn(0).getString());
  return out;
}

// Every table's columns with their types, NOT NULL, defaults and primary key positions, and
// whether it is STRICT.
std::string layout(SQLite::Database& db) {
  std::string text;
  for (const std::string& table : table_names(db)) {
    text += table + ":";
    SQLite::Statement info(db, "SELECT name, type, \"notnull\", coalesce(dflt_value, ''), pk FROM pragma_table_info(?)");
    info.bind(1, table);
    while (info.executeStep()) {
      text += fmt::format(" {} {} {} {} {},", info.getColumn(0).getString(), info.getColumn(1).getString(),
                          info.getColumn(2).getInt(), info.getColumn(3).getString(), info.getColumn(4).getInt());
    }
    SQLite::Statement strict(db, "SELECT strict FROM pragma_table_list WHERE name = ?");
    strict.bind(1, table);
    text += strict.executeStep() && strict.getColumn(0).getInt() == 1 ? " STRICT\n" : "\n";
  }
  return text;
}

// What SQLite says when `sql` fails, "" if it succeeds.
std::string failure(SQLite::Database& db, const std::string& sql) {
  try {
    db.exec(sql);
  } catch (const SQLite::Exception& e) {
    return e.what();
  }
  return "";
}

TEST(ReportSchema, TheStepsOfEachVersionMakeTheTablesOfANewReport) {
  SQLite::Database fresh(":memory:", SQLite::OPEN_READWRITE);
  create_report_schema(fresh);
  EXPECT_EQ(fresh.execAndGet("PRAGMA user_version").getInt(), kReportSchemaVersion);
  EXPECT_EQ(fresh.execAndGet("PRAGMA application_id").getInt(), kReportApplicationId);
  EXPECT_EQ(table_names(fresh),
            (std::set<std::string>{"runs", "run_sensors", "run_objects", "merge_pairs", "latencies",
                                   "distribution_distances", "summaries", "bench_runs", "bench_rows", "object_figures",
                                   "object_ranges", "cycle_blocks", "target_blocks", "object_state_blocks", "campaign",
                                   "criteria"}));
  SQLite::Database stepped(":memory:", SQLite::OPEN_READWRITE);
  stepped.exec(kReportSchemaSql);
  EXPECT_EQ(table_names(stepped).count("targets"), 1u) << "version 1's rows per target";
  stepped.exec(kBenchSchemaSql);
  stepped.exec(kRealDriveSchemaSql);
  stepped.exec(kBlockSchemaSql);
  stepped.exec(kDropRowTablesSql);
  EXPECT_EQ(table_names(stepped).count("targets"), 0u) << "dropped after the v4 conversion";
  stepped.exec(kCampaignSchemaSql);
  stepped.exec(kObjectRangeTargetsSql);
  EXPECT_EQ(layout(stepped), layout(fresh));
  EXPECT_NE(layout(fresh).find("runs: run_id INTEGER 0  1,"), std::string::npos) << layout(fresh);
  EXPECT_NE(layout(fresh).find(" store TEXT 1 'full' 0,"), std::string::npos) << "a run stored before v4 is full";
  EXPECT_NE(layout(fresh).find(" targets_recorded INTEGER 0  0, targets_simulated INTEGER 0  0, STRICT\n"),
            std::string::npos)
      << "object_ranges' v6 columns last, NULL allowed";
  // A step applied twice is refused: the version says which steps a database lacks.
  EXPECT_NE(failure(stepped, kObjectRangeTargetsSql).find("duplicate column name: targets_recorded"), std::string::npos);
}

class ReportSchemaRows : public testing::ScratchDirTest {
 protected:
  ReportSchemaRows() : ScratchDirTest("report_schema") {}
};

TEST_F(ReportSchemaRows, StrictTablesAndTheirChecksRefuseWhatTheSchemaDoesNotAllow) {
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  const std::string run = "INSERT INTO runs (run_id, recording_name, recording_dir, recording_checksum, recording_source, "
                          "cycle_time_s, cycles, seed, level, parameters, rcsim_version, created_utc{}) VALUES (1, 'r', "
                          "'/r', '0000000000000000', '{{}}', 0.04, {}, 0, 'tracks', '{{}}', '0', '2026-01-01T00:00:00Z'{})";
  EXPECT_NE(failure(*db, fmt::format(fmt::runtime(run), "", "'ten'", "")).find("cannot store TEXT value in INTEGER column runs.cycles"),
            std::string::npos);
  EXPECT_NE(failure(*db, fmt::format(fmt::runtime(run), ", store", "10", ", 'partial'")).find("CHECK constraint failed"),
            std::string::npos);
  ASSERT_EQ(failure(*db, fmt::format(fmt::runtime(run), "", "10", "")), "");
  EXPECT_EQ(db->execAndGet("SELECT store FROM runs").getString(), "full");
  const std::string criterion = "INSERT INTO criteria VALUES (0, 'gospa_mean_m', {}, {}, {}, 1.5, {})";
  EXPECT_EQ(failure(*db, fmt::format(fmt::runtime(criterion), "'recording'", "'value'", "'max'", "'fail'")), "");
  for (const auto& bad : {fmt::format(fmt::runtime(criterion), "'fleet'", "'value'", "'max'", "'fail'"),
                          fmt::format(fmt::runtime(criterion), "'campaign'", "'p90'", "'max'", "'fail'"),
                          fmt::format(fmt::runtime(criterion), "'campaign'", "'mean'", "'at_most'", "'fail'"),
                          fmt::format(fmt::runtime(criterion), "'campaign'", "'mean'", "'max'", "'skip'")}) {
    EXPECT_NE(failure(*db, "DELETE FROM criteria; " + bad).find("CHECK constraint failed"), std::string::npos) << bad;
  }
  // A row of a run that is not there.
  EXPECT_NE(failure(*db, "INSERT INTO object_figures VALUES (7, 0, 0, 1, 1, 1, 1, 1)").find("FOREIGN KEY"),
            std::string::npos);
  // The bins of a run stored before v6: their targets not known.
  EXPECT_EQ(failure(*db, "INSERT INTO object_ranges VALUES (1, 0, 0, 0, 10, 3, 1, 1, NULL, NULL)"), "");
}

TEST_F(ReportSchemaRows, DeletingARunDeletesItsRowsInEveryTable) {
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  for (const std::uint64_t seed : {1u, 2u}) {
    ReplayOptions options;
    options.seed = seed;
    ReportWriter writer(*db, StoreLevel::full);
    replay_recording_dir(testing::kBundledRecordings / "front_approach", options, writer);
  }
  std::set<std::string> run_tables;
  SQLite::Statement q(*db, "SELECT s.name FROM sqlite_schema AS s, pragma_table_info(s.name) AS c WHERE s.type = "
                           "'table' AND c.name = 'run_id'");
  while (q.executeStep()) run_tables.insert(q.getColumn(0).getString());
  const auto rows_of = [&](int run_id) {
    long long n = 0;
    for (const std::string& table : run_tables) {
      n += db->execAndGet(fmt::format("SELECT count(*) FROM {} WHERE run_id = {}", table, run_id)).getInt64();
    }
    return n;
  };
  const long long second = rows_of(2);
  EXPECT_GT(db->execAndGet("SELECT count(*) FROM target_blocks WHERE run_id = 1").getInt(), 0);
  db->exec("DELETE FROM runs WHERE run_id = 1");
  EXPECT_EQ(rows_of(1), 0);
  EXPECT_EQ(rows_of(2), second);
}

}  // namespace rcsim::report_schema_test
