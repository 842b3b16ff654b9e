// The SQLite extension (replay/store/extension/sqlite_extension.cpp, build/lib/rcsim.so): a report's
// compact blocks read as the tables cycles, targets and objects, row for row what `rcsim export`
// writes; run_id and cycle constraints; sqlite3 and Python load it as a user would; refusals.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::sqlite_extension_test {

namespace fs = std::filesystem;
using rcsim::testing::run_rcsim;
using rcsim::testing::run_shell_command;

// build/lib/rcsim.so beside build/bin/rcsim; absent where the tree was built without it (the
// sanitizer trees: RCSIM_SQLITE_EXTENSION=OFF).
fs::path extension_path() { return fs::path(RCSIM_BINARY).parent_path().parent_path() / "lib" / "rcsim.so"; }

const std::string kRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/two_in_one_cell";

class SqliteExtension : public rcsim::testing::ScratchDirTest {
 protected:
  SqliteExtension() : ScratchDirTest("sqlite_extension") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    if (!fs::exists(extension_path())) GTEST_SKIP() << "no " << extension_path() << " in this build tree (RCSIM_SQLITE_EXTENSION=OFF)";
    db_ = (dir_ / "r.sqlite").string();
    ASSERT_EQ(run_rcsim("replay " + kRecording + " --db " + db_ + " --seed 1").exit_code, 0);
    ASSERT_EQ(run_rcsim("replay " + kRecording + " --db " + db_ + " --seed 2 --store summary").exit_code, 0);
  }
  // A connection to the report with the extension loaded, as sqlite3's `.load` does.
  SQLite::Database connect() const {
    SQLite::Database db(db_, SQLite::OPEN_READONLY);
    db.loadExtension(extension_path().c_str(), nullptr);
    return db;
  }
  std::string db_;
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// One row as `rcsim export --format csv` writes it: integers as they are, reals in the shortest
// form that reads back (compared here by value), texts plain, NULL empty.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (const char c : line) {
    if (c == ',') {
      fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  fields.push_back(field);
  return fields;
}

void expect_same_value(const SQLite::Column& column, const std::string& exported, const std::string& where) {
  if (column.isNull()) {
    EXPECT_EQ(exported, "") << where;
  } else if (column.isInteger()) {
    EXPECT_EQ(std::to_string(column.getInt64()), exported) << where;
  } else if (column.isFloat()) {
    EXPECT_EQ(column.getDouble(), std::stod(exported)) << where;  // bit for bit
  } else {
    EXPECT_EQ(column.getString(), exported) << where;
  }
}

TEST_F(SqliteExtension, EveryTableHoldsRowForRowWhatExportWrites) {
  SQLite::Database db = connect();
  for (const std::string table : {"cycles", "targets", "objects"}) {
    const auto exported = run_rcsim("export " + db_ + " --run 1 --table " + table, false);
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    const std::vector<std::string> lines = lines_of(exported.output);
    ASSERT_GT(lines.size(), 10u) << table;
    SQLite::Statement rows(db, "SELECT * FROM " + table + " WHERE run_id = 1");
    ASSERT_EQ(rows.getColumnCount(), static_cast<int>(split_csv(lines[0]).size())) << table;
    for (int i = 0; i < rows.getColumnCount(); ++i) EXPECT_EQ(rows.getColumnName(i), split_csv(lines[0])[static_cast<std::size_t>(i)]);
    std::size_t row = 1;
    for (; rows.executeStep(); ++row) {
      ASSERT_LT(row, lines.size()) << table << ": more rows than exported";
      const std::vector<std::string> fields = split_csv(lines[row]);
      for (int i = 0; i < rows.getColumnCount(); ++i) {
        expect_same_value(rows.getColumn(i), fields[static_cast<std::size_t>(i)], table + " row " + std::to_string(row));
      }
    }
    EXPECT_EQ(row, lines.size()) << table << ": fewer rows than exported";
  }
}

TEST_F(SqliteExtension, RunAndCycleConstraintsSelectTheirRowsAndASummaryRunHasOnlyCycles) {
  SQLite::Database db = connect();
  const auto count = [&](const std::string& sql) { return db.execAndGet(sql).getInt64(); };
  const long long all_cycles = count("SELECT count(*) FROM cycles");
  const long long run1 = count("SELECT count(*) FROM cycles WHERE run_id = 1");
  EXPECT_EQ(count("SELECT count(*) FROM cycles WHERE run_id = 2"), run1);  // the same recording
  EXPECT_EQ(all_cycles, 2 * run1);
  EXPECT_EQ(count("SELECT count(*) FROM cycles WHERE run_id = 3"), 0);
  // The summary run keeps its cycles' figures, but no targets and no boxes.
  EXPECT_GT(count("SELECT count(*) FROM targets WHERE run_id = 1"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 2"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM objects WHERE run_id = 2"), 0);
  // Bounds on cycle read the blocks they need and give what a filter over all rows gives.
  for (const std::string where : {"cycle = 7", "cycle > 10 AND cycle <= 20", "cycle >= 30", "cycle < 3", "cycle BETWEEN 5 AND 5",
                                  "cycle > 100000", "cycle < -1"}) {
    EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 1 AND " + where),
              count("SELECT count(*) FROM (SELECT * FROM targets WHERE run_id = 1) WHERE " + where))
        << where;
  }
  EXPECT_GT(count("SELECT count(*) FROM targets WHERE run_id = 1 AND cycle = 7"), 0);
  // A join with a stored table: the sensors' types per cycle row.
  EXPECT_EQ(count("SELECT count(*) FROM cycles c JOIN runs r ON r.run_id = c.run_id WHERE r.seed = 1"), run1);
  // GOSPA's mean over the cycles, as the run's summary stores it.
  const double mean_m = db.execAndGet("SELECT avg(gospa_m) FROM cycles WHERE run_id = 1").getDouble();
  const double stored_m = db.execAndGet("SELECT gospa_mean FROM summaries WHERE run_id = 1").getDouble();
  EXPECT_NEAR(mean_m, stored_m, 1e-9 * std::max(1.0, stored_m));
}

// Issue 51, HIGH 1: a run that claims 2^31 - 1 cycles with its one block at the end made a cycle
// constraint walk every empty span (and wrap past 2^31): sqlite3 hung and could not be stopped.
// The cursor now walks the stored blocks only.
TEST_F(SqliteExtension, ARunClaimingTwoBillionCyclesIsReadAtOnce) {
  {
    SQLite::Database write(db_, SQLite::OPEN_READWRITE);
    write.exec("UPDATE runs SET cycles = 2147483647 WHERE run_id = 1");
    for (const char* table : {"cycle_blocks", "target_blocks", "object_state_blocks"}) {
      write.exec(std::string("DELETE FROM ") + table + " WHERE run_id = 1 AND first_cycle > 0");
      write.exec(std::string("UPDATE ") + table + " SET first_cycle = 2147483647 - cycles WHERE run_id = 1");
    }
  }
  SQLite::Database db = connect();
  const int block_cycles = db.execAndGet("SELECT cycles FROM cycle_blocks WHERE run_id = 1 LIMIT 1").getInt();
  const int sensors = db.execAndGet("SELECT count(DISTINCT sensor) FROM cycle_blocks WHERE run_id = 1").getInt();
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM cycles WHERE run_id = 1 AND cycle >= 2147483500").getInt(), block_cycles * sensors);
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM cycles WHERE run_id = 1").getInt(), block_cycles * sensors);
  EXPECT_EQ(db.execAndGet("SELECT max(cycle) FROM cycles WHERE run_id = 1 AND cycle <= 2147483647").getInt(), 2147483646);
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM cycles WHERE run_id = 1 AND cycle < 2147483000").getInt(), 0);
}

// Issue 51: each xFilter decoded every cycle block of the run (to find its last cycle), so a join
// (an xFilter per outer row) was quadratic in the run's length. A second block, damaged, is
// added after the run's one: a query for a cycle of the first reads the first only.
TEST_F(SqliteExtension, AConstraintOnOneCycleDecodesOnlyItsBlock) {
  {
    SQLite::Database write(db_, SQLite::OPEN_READWRITE);
    write.exec("UPDATE runs SET cycles = cycles + 256 WHERE run_id = 1");
    write.exec("CREATE TEMP TABLE copy AS SELECT * FROM cycle_blocks WHERE run_id = 1");
    write.exec("UPDATE copy SET first_cycle = first_cycle + 256, gospa_m = x'ff'");
    write.exec("INSERT INTO cycle_blocks SELECT * FROM copy");
  }
  SQLite::Database db = connect();
  const int sensors = db.execAndGet("SELECT count(DISTINCT sensor) FROM cycle_blocks WHERE run_id = 1").getInt();
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM cycles WHERE run_id = 1 AND cycle = 7").getInt(), sensors);
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM cycles a JOIN cycles b ON b.run_id = a.run_id AND b.cycle = a.cycle "
                          "AND b.sensor = a.sensor WHERE a.run_id = 1 AND a.cycle < 100").getInt(),
            100 * sensors);
  EXPECT_THROW(db.execAndGet("SELECT count(*) FROM cycles WHERE run_id = 1 AND cycle >= 256").getInt(), SQLite::Exception);
}

TEST_F(SqliteExtension, Sqlite3AndPythonLoadItAsAUserWould) {
  const std::string ext = extension_path().string();
  if (std::system("command -v sqlite3 > /dev/null 2>&1") != 0) {
    std::cout << "sqlite3 is not installed: the shell's .load is not tried\n";
  } else {
    const auto shell = run_shell_command("sqlite3 " + db_ + " '.load " + ext + "' 'SELECT cycle, gospa_m FROM cycles WHERE run_id = 1 LIMIT 2'");
    ASSERT_EQ(shell.exit_code, 0) << shell.output;
    ASSERT_EQ(lines_of(shell.output).size(), 2u) << shell.output;
    EXPECT_EQ(shell.output.rfind("0|", 0), 0u) << shell.output;
  }
  // Debian's python3 has loadable extensions (a pyenv build often has not).
  if (!fs::exists("/usr/bin/python3")) {
    std::cout << "/usr/bin/python3 is not installed: Python's load_extension is not tried\n";
    return;
  }
  const auto python = run_shell_command(
      "/usr/bin/python3 -c \"import sqlite3; c = sqlite3.connect('" + db_ + "'); c.enable_load_extension(True); c.load_extension('" +
      ext + "'); print(c.execute('SELECT count(*) FROM targets WHERE run_id = 1 AND origin = \\\"recorded\\\"').fetchone()[0])\"");
  ASSERT_EQ(python.exit_code, 0) << python.output;
  SQLite::Database db = connect();
  EXPECT_EQ(std::stoll(python.output), db.execAndGet("SELECT count(*) FROM targets WHERE run_id = 1 AND origin = 'recorded'").getInt64());
}

TEST_F(SqliteExtension, AnInMemoryConnectionOrAnotherDatabaseIsRefusedSayingWhy) {
  SQLite::Database memory(":memory:", SQLite::OPEN_READWRITE);
  memory.loadExtension(extension_path().c_str(), nullptr);
  try {
    memory.execAndGet("SELECT count(*) FROM cycles");
    FAIL() << "an in-memory connection served cycles";
  } catch (const SQLite::Exception& e) {
    EXPECT_NE(std::string(e.what()).find("reads the report database opened as main"), std::string::npos) << e.what();
  }
  const std::string other = (dir_ / "other.sqlite").string();
  {
    SQLite::Database db(other, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db.exec("CREATE TABLE t(x)");
  }
  SQLite::Database db(other, SQLite::OPEN_READONLY);
  db.loadExtension(extension_path().c_str(), nullptr);
  try {
    db.execAndGet("SELECT count(*) FROM targets");
    FAIL() << "a database of another application served targets";
  } catch (const SQLite::Exception& e) {
    EXPECT_NE(std::string(e.what()).find("rcsim: " + other), std::string::npos) << e.what();
    // docs/sql.md: named as not a report (issue 51: "no such table: runs").
    EXPECT_NE(std::string(e.what()).find("not an rcsim report database"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("no such table"), std::string::npos) << e.what();
  }
}

// Issue 51: a constraint's value was read as an integer whatever it was: `run_id = 1.5` returned
// run 1 and `cycle <= 'zzz'` the rows of cycle 0 only. Only an integer or a real narrows the
// blocks read, rounded outwards, and SQLite checks every constraint again.
TEST_F(SqliteExtension, ConstraintsOfAnotherTypeGiveWhatSqliteItselfGives) {
  SQLite::Database db = connect();
  const auto count = [&](const std::string& sql) { return db.execAndGet(sql).getInt64(); };
  const long long run1 = count("SELECT count(*) FROM targets WHERE run_id = 1");
  ASSERT_GT(run1, 0);
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 1.5"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 1.0"), run1);
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 'x'"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = NULL"), 0);
  for (const std::string where : {"cycle <= 'zzz'", "cycle >= 'zzz'", "cycle < x'00'", "cycle = 7.0", "cycle = 7.5", "cycle < 7.5",
                                  "cycle > 7.5", "cycle >= 1e300", "cycle <= -1e300", "cycle <= 1e300", "cycle = NULL"}) {
    EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 1 AND " + where),
              count("SELECT count(*) FROM (SELECT * FROM targets WHERE run_id = 1) WHERE " + where))
        << where;
  }
  EXPECT_EQ(count("SELECT count(*) FROM targets WHERE run_id = 1 AND cycle <= 'zzz'"), run1);
}

}  // namespace rcsim::sqlite_extension_test
