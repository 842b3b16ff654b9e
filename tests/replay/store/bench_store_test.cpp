// Storing a bench (replay/store/bench_store.hpp): NULLs where a level has no speed or
// ratio, increasing ids, the bench's seed.
#include "replay/store/bench_store.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "replay/evaluate/hand_bench_rows.hpp"
#include "replay/store/report_schema.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {

namespace {


class BenchStore : public testing::ScratchDirTest {
 protected:
  BenchStore() : ScratchDirTest("bench_store") {}
};

TEST_F(BenchStore, RowsWithNullsAndIncreasingIds) {
  const auto db = open_report_database((dir_ / "b.sqlite").string(), true);
  BenchOptions options;
  options.seed = 9;
  const auto rows = hand_rows();
  const std::int64_t first = store_bench(*db, options, "test machine", rows);
  const std::int64_t second = store_bench(*db, options, "test machine", rows);
  EXPECT_EQ(second, first + 1);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM bench_rows").getInt(), 16);
  SQLite::Statement q(*db, "SELECT cpu_s IS NULL, sensor_cycles_per_cpu_s IS NULL, gospa_mean_m, targets_per_cycle_ratio IS NULL, "
                           "latency_difference_s FROM bench_rows WHERE bench_id = ? AND recording = ? AND level = ?");
  q.bind(1, first);
  q.bind(2, 1);
  q.bind(3, "noise_floor");
  ASSERT_TRUE(q.executeStep());
  EXPECT_EQ(q.getColumn(0).getInt(), 1);
  EXPECT_EQ(q.getColumn(1).getInt(), 1);
  EXPECT_DOUBLE_EQ(q.getColumn(2).getDouble(), 1.0);
  EXPECT_EQ(q.getColumn(3).getInt(), 0);
  EXPECT_TRUE(q.getColumn(4).isNull());
  q.reset();
  q.bind(1, first);
  q.bind(2, 1);
  q.bind(3, "full");
  ASSERT_TRUE(q.executeStep());
  EXPECT_EQ(q.getColumn(3).getInt(), 1);  // nothing recorded: no ratio
  EXPECT_DOUBLE_EQ(q.getColumn(4).getDouble(), 0.1);
  EXPECT_EQ(db->execAndGet("SELECT seed FROM bench_runs WHERE bench_id = " + std::to_string(first)).getInt(), 9);
}

// The migration is the report store's (open_report_database); a bench is what version 2 added.
TEST_F(BenchStore, VersionOneDatabaseIsMigratedAndKeepsItsRuns) {
  const std::string path = (dir_ / "v1.sqlite").string();
  {
    SQLite::Database db_v1(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);  // as version 1 wrote it
    SQLite::Database* db = &db_v1;
    db->exec(kReportSchemaSql);
    db->exec(fmt::format("PRAGMA application_id = {}", kReportApplicationId));
    db->exec("INSERT INTO runs (recording_name, recording_dir, recording_checksum, recording_source, cycle_time_s, "
             "cycles, seed, level, parameters, rcsim_version, created_utc) "
             "VALUES ('old', '/x', '0000000000000000', '{}', 0.04, 1, 0, 'tracks', '{}', '0.0.1', '2026-01-01T00:00:00Z')");
    db->exec("PRAGMA user_version = 1");
  }
  // (report_store_test.cpp checks the layout a migration gives against a new database.)
  const auto db = open_report_database(path, false);
  EXPECT_EQ(db->execAndGet("PRAGMA user_version").getInt(), kReportSchemaVersion);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  EXPECT_EQ(store_bench(*db, BenchOptions{}, "m", hand_rows()), 1);
}

}  // namespace
}  // namespace rcsim::replay
