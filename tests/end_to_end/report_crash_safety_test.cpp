// Crash safety of the report database (issue 21): `rcsim replay` SIGKILLed at random moments, 120
// times, into one database; and four replays writing one database at once. Afterwards SQLite's
// integrity check passes, every replay that reported success has its run complete, and no run is
// half there (a run is one transaction).
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <chrono>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "app/stream/stream_test_support.hpp"
#include "sanitizers.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using stream::testing::Child;
using stream::testing::spawn;

const std::string kRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/city_drive_60s";

struct ReportState {
  std::string integrity;
  long long runs = 0, runs_without_summary = 0, runs_without_cycles = 0;
};

ReportState inspect(const fs::path& db_path) {
  SQLite::Database db(db_path.string(), SQLite::OPEN_READONLY);
  ReportState s;
  s.integrity = db.execAndGet("PRAGMA integrity_check").getString();
  s.runs = db.execAndGet("SELECT count(*) FROM runs").getInt64();
  s.runs_without_summary =
      db.execAndGet("SELECT count(*) FROM runs WHERE run_id NOT IN (SELECT run_id FROM summaries)").getInt64();
  s.runs_without_cycles =
      db.execAndGet("SELECT count(*) FROM runs WHERE run_id NOT IN (SELECT run_id FROM summaries WHERE cycles > 0)")
          .getInt64();
  return s;
}

TEST(ReportCrashSafety, ReplaysKilledAtRandomMomentsLeaveOnlyCompleteRuns) {
  const fs::path dir = testing::fresh_scratch_dir("crash_safety");
  const fs::path db = dir / "report.sqlite";
  // How long one replay takes here (to spread the kills over it): the faster of two complete ones
  // (the first also creates the database, and a busy machine slows one or the other).
  long replay_ms = 0;
  for (int i = 0; i < 2; ++i) {
    const auto start = std::chrono::steady_clock::now();
    Child first = spawn({RCSIM_BINARY, "replay", kRecording, "--db", db.string(), "--again"}, dir / "out", dir / "err");
    ASSERT_EQ(first.wait(std::chrono::seconds(60)), 0);
    const long ms = static_cast<long>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start).count());
    replay_ms = i == 0 ? ms : std::min(replay_ms, ms);
  }
  std::mt19937_64 rng(21);
  // Over the replay's measured duration: with other tests running beside it (ctest -j3) a replay's
  // duration varies by 2x, and delays beyond it only let replays finish first.
  std::uniform_int_distribution<long> delay_ms(0, std::max<long>(1, replay_ms));
  // Under the sanitizers a replay's start dominates, and the sanitizers look for memory errors, not
  // for the odds of a kill landing mid-commit: a third of the kills keeps the ASan stage short.
  constexpr int kKills = RCSIM_UNDER_SANITIZER ? 40 : 120;
  int succeeded = 2, killed = 0, failed = 0;
  std::vector<long long> reported_runs;  // the run ids successful replays printed
  for (int i = 0; i < kKills; ++i) {
    Child child = spawn({RCSIM_BINARY, "replay", kRecording, "--db", db.string(), "--again"}, dir / "out", dir / "err");
    ASSERT_GT(child.pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    ::kill(child.pid, SIGKILL);
    const int status = child.wait(std::chrono::seconds(60));
    if (status == 0) {
      ++succeeded;  // it finished before the kill
      const std::string out = stream::testing::read_file(dir / "out");  // "run N: ..."
      reported_runs.push_back(std::stoll(out.substr(4)));
    } else if (status == 128 + SIGKILL) {
      ++killed;
    } else {
      ++failed;
    }
  }
  const ReportState s = inspect(db);
  EXPECT_EQ(s.integrity, "ok");
  EXPECT_EQ(failed, 0);
  EXPECT_GE(killed, kKills / 4) << "the kills must land inside replays to test anything";
  // A kill may land after a run's commit, before the process ends: that run is complete too.
  EXPECT_GE(s.runs, succeeded);
  EXPECT_LE(s.runs, succeeded + killed);
  EXPECT_EQ(s.runs_without_summary, 0) << "no run is half there";
  EXPECT_EQ(s.runs_without_cycles, 0);
  SQLite::Database read(db.string(), SQLite::OPEN_READONLY);
  for (const long long run : reported_runs) {
    SQLite::Statement q(read, "SELECT count(*) FROM summaries WHERE run_id = ?");
    q.bind(1, static_cast<std::int64_t>(run));
    ASSERT_TRUE(q.executeStep());
    EXPECT_EQ(q.getColumn(0).getInt(), 1) << "run " << run << " reported success";
  }
  // The database still takes runs.
  Child last = spawn({RCSIM_BINARY, "replay", kRecording, "--db", db.string(), "--again"}, dir / "out", dir / "err");
  EXPECT_EQ(last.wait(std::chrono::seconds(60)), 0);
  EXPECT_EQ(inspect(db).runs, s.runs + 1);
  std::cout << "[ figures  ] " << kKills << " kills over a " << replay_ms << " ms replay: " << killed
            << " killed mid-run, " << succeeded - 1 << " finished first; " << s.runs << " runs, integrity ok\n";
}

TEST(ReportCrashSafety, FourReplaysWritingOneDatabaseAtOnceAllSucceedOrSaySoCleanly) {
  const fs::path dir = testing::fresh_scratch_dir("concurrent_writers");
  const fs::path db = dir / "report.sqlite";
  Child create = spawn({RCSIM_BINARY, "replay", kRecording, "--db", db.string(), "--again"}, dir / "out", dir / "err");
  ASSERT_EQ(create.wait(std::chrono::seconds(60)), 0);
  std::vector<Child> writers;
  for (int i = 0; i < 4; ++i) {
    writers.push_back(spawn({RCSIM_BINARY, "replay", kRecording, "--db", db.string(), "--seed", std::to_string(i), "--again"},
                            dir / ("out" + std::to_string(i)), dir / ("err" + std::to_string(i))));
  }
  int succeeded = 1;
  for (int i = 0; i < 4; ++i) {
    const int status = writers[static_cast<std::size_t>(i)].wait(std::chrono::seconds(120));
    const std::string err = stream::testing::read_file(dir / ("err" + std::to_string(i)));
    if (status == 0) {
      ++succeeded;
    } else {
      // A writer that could not get the database in time says so and exits with the bad-input code.
      EXPECT_EQ(status, 2) << err;
      EXPECT_NE(err.find("report.sqlite"), std::string::npos) << err;
    }
  }
  const ReportState s = inspect(db);
  EXPECT_EQ(s.integrity, "ok");
  EXPECT_EQ(s.runs, succeeded);
  EXPECT_EQ(s.runs_without_summary, 0);
  EXPECT_EQ(succeeded, 5) << "short replays wait for each other within the busy timeout";
}

}  // namespace
}  // namespace rcsim
