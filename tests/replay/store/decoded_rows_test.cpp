// A run's rows decoded from the report's blocks (replay/store/decoded_rows.cpp): the one list of
// columns with their SQL types, the table names, and the rows of a stored run by span.
#include "replay/store/decoded_rows.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <variant>

#include "app/cli/run_rcsim.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::decoded_rows_test {

using replay::DecodedTable;
using replay::DecodedValue;

TEST(DecodedRows, TableNamesRoundTripAndEveryTableStartsWithRunAndCycle) {
  for (const DecodedTable table : {DecodedTable::cycles, DecodedTable::targets, DecodedTable::objects}) {
    EXPECT_EQ(replay::decoded_table_from_name(replay::decoded_table_name(table)), table);
    const auto& columns = replay::decoded_columns(table);
    ASSERT_GE(columns.size(), 6u);
    EXPECT_EQ(columns[0].name, "run_id");
    EXPECT_EQ(columns[1].name, "cycle");
    std::set<std::string> names;
    for (const auto& c : columns) {
      EXPECT_TRUE(c.sql_type == "INTEGER" || c.sql_type == "REAL" || c.sql_type == "TEXT") << c.name;
      EXPECT_TRUE(names.insert(c.name).second) << c.name << " twice";
      // Units in the names: a real is metres, seconds, radians, decibels or m/s (or a GOSPA part).
      if (c.sql_type == "REAL") {
        const bool unit = c.name.ends_with("_m") || c.name.ends_with("_s") || c.name.ends_with("_rad") ||
                          c.name.ends_with("_db") || c.name.ends_with("_dbsm") || c.name.ends_with("_mps") ||
                          c.name.ends_with("_mp");
        EXPECT_TRUE(unit) << c.name;
      }
    }
  }
  EXPECT_EQ(replay::decoded_table_from_name("object_states"), std::nullopt);
  EXPECT_EQ(replay::decoded_columns(DecodedTable::objects).size(), 6u);
}

class DecodedRowsStored : public rcsim::testing::ScratchDirTest {
 protected:
  DecodedRowsStored() : ScratchDirTest("decoded_rows") {}
};

// Issue 51: the extension held a decoded 256-cycle block as rows of values (some 850 bytes a
// target; 1 GB for the Astyx report's targets); it now holds the store's records and makes the row
// asked for. The chunk's rows are those of for_each_decoded_row, value for value, every table.
TEST_F(DecodedRowsStored, AChunkHoldsRecordsAndMakesTheSameRowsWhenAsked) {
  const std::string db_path = (dir_ / "r.sqlite").string();
  ASSERT_EQ(rcsim::testing::run_rcsim("replay " + std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/two_in_one_cell --db " + db_path).exit_code, 0);
  const auto db = replay::open_report_database_for_reading(db_path);
  for (const DecodedTable table : {DecodedTable::cycles, DecodedTable::targets, DecodedTable::objects}) {
    std::vector<std::vector<DecodedValue>> expected;
    replay::for_each_decoded_row(*db, table, 1, {5, 40}, [&](const std::vector<DecodedValue>& row) { expected.push_back(row); });
    replay::DecodedChunk chunk;
    chunk.read(*db, table, 1, {5, 40});
    ASSERT_EQ(chunk.size(), expected.size()) << replay::decoded_table_name(table);
    EXPECT_GT(chunk.size(), 0u) << replay::decoded_table_name(table);
    for (std::size_t i = 0; i < chunk.size(); ++i) EXPECT_TRUE(chunk.row(i) == expected[i]) << replay::decoded_table_name(table) << " row " << i;
    chunk.read(*db, table, 1, {200, 300});  // replaced: nothing there
    EXPECT_EQ(chunk.size(), 0u);
  }
  EXPECT_LT(sizeof(replay::StoredTarget), replay::decoded_columns(DecodedTable::targets).size() * sizeof(DecodedValue) / 4);
}

TEST_F(DecodedRowsStored, RowsComeInCycleOrderWithinTheSpanTypedAsTheirColumns) {
  const std::string db_path = (dir_ / "r.sqlite").string();
  ASSERT_EQ(rcsim::testing::run_rcsim("replay " + std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/two_in_one_cell --db " + db_path).exit_code, 0);
  const auto db = replay::open_report_database_for_reading(db_path);
  const int last = replay::last_stored_cycle(*db, 1);
  EXPECT_GT(last, 20);
  EXPECT_THROW(replay::last_stored_cycle(*db, 2), std::exception);  // no such run
  const auto& columns = replay::decoded_columns(DecodedTable::targets);
  int rows = 0, previous_cycle = -1;
  replay::for_each_decoded_row(*db, DecodedTable::targets, 1, {10, 19}, [&](const std::vector<DecodedValue>& row) {
    ASSERT_EQ(row.size(), columns.size());
    EXPECT_EQ(std::get<std::int64_t>(row[0]), 1);
    const auto cycle = static_cast<int>(std::get<std::int64_t>(row[1]));
    EXPECT_GE(cycle, 10);
    EXPECT_LE(cycle, 19);
    EXPECT_GE(cycle, previous_cycle);
    previous_cycle = cycle;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (std::holds_alternative<std::monostate>(row[i])) continue;  // NULL fits every type
      const std::string_view type = columns[i].sql_type;
      EXPECT_EQ(std::holds_alternative<std::int64_t>(row[i]), type == "INTEGER") << columns[i].name;
      EXPECT_EQ(std::holds_alternative<double>(row[i]), type == "REAL") << columns[i].name;
      EXPECT_EQ(std::holds_alternative<std::string>(row[i]), type == "TEXT") << columns[i].name;
    }
    const std::string& origin = std::get<std::string>(row[3]);
    EXPECT_TRUE(origin == "recorded" || origin == "simulated") << origin;
    ++rows;
  });
  EXPECT_GT(rows, 10);
  int cycle_rows = 0;
  replay::for_each_decoded_row(*db, DecodedTable::cycles, 1, {}, [&](const std::vector<DecodedValue>&) { ++cycle_rows; });
  EXPECT_EQ(cycle_rows % (last + 1), 0);  // every cycle once per sensor
}

}  // namespace rcsim::decoded_rows_test
