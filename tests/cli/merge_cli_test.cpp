// `rcsim merge` as a user runs it (docs/merge.md): a line per shard, per duplicate and a total,
// --json, refusals with exit status 2 naming the file; and atomicity under SIGKILL at random
// moments: the output is always the old report or the complete new one, never anything between.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "../stream/stream_test_support.hpp"
#include "cli/run_rcsim.hpp"
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
  SQLite::Database db(path.string(), SQLite::OPEN_READONLY);
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
  EXPECT_NE(r.output.find("rcsim: error: " + old.string() + ": report schema version 4, expected 5"), std::string::npos)
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

  // The merged report, made by a merge left alone, and how long that took.
  static std::pair<ReportContent, long> merged(const fs::path& out) {
    fs::copy_file(old_report(), out, fs::copy_options::overwrite_existing);
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

// SIGKILL at random moments of a merge into an existing report, 30 times: afterwards the output
// is, every time, either the report as it was or the complete merged one, and passes SQLite's
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
  std::mt19937_64 rng(20);
  std::uniform_int_distribution<long> delay_ms(0, std::max<long>(2, 5 * merge_ms / 4));
  constexpr int kKills = 30;
  int killed = 0, finished = 0, old_seen = 0, new_seen = 0;
  for (int i = 0; i < kKills; ++i) {
    fs::copy_file(old_report(), out, fs::copy_options::overwrite_existing);
    Child child = spawn({RCSIM_BINARY, "merge", shard().string(), "-o", out.string()}, work / "out", work / "err");
    ASSERT_GT(child.pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    ::kill(child.pid, SIGKILL);
    const int status = child.wait(std::chrono::seconds(60));
    if (status == 0) {
      ++finished;
    } else {
      ASSERT_EQ(status, 128 + SIGKILL) << stream::testing::read_file(work / "err");
      ++killed;
    }
    const ReportContent now = content(out);
    ASSERT_EQ(now.integrity, "ok") << "kill " << i;
    const bool is_old = now.rows == old_state.rows, is_new = now.rows == new_state.rows;
    ASSERT_TRUE(is_old || is_new) << "kill " << i << " after a merge of " << merge_ms << " ms left something between";
    if (status == 0) {
      EXPECT_TRUE(is_new) << "kill " << i << ": a merge that finished left the old report";
    }
    old_seen += is_old;
    new_seen += is_new;
  }
  EXPECT_GE(killed, kKills / 3) << "the kills must land inside merges to test anything";
  EXPECT_GT(old_seen, 0);
  // The killed merges' temporary files go with the next merge, which then adds the runs.
  const auto r = run_rcsim(fmt::format("merge {} -o {}", shard().string(), out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(content(out).rows, new_state.rows);
  for (const auto& e : fs::directory_iterator(work)) {
    EXPECT_EQ(e.path().filename().string().find(".merge-"), std::string::npos) << e.path();
  }
  std::cout << "[ figures  ] " << kKills << " kills over a " << merge_ms << " ms merge of 24 full runs: " << killed
            << " killed, " << finished << " finished first; the old report left " << old_seen << " times, the new "
            << new_seen << " times, never anything else\n";
  fs::remove_all(work);
}

// Something writing the output while a merge runs (a replay into it): its write is never lost.
// Either it came before the merge read the output, or after its rename, and is in the merged
// report; or the merge notices the change before its rename and refuses, status 2, leaving the
// output with the write. Half the writes come at random moments, half once the merge is building
// its temporary file (those it must refuse).
TEST_F(MergeCliAtomicity, AWriteIntoTheOutputDuringAMergeIsNeverLost) {
  const fs::path work = testing::fresh_scratch_dir("merge_cli_writer");
  const fs::path out = work / "campaign.sqlite";
  const long merge_ms = merged(out).second;
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<long> delay_ms(0, std::max<long>(2, merge_ms));
  int refused = 0, merged_with_it = 0;
  for (int i = 0; i < 8; ++i) {
    fs::copy_file(old_report(), out, fs::copy_options::overwrite_existing);
    Child child = spawn({RCSIM_BINARY, "merge", shard().string(), "-o", out.string()}, work / "out", work / "err");
    ASSERT_GT(child.pid, 0);
    if (i % 2 == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    } else {
      // Once the merge builds its temporary file: it has read the output, and not renamed yet.
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (!has_merge_file(work) && std::chrono::steady_clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    const std::string name = fmt::format("written {}", i);
    {
      SQLite::Database writer(out.string(), SQLite::OPEN_READWRITE);
      writer.setBusyTimeout(10000);
      SQLite::Statement update(writer, "UPDATE runs SET recording_name = ? WHERE run_id = 1");
      update.bind(1, name);
      update.exec();
    }
    const int status = child.wait(std::chrono::seconds(60));
    const std::string err = stream::testing::read_file(work / "err");
    SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
    EXPECT_EQ(db.execAndGet("SELECT recording_name FROM runs WHERE run_id = 1").getString(), name)
        << "write " << i << " lost; merge status " << status << ": " << err;
    const long long runs = db.execAndGet("SELECT count(*) FROM runs").getInt64();
    if (status == 0) {
      ++merged_with_it;
      EXPECT_EQ(runs, 25);
    } else {
      ++refused;
      EXPECT_EQ(status, 2) << err;
      EXPECT_NE(err.find(out.string() + ": changed while it was being merged into"), std::string::npos) << err;
      EXPECT_EQ(runs, 1);
    }
  }
  EXPECT_GT(refused, 0) << "writes during the merge";
  std::cout << "[ figures  ] 8 writes during " << merge_ms << " ms merges: " << refused << " merges refused, "
            << merged_with_it << " took the write in\n";
  fs::remove_all(work);
}

}  // namespace
}  // namespace rcsim
