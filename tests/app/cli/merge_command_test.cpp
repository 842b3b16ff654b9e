// `rcsim merge` as a user runs it (docs/merge.md): a line per shard, per duplicate and a total,
// --json, refusals with exit status 2 naming the file; atomicity under SIGKILL at random moments
// (the output is always the old report or the complete new one, never anything between); and
// other processes writing the output during a merge: nothing they write is lost or replaced.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>
#include <sys/wait.h>

#include <chrono>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "app/stream/stream_test_support.hpp"
#include "app/cli/run_rcsim.hpp"
#include "replay/store/report_merge.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using stream::testing::Child;
using stream::testing::spawn;
using testing::run_rcsim;

const std::string kRecordings = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/";

std::string value_text(const SQLite::Column& v) {
  if (v.isNull()) return "NULL";
  if (v.isInteger()) return fmt::format("i{}", v.getInt64());
  if (v.isFloat()) return fmt::format("r{}", v.getDouble());
  if (v.isText()) return fmt::format("t{}", v.getString());
  // A blob by its size and hash: the blocks of full runs are megabytes.
  const std::string_view bytes(static_cast<const char*>(v.getBlob()), static_cast<std::size_t>(v.getBytes()));
  return fmt::format("b{}:{:x}", bytes.size(), std::hash<std::string_view>{}(bytes));
}

// The report's logical content: its header and every row of every table, ordered, exactly.
struct ReportContent {
  std::string integrity;
  std::string rows;
};

ReportContent content(const fs::path& path) {
  // Read-write, as sqlite3 and rcsim open a report they may write: a finished report has a rollback
  // journal (issue 53), and a merge killed in it leaves a hot journal that the next such connection
  // rolls back (a read-only one cannot).
  SQLite::Database db(path.string(), SQLite::OPEN_READWRITE);
  ReportContent c;
  c.integrity = db.execAndGet("PRAGMA integrity_check").getString();
  c.rows = fmt::format("{} {}\n", db.execAndGet("PRAGMA application_id").getInt(),
                       db.execAndGet("PRAGMA user_version").getInt());
  std::vector<std::string> tables;
  SQLite::Statement q(db, "SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  while (q.executeStep()) tables.push_back(q.getColumn(0).getString());
  for (const std::string& table : tables) {
    c.rows += fmt::format("== {}\n", table);
    const int columns = db.execAndGet(fmt::format("SELECT count(*) FROM pragma_table_info('{}')", table)).getInt();
    std::vector<int> order(static_cast<std::size_t>(columns));
    for (int i = 0; i < columns; ++i) order[static_cast<std::size_t>(i)] = i + 1;
    SQLite::Statement rows(db, fmt::format("SELECT * FROM {} ORDER BY {}", table, fmt::join(order, ", ")));
    while (rows.executeStep()) {
      for (int i = 0; i < rows.getColumnCount(); ++i) c.rows += value_text(rows.getColumn(i)) + '\x1f';
      c.rows += '\n';
    }
  }
  return c;
}

void replay(const std::string& recording, const fs::path& db, int seed, const char* store = "summary") {
  const auto r = run_rcsim(fmt::format("replay {}{} --db {} --seed {} --store {}", kRecordings, recording, db.string(),
                                       seed, store));
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

// Makes the database's runs `copies` times as many, each copy another seed (another identity):
// a large shard without replaying it.
void multiply_runs(const fs::path& path, int copies) {
  SQLite::Database db(path.string(), SQLite::OPEN_READWRITE);
  const auto tables = replay::classify_report_tables(db);
  const std::int64_t n = db.execAndGet("SELECT max(run_id) FROM runs").getInt64();
  SQLite::Transaction transaction(db);
  for (int k = 1; k < copies; ++k) {
    for (const std::string& table : tables.run_scoped) {
      std::string columns;
      SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?) ORDER BY cid");
      info.bind(1, table);
      while (info.executeStep()) {
        const std::string name = info.getColumn(0).getString();
        columns += (columns.empty() ? "" : ", ") + (name == "run_id" ? fmt::format("run_id + {}", k * n) : name);
      }
      db.exec(fmt::format("INSERT INTO {} SELECT {} FROM {} WHERE run_id <= {}", table, columns, table, n));
    }
  }
  db.exec(fmt::format("UPDATE runs SET seed = seed + 1000 * run_id WHERE run_id > {}", n));
  transaction.commit();
}

class MergeCli : public testing::ScratchDirTest {
 protected:
  MergeCli() : ScratchDirTest("merge_cli") {}
};

TEST_F(MergeCli, SaysWhatItAddedPerShardEachDuplicateAndTheTotal) {
  const fs::path a = dir_ / "a.sqlite", b = dir_ / "b.sqlite", out = dir_ / "campaign.sqlite";
  replay("two_in_one_cell", a, 1);
  replay("standstill_1m", a, 1);
  replay("two_in_one_cell", b, 1);  // the same run as a's first
  replay("two_in_one_cell", b, 2);
  auto r = run_rcsim(fmt::format("merge {} {} -o {}", a.string(), b.string(), out.string()), false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(a.string() + ": 2 runs, 2 added, 0 duplicates\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(b.string() + ": 2 runs, 1 added, 1 duplicate\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(b.string() + " run 1 duplicates run 1 of " + a.string() +
                          " (recording two_in_one_cell, seed 1); same figures\n"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("merged 4 runs from 2 shards into " + out.string() + ": 3 added, 1 duplicate; " +
                          out.string() + " now holds 3 runs\n"),
            std::string::npos)
      << r.output;
  // Again, as JSON: nothing added.
  r = run_rcsim(fmt::format("merge {} {} -o {} --json", a.string(), b.string(), out.string()), false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = nlohmann::json::parse(r.output);
  EXPECT_EQ(json["output"], out.string());
  EXPECT_EQ(json["runs_before"], 3);
  EXPECT_EQ(json["runs_merged"], 4);
  EXPECT_EQ(json["added"], 0);
  EXPECT_EQ(json["duplicates"], 4);
  EXPECT_EQ(json["inconsistent_duplicates"], 0);
  EXPECT_EQ(json["runs_after"], 3);
  ASSERT_EQ(json["inputs"].size(), 2u);
  EXPECT_EQ(json["inputs"][1]["file"], b.string());
  EXPECT_EQ(json["inputs"][1]["run_ids"], nlohmann::json::parse("[[1, 1], [2, 3]]"));
  EXPECT_EQ(json["duplicate_runs"][3]["duplicate_of"]["file"], out.string());
  EXPECT_EQ(json["duplicate_runs"][3]["duplicate_of"]["run_id"], 3);
  EXPECT_EQ(json["duplicate_runs"][3]["recording"], "two_in_one_cell");
  EXPECT_EQ(json["duplicate_runs"][3]["seed"], 2);
  // The merged report is a report.
  r = run_rcsim(fmt::format("report {} -o {}", out.string(), (dir_ / "r.html").string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(MergeCli, ADuplicateWithOtherFiguresIsAWarning) {
  const fs::path a = dir_ / "a.sqlite", b = dir_ / "b.sqlite", out = dir_ / "campaign.sqlite";
  replay("two_in_one_cell", a, 1);
  fs::copy_file(a, b);
  SQLite::Database(b.string(), SQLite::OPEN_READWRITE).exec("UPDATE summaries SET targets_simulated = 7");
  const auto r = run_rcsim(fmt::format("merge {} {} -o {}", a.string(), b.string(), out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rcsim: warning: " + b.string() + " run 1 duplicates run 1 of " + a.string() +
                          " (recording two_in_one_cell, seed 1) but its figures differ from the kept run's: "
                          "targets_simulated"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("; FIGURES DIFFER\n"), std::string::npos) << r.output;
}

TEST_F(MergeCli, RefusesAShardOfAnotherSchemaVersionWithStatus2NamingIt) {
  const fs::path a = dir_ / "a.sqlite", old = dir_ / "shard-3.sqlite", out = dir_ / "campaign.sqlite";
  replay("two_in_one_cell", a, 1);
  fs::copy_file(a, old);
  SQLite::Database(old.string(), SQLite::OPEN_READWRITE).exec("PRAGMA user_version = 4");
  auto r = run_rcsim(fmt::format("merge {} {} -o {}", a.string(), old.string(), out.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fmt::format("rcsim: error: {}: report schema version 4, expected {}", old.string(),
                                      replay::kReportSchemaVersion)),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  r = run_rcsim(fmt::format("merge {} -o {}", (dir_ / "nothing.sqlite").string(), out.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing.sqlite: no such report database"), std::string::npos) << r.output;
  r = run_rcsim(fmt::format("merge -o {}", out.string()));
  EXPECT_NE(r.exit_code, 0) << "a shard is required";
}

bool has_merge_file(const fs::path& dir) {
  std::error_code error;
  for (const auto& e : fs::directory_iterator(dir, error)) {
    if (e.path().filename().string().find(".merge-") != std::string::npos) return true;
  }
  return false;
}

// The output made a copy of `from`, or removed if `from` is empty; first its -wal and -shm (of a
// merge killed inside its transaction, or of a reader) go, so that none is read with another file.
void put_output(const fs::path& from, const fs::path& out) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(out.string() + suffix);
  if (!from.empty()) fs::copy_file(from, out);
}

// Whether the child has ended, without reaping it (Child::wait does).
bool ended(const Child& child) {
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(child.pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == child.pid;
}

// Waits until the merge holds the output's write lock (a BEGIN IMMEDIATE from here finds it busy):
// true then; false if the merge ended first.
bool wait_for_the_merges_lock(const fs::path& out, const Child& merge) {
  SQLite::Database probe(out.string(), SQLite::OPEN_READWRITE);  // busy timeout 0: never waits
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!ended(merge) && std::chrono::steady_clock::now() < give_up) {
    try {
      probe.exec("BEGIN IMMEDIATE");
      probe.exec("ROLLBACK");
    } catch (const SQLite::Exception& e) {
      if (e.getErrorCode() == SQLITE_BUSY) return true;
      throw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

// A write into the output, as a replay's: it waits for a lock up to 60 s.
void write_name(const fs::path& out, const std::string& name) {
  SQLite::Database writer(out.string(), SQLite::OPEN_READWRITE);
  writer.setBusyTimeout(60000);
  SQLite::Statement update(writer, "UPDATE runs SET recording_name = ? WHERE run_id = 1");
  update.bind(1, name);
  update.exec();
}

// A report of one full run (the old output) and a shard of 24 full runs to merge into it: a merge
// of a few hundred milliseconds, long enough to be interrupted.
class MergeCliAtomicity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(testing::fresh_scratch_dir("merge_cli_atomicity"));
    replay("city_drive_60s", *dir_ / "a.sqlite", 1, "full");
    replay("city_drive_60s", *dir_ / "b.sqlite", 2, "full");
    multiply_runs(*dir_ / "b.sqlite", 24);
    const auto r = run_rcsim(fmt::format("merge {} -o {}", (*dir_ / "a.sqlite").string(), old_report().string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path old_report() { return *dir_ / "old.sqlite"; }
  static fs::path shard() { return *dir_ / "b.sqlite"; }

  // The merged report, made by a merge left alone into a copy of the old report (or, `into_old`
  // false, into a missing output), and how long that took.
  static std::pair<ReportContent, long> merged(const fs::path& out, bool into_old = true) {
    put_output(into_old ? old_report() : fs::path(), out);
    const auto start = std::chrono::steady_clock::now();
    const auto r = run_rcsim(fmt::format("merge {} -o {}", shard().string(), out.string()));
    const long ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return {content(out), ms};
  }

  static fs::path* dir_;
};

fs::path* MergeCliAtomicity::dir_ = nullptr;

// SIGKILL at random moments of a merge, 30 times into an existing report (written in place, in one
// transaction) and 10 times into a missing one (built in a temporary file): afterwards the output
// is, every time, the report as it was (or none) or the complete merged one, and passes SQLite's
// integrity check; the next merge clears the killed ones' temporary files.
TEST_F(MergeCliAtomicity, AMergeKilledAtAnyMomentLeavesTheOldOrTheNewReport) {
  const fs::path work = testing::fresh_scratch_dir("merge_cli_kill");
  const fs::path out = work / "campaign.sqlite";
  const ReportContent old_state = content(old_report());
  const auto [new_state, first_ms] = merged(out);
  ASSERT_NE(new_state.rows, old_state.rows);
  // The kills spread over the faster of two merges (a busy machine slows one or the other, and
  // the first also warms the page cache), so that most land inside a merge.
  const long merge_ms = std::min(first_ms, merged(out).second);
  const auto [fresh_state, fresh_ms] = merged(out, false);
  std::mt19937_64 rng(20);
  constexpr int kKillsInPlace = 30, kKillsNew = 10;
  int killed = 0, finished = 0, old_seen = 0, new_seen = 0, none_seen = 0, fresh_seen = 0;
  for (int i = 0; i < kKillsInPlace + kKillsNew; ++i) {
    const bool in_place = i < kKillsInPlace;
    put_output(in_place ? old_report() : fs::path(), out);
    Child child = spawn({RCSIM_BINARY, "merge", shard().string(), "-o", out.string()}, work / "out", work / "err");
    ASSERT_GT(child.pid, 0);
    std::uniform_int_distribution<long> delay_ms(0, std::max<long>(2, 5 * (in_place ? merge_ms : fresh_ms) / 4));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    ::kill(child.pid, SIGKILL);
    const int status = child.wait(std::chrono::seconds(60));
    if (status == 0) {
      ++finished;
    } else {
      ASSERT_EQ(status, 128 + SIGKILL) << stream::testing::read_file(work / "err");
      ++killed;
    }
    if (!in_place && !fs::exists(out)) {
      EXPECT_NE(status, 0) << "kill " << i << ": a merge that finished left no report";
      ++none_seen;
      continue;
    }
    const ReportContent now = content(out);
    ASSERT_EQ(now.integrity, "ok") << "kill " << i;
    const bool is_old = in_place && now.rows == old_state.rows;
    const bool is_new = now.rows == (in_place ? new_state : fresh_state).rows;
    ASSERT_TRUE(is_old || is_new) << "kill " << i << " after a merge of " << merge_ms << " ms left something between";
    if (status == 0) {
      EXPECT_TRUE(is_new) << "kill " << i << ": a merge that finished left the old report";
    }
    old_seen += is_old;
    new_seen += in_place && is_new;
    fresh_seen += !in_place && is_new;
  }
  EXPECT_GE(killed, (kKillsInPlace + kKillsNew) / 3) << "the kills must land inside merges to test anything";
  EXPECT_GT(old_seen, 0);
  // The killed merges' temporary files go with the next merge, which then adds the runs.
  put_output(old_report(), out);
  const auto r = run_rcsim(fmt::format("merge {} -o {}", shard().string(), out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(content(out).rows, new_state.rows);
  EXPECT_FALSE(has_merge_file(work));
  std::cout << "[ figures  ] " << kKillsInPlace << " kills over a " << merge_ms
            << " ms merge of 24 full runs into a report: the old report left " << old_seen << " times, the new "
            << new_seen << " times; " << kKillsNew << " over a " << fresh_ms << " ms merge into none: no report "
            << none_seen << " times, the new " << fresh_seen << " times; " << killed << " killed, " << finished
            << " finished first, never anything else\n";
  fs::remove_all(work);
}

// Something writing the output while a merge runs into it: its write is never lost, and the merge
// succeeds. The merge holds the output's write lock from before it reads the output until it
// commits: a writer waits for the merge, or the merge for the writer, and the merged report holds
// both. Writes at random moments; once the merge holds the lock; from a writer whose transaction
// is open when the merge starts; and by `rcsim replay --db` into the output.
TEST_F(MergeCliAtomicity, AWriteIntoTheOutputDuringAMergeIsNeverLost) {
  const fs::path work = testing::fresh_scratch_dir("merge_cli_writer");
  const fs::path out = work / "campaign.sqlite";
  const long merge_ms = merged(out).second;
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<long> delay_ms(0, std::max<long>(2, merge_ms));
  enum class Writer { at_random, under_the_merges_lock, open_before_the_merge, replay };
  constexpr int kWrites = 12;
  int under_lock = 0, merge_waited = 0;
  for (int i = 0; i < kWrites; ++i) {
    const auto writer = static_cast<Writer>(i % 4);
    const std::string name = fmt::format("written {}", i);
    const int seed = 100 + i;
    put_output(old_report(), out);
    std::optional<SQLite::Database> early;
    if (writer == Writer::open_before_the_merge) {
      early.emplace(out.string(), SQLite::OPEN_READWRITE);
      early->exec("BEGIN IMMEDIATE");
      early->exec(fmt::format("UPDATE runs SET recording_name = '{}' WHERE run_id = 1", name));
    }
    Child child = spawn({RCSIM_BINARY, "merge", shard().string(), "-o", out.string()}, work / "out", work / "err");
    ASSERT_GT(child.pid, 0);
    int replay_status = 0;
    std::string replay_output;
    switch (writer) {
      case Writer::at_random:
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
        write_name(out, name);
        break;
      case Writer::under_the_merges_lock:
        under_lock += wait_for_the_merges_lock(out, child);
        write_name(out, name);
        break;
      case Writer::open_before_the_merge:
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
        EXPECT_FALSE(ended(child)) << "write " << i << ": the merge ended while another process held the lock";
        merge_waited += !ended(child);
        early->exec("COMMIT");
        early.reset();
        break;
      case Writer::replay: {
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
        const auto r = run_rcsim(fmt::format("replay {}two_in_one_cell --db {} --seed {} --store summary", kRecordings,
                                             out.string(), seed));
        replay_status = r.exit_code;
        replay_output = r.output;
        break;
      }
    }
    const int status = child.wait(std::chrono::seconds(120));
    const std::string err = stream::testing::read_file(work / "err");
    EXPECT_EQ(status, 0) << "write " << i << ": " << err;
    SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
    EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
    const long long runs = db.execAndGet("SELECT count(*) FROM runs").getInt64();
    if (writer == Writer::replay) {
      EXPECT_EQ(replay_status, 0) << replay_output;
      EXPECT_EQ(runs, 26) << "write " << i << ": the replay's run and the merge's 24";
      SQLite::Statement q(db, "SELECT count(*) FROM runs WHERE recording_name = 'two_in_one_cell' AND seed = ?");
      q.bind(1, seed);
      ASSERT_TRUE(q.executeStep());
      EXPECT_EQ(q.getColumn(0).getInt(), 1) << "write " << i << ": the replay's run lost; merge status " << status;
    } else {
      EXPECT_EQ(db.execAndGet("SELECT recording_name FROM runs WHERE run_id = 1").getString(), name)
          << "write " << i << " lost; merge status " << status << ": " << err;
      EXPECT_EQ(runs, 25);
    }
  }
  EXPECT_GT(under_lock, 0) << "writes while the merge held the lock";
  std::cout << "[ figures  ] " << kWrites << " writes during " << merge_ms << " ms merges, every one kept and every "
            << "merge complete; " << under_lock << " of " << kWrites / 4 << " writes came while the merge held the "
            << "lock, " << merge_waited << " merges waited for a writer's lock\n";
  fs::remove_all(work);
}

// A merge into a missing output builds it in a temporary file; an output that another process
// creates meanwhile (a replay into it) is never replaced: the merge refuses, status 2, naming it,
// and the next merge adds the runs to it. The merge is stopped (SIGSTOP) once its temporary file
// is there, the output created, and the merge continued.
TEST_F(MergeCliAtomicity, AnOutputCreatedDuringAMergeIntoAMissingOneIsNeverReplaced) {
  const fs::path work = testing::fresh_scratch_dir("merge_cli_appeared");
  const fs::path out = work / "campaign.sqlite";
  int caught = 0, too_late = 0;
  for (int attempt = 0; attempt < 10 && caught < 3; ++attempt) {
    put_output({}, out);
    Child child = spawn({RCSIM_BINARY, "merge", shard().string(), "-o", out.string()}, work / "out", work / "err");
    ASSERT_GT(child.pid, 0);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!has_merge_file(work) && !ended(child) && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(child.pid, SIGSTOP);
    if (fs::exists(out) || !has_merge_file(work)) {  // it had moved its file into place already
      ::kill(child.pid, SIGCONT);
      EXPECT_EQ(child.wait(std::chrono::seconds(60)), 0);
      ++too_late;
      continue;
    }
    replay("two_in_one_cell", out, 7);
    const std::string created = content(out).rows;
    ::kill(child.pid, SIGCONT);
    const int status = child.wait(std::chrono::seconds(60));
    const std::string err = stream::testing::read_file(work / "err");
    EXPECT_EQ(status, 2) << err;
    EXPECT_NE(err.find("rcsim: error: " + out.string() + ": created by another process while the merge built it"),
              std::string::npos)
        << err;
    EXPECT_EQ(content(out).rows, created) << "the output created meanwhile was replaced";
    EXPECT_FALSE(has_merge_file(work)) << "the temporary file stays behind";
    ++caught;
  }
  EXPECT_GT(caught, 0) << "every merge was done before it was stopped";
  // Merged again, its runs go into the output that appeared.
  const auto r = run_rcsim(fmt::format("merge {} -o {}", shard().string(), out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs").getInt64(), 25);
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs WHERE seed = 7").getInt64(), 1);
  std::cout << "[ figures  ] " << caught << " outputs created during a merge into none, none replaced; " << too_late
            << " merges done before they were stopped\n";
  fs::remove_all(work);
}

}  // namespace
}  // namespace rcsim
