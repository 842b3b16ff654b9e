// Damaged and forged report databases (docs/hardening.md): `rcsim report` checks every stored count
// against the run before it allocates, `rcsim merge` checks every input's pages before it copies
// anything, and both name the file and exit with status 2. Eight replays into one new database at
// once all store their runs.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kDamagedRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/close_front";

class DamagedReport : public rcsim::testing::ScratchDirTest {
 protected:
  DamagedReport() : ScratchDirTest("damaged_report") {}
  fs::path replayed(const std::string& name) {
    const fs::path db = dir_ / name;
    const auto r = rcsim::testing::run_rcsim("replay " + kDamagedRecording + " --db " + db.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return db;
  }
};

TEST_F(DamagedReport, ABlockClaimingMoreCyclesThanItsRunIsRefusedBeforeAnythingIsAllocated) {
  // 2^31 - 1 cycles made report throw std::bad_alloc; 3e6 cycles of empty columns rendered
  // three million phantom cycles.
  for (const char* forged : {"UPDATE target_blocks SET cycles = 2147483647",
                             "UPDATE cycle_blocks SET cycles = 3000000 WHERE first_cycle = 0",
                             "UPDATE object_state_blocks SET first_cycle = -5"}) {
    const fs::path db = replayed(std::string("forged_") + std::to_string(std::hash<std::string>{}(forged)) + ".sqlite");
    {
      SQLite::Database write(db.string(), SQLite::OPEN_READWRITE);
      ASSERT_GT(write.exec(forged), 0) << forged;
    }
    const fs::path html = dir_ / "report.html";
    const auto r = rcsim::testing::run_rcsim("report " + db.string() + " -o " + html.string());
    EXPECT_EQ(r.exit_code, 2) << forged << "\n" << r.output;
    EXPECT_NE(r.output.find(db.string() + ": report database: a row of"), std::string::npos) << forged << "\n" << r.output;
    EXPECT_NE(r.output.find("(damaged)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(html));
  }
}

// Issue 51, HIGH 2 and 3: a run that claims 2^31 - 1 cycles with its one block at the end made
// `export --format mcap` loop for ever (its block counter wrapped); counts whose sum wraps to the
// bytes behind them made export and report allocate 2^63 targets. Both now end, the counts refused.
TEST_F(DamagedReport, ClaimedCyclesAndWrappingCountsCostNoTimeAndNoMemory) {
  const fs::path far = replayed("far.sqlite");
  {
    SQLite::Database write(far.string(), SQLite::OPEN_READWRITE);
    write.exec("UPDATE runs SET cycles = 2147483647");
    for (const char* table : {"cycle_blocks", "target_blocks", "object_state_blocks"}) {
      write.exec(std::string("DELETE FROM ") + table + " WHERE first_cycle > 0");
      write.exec(std::string("UPDATE ") + table + " SET first_cycle = 2147483647 - cycles");
    }
  }
  const fs::path mcap = dir_ / "far.mcap";
  const auto exported = rcsim::testing::run_shell_command("timeout 120 " + std::string(RCSIM_BINARY) + " export " + far.string() +
                                                          " --run 1 --format mcap -o " + mcap.string());
  EXPECT_NE(exported.exit_code, 124) << "export ran for 2 minutes: " << exported.output;
  EXPECT_EQ(exported.exit_code, 0) << exported.output;

  const fs::path wrapped = replayed("wrapped.sqlite");
  {
    SQLite::Database write(wrapped.string(), SQLite::OPEN_READWRITE);
    // 2^63 + 2^63 recorded targets: a sum of 0 mod 2^64, over an empty range column.
    ASSERT_GT(write.exec("UPDATE target_blocks SET n_recorded = CAST(X'80808080808080808001' || X'80808080808080808001' || "
                         "zeroblob(cycles - 2) AS BLOB), n_simulated = zeroblob(cycles), range_m = X'' WHERE first_cycle = 0"),
              0);
  }
  for (const std::string& command : {"export " + wrapped.string() + " --run 1 --table targets",
                                    "report " + wrapped.string() + " -o " + (dir_ / "wrapped.html").string()}) {
    const auto r = rcsim::testing::run_rcsim(command);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.output.substr(0, 2000);
    EXPECT_NE(r.output.find("is damaged"), std::string::npos) << command << "\n" << r.output.substr(0, 2000);
  }
}

TEST_F(DamagedReport, AMergeRefusesAnInputWhosePagesAreDamagedNamingIt) {
  const fs::path good = replayed("good.sqlite"), bad = replayed("bad.sqlite");
  long long root_page = 0, page_size = 0;
  {
    SQLite::Database read(bad.string(), SQLite::OPEN_READONLY);
    root_page = read.execAndGet("SELECT rootpage FROM sqlite_schema WHERE name = 'merge_pairs'").getInt64();
    page_size = read.execAndGet("PRAGMA page_size").getInt64();
  }
  ASSERT_GT(root_page, 1);
  {
    // The b-tree page's type byte: no page type SQLite knows.
    std::fstream file(bad, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp((root_page - 1) * page_size);
    file.put(static_cast<char>(0x42));
  }
  const fs::path merged = dir_ / "merged.sqlite";
  const auto r = rcsim::testing::run_rcsim("merge " + good.string() + " " + bad.string() + " -o " + merged.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // Named, whichever check finds it first: SQLite reading the schema, or quick_check.
  EXPECT_NE(r.output.find(bad.string() + ": "), std::string::npos) << r.output;
  EXPECT_TRUE(r.output.find("malformed") != std::string::npos || r.output.find("damaged") != std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(merged)) << "the merge wrote a report from a damaged input";
}

TEST_F(DamagedReport, AReadOnlyDatabaseInAReadOnlyDirectoryIsReported) {
  // "attempt to write a readonly database": report opened every database read-write.
  const fs::path db = replayed("readonly.sqlite");
  fs::permissions(db, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  std::string as_someone_else;
  if (::geteuid() == 0) {
    // Root may write anything: the report runs as nobody, for whom the file and the directory
    // are read-only.
    if (std::system("command -v runuser >/dev/null 2>&1 && id nobody >/dev/null 2>&1") != 0) {
      GTEST_SKIP() << "running as root without runuser or the user nobody: read-only access cannot be tried";
    }
    as_someone_else = "runuser -u nobody -- ";
  } else {
    fs::permissions(dir_, fs::perms::owner_write, fs::perm_options::remove);
  }
  const fs::path html = fs::temp_directory_path() / ("rcsim_readonly_" + std::to_string(::getpid()) + ".html");
  const std::string command = as_someone_else + RCSIM_BINARY + " report " + db.string() + " -o " + html.string() + " 2>&1";
  const int status = std::system(command.c_str());
  fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
  EXPECT_EQ(WEXITSTATUS(status), 0) << command;
  EXPECT_TRUE(fs::exists(html));
  fs::remove(html);
}

TEST_F(DamagedReport, AFullDiskIsNamedAndLeavesNoNewDatabaseBehind) {
  // A 64 KiB file system of its own, in a user and mount namespace (no privilege needed).
  if (std::system("unshare -rm true >/dev/null 2>&1") != 0) GTEST_SKIP() << "unshare -rm unavailable: no private file system to fill";
  const fs::path full = dir_ / "full";
  fs::create_directories(full);
  const std::string command = "unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs " + full.string() + " && " +
                              RCSIM_BINARY + " replay " + kDamagedRecording + " --db " + full.string() +
                              "/r.sqlite; echo \"rc $?\"; ls -A " + full.string() + "' 2>&1";
  std::string output;
  {
    FILE* pipe = ::popen(command.c_str(), "r");
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    ::pclose(pipe);
  }
  EXPECT_NE(output.find((full / "r.sqlite").string() + ": cannot use as a report database: database or disk is full"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("rc 2\n"), std::string::npos) << output;
  EXPECT_EQ(output.substr(output.find("rc 2\n") + 5), "") << "left behind: " << output;
}

TEST_F(DamagedReport, EightReplaysIntoOneNewDatabaseAtOnceAllStoreTheirRuns) {
  // Creating the schema was not one locked transaction: 1 to 7 of 8 failed with "duplicate column
  // name", "application_id 0x0" or "database is locked", and their runs were lost.
  const fs::path db = dir_ / "new.sqlite";
  std::vector<rcsim::testing::CommandResult> results(8);
  std::vector<std::thread> replays;
  for (std::size_t i = 0; i < results.size(); ++i) {
    replays.emplace_back([&, i] {
      results[i] = rcsim::testing::run_rcsim("replay " + kDamagedRecording + " --db " + db.string() + " --store summary --seed " +
                                             std::to_string(i));
    });
  }
  for (std::thread& t : replays) t.join();
  for (const auto& r : results) EXPECT_EQ(r.exit_code, 0) << r.output;
  SQLite::Database read(db.string(), SQLite::OPEN_READONLY);
  EXPECT_EQ(read.execAndGet("SELECT count(*) FROM runs").getInt(), 8);
  EXPECT_EQ(read.execAndGet("PRAGMA integrity_check").getString(), "ok");
}

}  // namespace
