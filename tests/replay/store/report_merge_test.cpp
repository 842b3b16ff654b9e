// Merging report databases (replay/store/report_merge.hpp, docs/merge.md): two shards merge into
// what one serial replay stores, figure for figure; a second merge of the same shards changes
// nothing; duplicates are reported, and figures that differ between them; inputs of another
// schema version, of another program or of another campaign are refused naming the file, the
// output left as it was; inputs are never written; benches are copied once; an existing output is
// written in place, in one transaction that waits for another writer; the temporary files of
// killed merges are removed.
#include "replay/store/report_merge.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

const fs::path kMergeRecordings = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic";

struct RunSpec {
  const char* recording;
  std::uint64_t seed;
  StoreLevel store;
};

void replay_into(const fs::path& db_path, const std::vector<RunSpec>& runs) {
  const auto db = open_report_database(db_path.string(), true);
  for (const RunSpec& r : runs) {
    ReplayOptions options;
    options.seed = r.seed;
    ReportWriter writer(*db, r.store);
    replay_recording_dir(kMergeRecordings / r.recording, options, writer);
  }
}

const std::vector<RunSpec> kShardA{{"standstill_1m", 1, StoreLevel::full}, {"two_in_one_cell", 1, StoreLevel::summary}};
const std::vector<RunSpec> kShardB{{"front_approach", 1, StoreLevel::full}, {"two_in_one_cell", 2, StoreLevel::summary}};

std::string value_text(const SQLite::Column& v) {
  if (v.isNull()) return "NULL";
  if (v.isInteger()) return fmt::format("i{}", v.getInt64());
  if (v.isFloat()) return fmt::format("r{}", v.getDouble());
  if (v.isText()) return fmt::format("t{}", v.getString());
  std::string hex = "b";
  const auto* bytes = static_cast<const unsigned char*>(v.getBlob());
  for (int i = 0; i < v.getBytes(); ++i) hex += fmt::format("{:02x}", bytes[i]);
  return hex;
}

// The logical content: the header, then every row of every table ordered by all its columns,
// values exactly with their types; without the columns named.
std::string dump(const fs::path& path, const std::set<std::string>& without = {}) {
  SQLite::Database db(path.string(), SQLite::OPEN_READONLY);
  std::string text = fmt::format("application_id {} user_version {}\n", db.execAndGet("PRAGMA application_id").getInt(),
                                 db.execAndGet("PRAGMA user_version").getInt());
  std::vector<std::string> tables;
  SQLite::Statement q(db, "SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  while (q.executeStep()) tables.push_back(q.getColumn(0).getString());
  for (const std::string& table : tables) {
    std::vector<std::string> columns;
    SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?) ORDER BY cid");
    info.bind(1, table);
    while (info.executeStep()) {
      if (without.count(info.getColumn(0).getString()) == 0) columns.push_back(info.getColumn(0).getString());
    }
    std::vector<std::string> order;
    for (std::size_t i = 0; i < columns.size(); ++i) order.push_back(std::to_string(i + 1));
    const std::string select = fmt::format("SELECT {} FROM {} ORDER BY {}", fmt::join(columns, ", "), table,
                                           fmt::join(order, ", "));
    text += fmt::format("== {}\n", table);
    SQLite::Statement rows(db, select);
    while (rows.executeStep()) {
      for (int c = 0; c < rows.getColumnCount(); ++c) text += value_text(rows.getColumn(c)) + '\x1f';
      text += '\n';
    }
  }
  return text;
}

long long count(const fs::path& path, const std::string& sql) {
  SQLite::Database db(path.string(), SQLite::OPEN_READONLY);
  return db.execAndGet(sql).getInt64();
}

void exec(const fs::path& path, const std::string& sql) {
  SQLite::Database db(path.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  db.exec(sql);
}

std::vector<std::string> merge_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().find(".merge-") != std::string::npos) names.push_back(e.path().filename().string());
  }
  return names;
}

// The message of the InputError the merge throws ("" if none).
std::string refusal(const std::vector<std::string>& inputs, const fs::path& output) {
  try {
    merge_reports(inputs, output.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class ReportMerge : public testing::ScratchDirTest {
 protected:
  ReportMerge() : ScratchDirTest("report_merge") {}

  static void SetUpTestSuite() {
    shards_ = new fs::path(testing::fresh_scratch_dir("report_merge_shards"));
    replay_into(*shards_ / "a.sqlite", kShardA);
    replay_into(*shards_ / "b.sqlite", kShardB);
    std::vector<RunSpec> serial = kShardA;
    serial.insert(serial.end(), kShardB.begin(), kShardB.end());
    replay_into(*shards_ / "serial.sqlite", serial);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*shards_);
    delete shards_;
  }

  // A copy of a prepared shard in this test's directory.
  std::string shard(const std::string& name, const std::string& as = "") const {
    const fs::path to = dir_ / (as.empty() ? name : as);
    fs::copy_file(*shards_ / name, to, fs::copy_options::overwrite_existing);
    return to.string();
  }

  static fs::path* shards_;
};

fs::path* ReportMerge::shards_ = nullptr;

TEST(ReportMergeTables, EveryTableOfAReportIsMergedOneWayOrAnother) {
  const fs::path dir = testing::fresh_scratch_dir("report_merge_tables");
  open_report_database((dir / "new.sqlite").string(), true);
  SQLite::Database db((dir / "new.sqlite").string(), SQLite::OPEN_READONLY);
  const ReportTables tables = classify_report_tables(db);
  EXPECT_TRUE(tables.unknown.empty()) << "a table merge does not know: " << tables.unknown.front();
  ASSERT_FALSE(tables.run_scoped.empty());
  EXPECT_EQ(tables.run_scoped.front(), "runs") << "the runs before the rows that refer to them";
  const std::set<std::string> run_scoped(tables.run_scoped.begin(), tables.run_scoped.end());
  EXPECT_EQ(run_scoped, (std::set<std::string>{"runs", "run_sensors", "run_objects", "cycle_blocks", "target_blocks",
                                               "object_state_blocks", "merge_pairs", "latencies",
                                               "distribution_distances", "summaries", "object_figures",
                                               "object_ranges"}));
  EXPECT_EQ(tables.bench, (std::vector<std::string>{"bench_runs", "bench_rows"}));
  EXPECT_EQ(std::set<std::string>(tables.campaign.begin(), tables.campaign.end()),
            (std::set<std::string>{"campaign", "criteria"}));
  // Independently of the classification: every table with a run_id column is copied per run.
  SQLite::Statement q(db, "SELECT s.name FROM sqlite_schema AS s, pragma_table_info(s.name) AS c WHERE s.type = "
                          "'table' AND c.name = 'run_id'");
  int with_run_id = 0;
  while (q.executeStep()) {
    ++with_run_id;
    EXPECT_EQ(run_scoped.count(q.getColumn(0).getString()), 1u) << q.getColumn(0).getString();
  }
  EXPECT_EQ(with_run_id, 12);
  fs::remove_all(dir);
}

TEST_F(ReportMerge, TwoShardsMergeIntoWhatASerialReplayStoresFigureForFigure) {
  const fs::path out = dir_ / "campaign.sqlite";
  const MergeResult r = merge_reports({shard("a.sqlite"), shard("b.sqlite")}, out.string());
  EXPECT_FALSE(r.output_existed);
  ASSERT_EQ(r.inputs.size(), 2u);
  EXPECT_EQ(r.inputs[0].added, 2);
  EXPECT_EQ(r.inputs[1].added, 2);
  EXPECT_EQ(r.runs_merged(), 4);
  EXPECT_EQ(r.added(), 4);
  EXPECT_TRUE(r.duplicates.empty());
  EXPECT_EQ(r.runs_after, 4);
  EXPECT_EQ(r.inputs[1].run_ids, (std::vector<std::pair<std::int64_t, std::int64_t>>{{1, 3}, {2, 4}}));
  // Every row of every table, the moment and the timings aside (the run ids match: shard a's runs
  // come first, as in the serial replay).
  // A finished report like every other: a rollback journal (issue 53: readable on read-only
  // storage), closed cleanly (no -wal, -shm), no temporary file left.
  EXPECT_FALSE(fs::exists(out.string() + "-wal"));
  EXPECT_FALSE(fs::exists(out.string() + "-shm"));
  EXPECT_TRUE(merge_files(dir_).empty());
  const std::set<std::string> circumstantial{"created_utc", "simulate_cpu_s", "total_wall_s"};
  const std::string merged = dump(out, circumstantial), serial = dump(*shards_ / "serial.sqlite", circumstantial);
  EXPECT_EQ(merged, serial);
  EXPECT_GT(merged.size(), 10000u);
  EXPECT_EQ(count(out, "SELECT count(*) FROM target_blocks"), count(*shards_ / "serial.sqlite", "SELECT count(*) FROM target_blocks"));
  EXPECT_GT(count(out, "SELECT count(*) FROM target_blocks"), 0);
  // Schema v6's targets per range bin came over with the rest, none of them unknown.
  EXPECT_GT(count(out, "SELECT count(*) FROM object_ranges"), 0);
  EXPECT_EQ(count(out, "SELECT count(*) FROM object_ranges WHERE targets_recorded IS NULL OR targets_simulated IS NULL"), 0);
  EXPECT_GT(count(out, "SELECT sum(targets_recorded) FROM object_ranges"), 0);
  SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA journal_mode").getString(), "delete");
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM pragma_foreign_key_check").getInt(), 0);
  // It reads as a report and takes new runs.
  replay_into(out, {{"standstill_1m", 9, StoreLevel::summary}});
  EXPECT_EQ(count(out, "SELECT max(run_id) FROM runs"), 5);
}

TEST_F(ReportMerge, MergingTheSameShardsAgainChangesNothing) {
  const fs::path out = dir_ / "campaign.sqlite";
  const std::vector<std::string> inputs{shard("a.sqlite"), shard("b.sqlite")};
  merge_reports(inputs, out.string());
  const std::string bytes = testing::read_file(out), first = dump(out);
  const auto modified = fs::last_write_time(out);
  const MergeResult again = merge_reports(inputs, out.string());
  // Nothing new: the file is not written at all (and no -wal left; a read-only connection, as
  // dump's, would leave one).
  EXPECT_FALSE(fs::exists(out.string() + "-wal"));
  EXPECT_FALSE(fs::exists(out.string() + "-shm"));
  EXPECT_EQ(testing::read_file(out), bytes);
  EXPECT_EQ(fs::last_write_time(out), modified);
  EXPECT_EQ(dump(out), first);
  EXPECT_TRUE(again.output_existed);
  EXPECT_EQ(again.runs_before, 4);
  EXPECT_EQ(again.added(), 0);
  EXPECT_EQ(again.duplicates.size(), 4u);
  EXPECT_EQ(again.inconsistent_duplicates(), 0);
  EXPECT_EQ(again.runs_after, 4);
  // Each names the run kept in the output.
  EXPECT_EQ(again.duplicates[2].file, inputs[1]);
  EXPECT_EQ(again.duplicates[2].run_id, 1);
  EXPECT_EQ(again.duplicates[2].kept_file, out.string());
  EXPECT_EQ(again.duplicates[2].kept_run_id, 3);
  EXPECT_EQ(again.duplicates[2].output_run_id, 3);
  EXPECT_EQ(again.duplicates[2].recording_name, "front_approach");
  // One shard at a time gives the same.
  const fs::path one_by_one = dir_ / "one_by_one.sqlite";
  merge_reports({inputs[0]}, one_by_one.string());
  merge_reports({inputs[1]}, one_by_one.string());
  merge_reports({inputs[0]}, one_by_one.string());
  EXPECT_EQ(dump(one_by_one), first);
}

TEST_F(ReportMerge, TheSameShardTwiceAndOneRunInTwoShardsAreDuplicates) {
  const fs::path out = dir_ / "campaign.sqlite";
  const std::string a = shard("a.sqlite"), c = (dir_ / "c.sqlite").string();
  // c: a run of shard a again (same recording, seed, store, parameters), and a new one.
  replay_into(c, {{"two_in_one_cell", 1, StoreLevel::summary}, {"two_in_one_cell", 3, StoreLevel::summary}});
  const MergeResult r = merge_reports({a, a, c}, out.string());
  EXPECT_EQ(r.inputs[0].added, 2);
  EXPECT_EQ(r.inputs[1].added, 0);
  EXPECT_EQ(r.inputs[1].duplicates, 2);
  EXPECT_EQ(r.inputs[2].added, 1);
  EXPECT_EQ(r.inputs[2].duplicates, 1);
  ASSERT_EQ(r.duplicates.size(), 3u);
  const MergeDuplicate& d = r.duplicates[2];
  EXPECT_EQ(d.file, c);
  EXPECT_EQ(d.run_id, 1);
  EXPECT_EQ(d.kept_file, a);
  EXPECT_EQ(d.kept_run_id, 2);
  EXPECT_EQ(d.output_run_id, 2);
  EXPECT_EQ(d.recording_name, "two_in_one_cell");
  EXPECT_EQ(d.seed, 1);
  EXPECT_TRUE(d.differences.empty()) << "the same run, the same figures";
  EXPECT_EQ(r.inputs[2].run_ids, (std::vector<std::pair<std::int64_t, std::int64_t>>{{1, 2}, {2, 3}}));
  EXPECT_EQ(r.runs_after, 3);
  EXPECT_EQ(count(out, "SELECT count(*) FROM runs WHERE seed = 3"), 1);
  EXPECT_EQ(count(out, "SELECT count(*) FROM summaries"), 3);
  // A different store level is another run.
  const std::string full = (dir_ / "full.sqlite").string();
  replay_into(full, {{"two_in_one_cell", 1, StoreLevel::full}});
  EXPECT_EQ(merge_reports({full}, out.string()).added(), 1);
}

TEST_F(ReportMerge, ADuplicateWithOtherFiguresIsReportedWithThem) {
  const fs::path out = dir_ / "campaign.sqlite";
  const std::string a = shard("a.sqlite"), changed = shard("a.sqlite", "changed.sqlite");
  exec(changed, "UPDATE summaries SET gospa_mean = 1.25, total_wall_s = total_wall_s + 1 WHERE run_id = 2");
  const MergeResult r = merge_reports({a, changed}, out.string());
  ASSERT_EQ(r.duplicates.size(), 2u);
  EXPECT_TRUE(r.duplicates[0].differences.empty()) << "the timings are no figures";
  ASSERT_EQ(r.duplicates[1].differences.size(), 1u);
  EXPECT_EQ(r.duplicates[1].differences[0].figure, "gospa_mean");
  EXPECT_EQ(r.duplicates[1].differences[0].duplicate, "1.25");
  EXPECT_NE(r.duplicates[1].differences[0].kept, "1.25");
  EXPECT_EQ(r.inconsistent_duplicates(), 1);
  EXPECT_NE(count(out, "SELECT gospa_mean = 1.25 FROM summaries WHERE run_id = 2"), 1) << "the first one is kept";
}

TEST_F(ReportMerge, AnotherSchemaVersionIsRefusedNamingTheFileAndTheOutputStaysAsItWas) {
  const fs::path out = dir_ / "campaign.sqlite";
  merge_reports({shard("a.sqlite")}, out.string());
  const std::string before = dump(out);
  const std::string old = shard("b.sqlite", "shard-3.sqlite");
  const int older = kReportSchemaVersion - 1, newer = kReportSchemaVersion + 1;
  exec(old, fmt::format("PRAGMA user_version = {}", older));
  std::string message = refusal({shard("b.sqlite"), old}, out);
  EXPECT_NE(message.find(fmt::format("{}: report schema version {}, expected {}", old, older, kReportSchemaVersion)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("rcsim report"), std::string::npos) << "says how to migrate it: " << message;
  EXPECT_EQ(dump(out), before);
  EXPECT_TRUE(merge_files(dir_).empty());
  exec(old, fmt::format("PRAGMA user_version = {}", newer));
  message = refusal({old}, out);
  EXPECT_NE(message.find(fmt::format("{}: report schema version {}, expected {}: written by a newer rcsim", old, newer,
                                     kReportSchemaVersion)),
            std::string::npos)
      << message;
  // An output of another version is refused alike.
  exec(out, fmt::format("PRAGMA user_version = {}", older));
  message = refusal({shard("b.sqlite")}, out);
  EXPECT_NE(message.find(fmt::format("{}: report schema version {}, expected {}", out.string(), older,
                                     kReportSchemaVersion)),
            std::string::npos)
      << message;
  EXPECT_EQ(count(out, "PRAGMA user_version"), older);
}

TEST_F(ReportMerge, WhatIsNotAReportIsRefusedNamingTheFile) {
  const fs::path out = dir_ / "campaign.sqlite";
  const fs::path missing = dir_ / "missing.sqlite", empty = dir_ / "empty.sqlite", text = dir_ / "notes.sqlite",
                 foreign = dir_ / "foreign.sqlite", empty_db = dir_ / "empty_db.sqlite";
  std::ofstream(empty.string()).close();
  std::ofstream(text.string()) << "this is no database, only a text file that is long enough to have a header\n";
  exec(foreign, "CREATE TABLE t (x)");  // SQLite creates it
  SQLite::Database(empty_db.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE).exec("PRAGMA user_version = 0");
  const std::vector<std::pair<fs::path, std::string>> cases{
      {missing, "no such report database"},
      {empty, "the database is empty"},
      {empty_db, "the database is empty"},
      {text, "not an SQLite database"},
      {foreign, "not an rcsim report database (application_id 0x0, expected 0x52435352)"},
      {dir_, "not a regular file"}};
  for (const auto& [file, expected] : cases) {
    const std::string message = refusal({shard("a.sqlite"), file.string()}, out);
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(out)) << file;
  }
  EXPECT_TRUE(merge_files(dir_).empty());
}

TEST_F(ReportMerge, InputsAreOnlyRead) {
  const std::string a = shard("a.sqlite");
  const std::string bytes = testing::read_file(a);
  const auto modified = fs::last_write_time(a);
  merge_reports({a}, (dir_ / "campaign.sqlite").string());
  EXPECT_EQ(testing::read_file(a), bytes);
  EXPECT_EQ(fs::last_write_time(a), modified);
  // Also when it has a WAL of committed runs not yet checkpointed (a shard killed after a commit):
  // the merge reads them, and leaves the WAL as it was.
  const std::string live = shard("b.sqlite", "live.sqlite");
  SQLite::Database writer(live, SQLite::OPEN_READWRITE);
  writer.exec("PRAGMA journal_mode = WAL");  // a writer's, as the store opens it (a finished report has none)
  writer.exec("PRAGMA wal_autocheckpoint = 0");
  writer.exec("UPDATE runs SET seed = seed + 100");
  ASSERT_GT(fs::file_size(live + "-wal"), 0u);
  const std::string db_bytes = testing::read_file(live), wal_bytes = testing::read_file(live + "-wal");
  const MergeResult r = merge_reports({live}, (dir_ / "from_wal.sqlite").string());
  EXPECT_EQ(r.added(), 2);
  EXPECT_EQ(count(dir_ / "from_wal.sqlite", "SELECT min(seed) FROM runs"), 101);
  EXPECT_EQ(testing::read_file(live), db_bytes);
  EXPECT_EQ(testing::read_file(live + "-wal"), wal_bytes);
}

TEST_F(ReportMerge, AnExistingOutputsWalIsTakenIn) {
  const fs::path out = dir_ / "campaign.sqlite";
  merge_reports({shard("a.sqlite")}, out.string());
  // A change committed to the output's WAL and not checkpointed, the files left as a killed
  // writer leaves them.
  const fs::path copy = dir_ / "copy.sqlite";
  {
    SQLite::Database writer(out.string(), SQLite::OPEN_READWRITE);
    writer.exec("PRAGMA journal_mode = WAL");  // a writer's, as the store opens it (a finished report has none)
    writer.exec("PRAGMA wal_autocheckpoint = 0");
    writer.exec("UPDATE runs SET recording_name = 'renamed' WHERE run_id = 1");
    fs::copy_file(out, copy);
    fs::copy_file(out.string() + "-wal", copy.string() + "-wal");
  }
  fs::rename(copy, out);
  fs::rename(copy.string() + "-wal", out.string() + "-wal");
  ASSERT_GT(fs::file_size(out.string() + "-wal"), 0u);
  const MergeResult r = merge_reports({shard("b.sqlite")}, out.string());
  EXPECT_EQ(r.runs_after, 4);
  EXPECT_FALSE(fs::exists(out.string() + "-wal")) << "no WAL of the old file beside the new one";
  EXPECT_EQ(count(out, "SELECT count(*) FROM runs WHERE recording_name = 'renamed'"), 1);
  SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
}

ino_t inode(const fs::path& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

TEST_F(ReportMerge, AnExistingOutputIsWrittenInPlaceInOneTransaction) {
  const fs::path out = dir_ / "campaign.sqlite";
  merge_reports({shard("a.sqlite")}, out.string());
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const ino_t before = inode(out);
  const MergeResult r = merge_reports({shard("b.sqlite")}, out.string());
  EXPECT_TRUE(r.output_existed);
  EXPECT_EQ(r.runs_before, 2);
  EXPECT_EQ(r.runs_after, 4);
  EXPECT_EQ(inode(out), before) << "the same file, not a copy renamed over it";
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_FALSE(fs::exists(out.string() + "-wal")) << "checkpointed when the merge closed it";
  EXPECT_TRUE(merge_files(dir_).empty()) << "no temporary file";
  SQLite::Database db(out.string(), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA journal_mode").getString(), "delete");
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM pragma_foreign_key_check").getInt(), 0);
  // The same as merging both into a new report.
  merge_reports({shard("a.sqlite"), shard("b.sqlite")}, (dir_ / "at_once.sqlite").string());
  EXPECT_EQ(dump(out), dump(dir_ / "at_once.sqlite"));
}

TEST_F(ReportMerge, AnEmptyExistingOutputIsMadeAReportInPlace) {
  const fs::path out = dir_ / "campaign.sqlite";
  std::ofstream(out.string()).close();  // as `touch` leaves it
  const ino_t before = inode(out);
  const MergeResult r = merge_reports({shard("a.sqlite")}, out.string());
  EXPECT_FALSE(r.output_existed);
  EXPECT_EQ(r.runs_after, 2);
  EXPECT_EQ(inode(out), before);
  EXPECT_EQ(count(out, "PRAGMA user_version"), kReportSchemaVersion);
  merge_reports({shard("a.sqlite")}, (dir_ / "new.sqlite").string());
  EXPECT_EQ(dump(out), dump(dir_ / "new.sqlite"));
}

// SQLite attaches at most 10 databases and detaches none inside a transaction: the merge into an
// existing report copies its inputs without ATTACH, all in its one transaction; one into a new
// report attaches them one at a time.
TEST_F(ReportMerge, MoreInputsThanSQLiteAttachesAtOnce) {
  const fs::path out = dir_ / "campaign.sqlite";
  merge_reports({shard("a.sqlite")}, out.string());
  std::vector<std::string> inputs;
  for (int k = 1; k <= 12; ++k) {
    inputs.push_back(shard("b.sqlite", fmt::format("b{}.sqlite", k)));
    exec(inputs.back(), fmt::format("UPDATE runs SET seed = seed + {}", 100 * k));  // other runs
  }
  const MergeResult r = merge_reports(inputs, out.string());
  EXPECT_EQ(r.added(), 24);
  EXPECT_EQ(r.runs_after, 26);
  EXPECT_EQ(count(out, "SELECT count(DISTINCT seed) FROM runs"), 25);  // standstill_1m and two_in_one_cell share seed 1
  EXPECT_EQ(count(out, "SELECT count(*) FROM summaries"), 26);
  // Into a new report (each input ATTACHed in turn) the same.
  inputs.insert(inputs.begin(), shard("a.sqlite"));
  merge_reports(inputs, (dir_ / "new.sqlite").string());
  EXPECT_EQ(dump(dir_ / "new.sqlite"), dump(out));
}

// The output is read under its write lock: a writer that holds the lock when the merge begins is
// waited for, and what it commits is in the merged report.
TEST_F(ReportMerge, AMergeWaitsForAWriterOfTheOutputAndKeepsItsWrite) {
  const fs::path out = dir_ / "campaign.sqlite";
  merge_reports({shard("a.sqlite")}, out.string());
  const std::string b = shard("b.sqlite");
  SQLite::Database writer(out.string(), SQLite::OPEN_READWRITE);
  writer.exec("BEGIN IMMEDIATE");
  writer.exec("UPDATE runs SET recording_name = 'written meanwhile' WHERE run_id = 1");
  std::atomic<bool> done{false};
  MergeResult r;
  std::string error;
  std::thread merge([&] {
    try {
      r = merge_reports({b}, out.string());
    } catch (const std::exception& e) {
      error = e.what();
    }
    done = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(done) << "the merge waits for the writer's lock";
  writer.exec("COMMIT");
  merge.join();
  ASSERT_EQ(error, "");
  EXPECT_EQ(r.runs_before, 2);
  EXPECT_EQ(r.runs_after, 4);
  EXPECT_EQ(count(out, "SELECT count(*) FROM runs WHERE recording_name = 'written meanwhile'"), 1);
}

TEST_F(ReportMerge, CampaignsAndCriteriaMustAgree) {
  const std::string campaign = "INSERT INTO campaign VALUES ('drives', '{\"recordings\": [\"a\", \"b\"]}')";
  const std::string criterion = "INSERT INTO criteria VALUES (0, 'gospa_mean_m', 'recording', 'value', 'max', 0.5, 'fail')";
  const std::string a = shard("a.sqlite"), b = shard("b.sqlite");
  exec(a, campaign + ";" + criterion);
  exec(b, "INSERT INTO campaign VALUES ('drives', '{\"recordings\":[\"a\",\"b\"]}');" + criterion);  // the same manifest
  const fs::path out = dir_ / "campaign.sqlite";
  MergeResult r = merge_reports({a, b}, out.string());
  EXPECT_EQ(r.campaign, "drives");
  EXPECT_EQ(r.criteria, 1);
  EXPECT_TRUE(r.campaign_copied);
  EXPECT_EQ(count(out, "SELECT count(*) FROM campaign"), 1);
  EXPECT_EQ(count(out, "SELECT count(*) FROM criteria"), 1);
  // A shard without them joins the campaign.
  r = merge_reports({shard("b.sqlite", "plain.sqlite")}, out.string());
  EXPECT_EQ(r.campaign, "drives");
  EXPECT_FALSE(r.campaign_copied);
  EXPECT_EQ(count(out, "SELECT count(*) FROM criteria"), 1);
  const std::string before = dump(out);
  // Another campaign's shard is refused, against the output or another input.
  const std::string other = shard("b.sqlite", "other.sqlite");
  exec(other, "INSERT INTO campaign VALUES ('night drives', '{}')");
  std::string message = refusal({other}, out);
  EXPECT_NE(message.find(other + ": campaign 'night drives' differs from campaign 'drives' of " + out.string()),
            std::string::npos)
      << message;
  message = refusal({a, other}, dir_ / "new.sqlite");
  EXPECT_NE(message.find(other + ": campaign 'night drives' differs from campaign 'drives' of " + a), std::string::npos)
      << message;
  const std::string manifest = shard("b.sqlite", "manifest.sqlite");
  exec(manifest, "INSERT INTO campaign VALUES ('drives', '{\"recordings\": [\"c\"]}')");
  message = refusal({manifest}, out);
  EXPECT_NE(message.find(manifest + ": the manifest of campaign 'drives' differs from that of " + out.string() +
                         " (field \"recordings\": [\"c\"] against [\"a\",\"b\"])"),
            std::string::npos)
      << "names the first field that differs: " << message;
  const std::string criteria = shard("b.sqlite", "criteria.sqlite");
  exec(criteria, "INSERT INTO criteria VALUES (0, 'gospa_mean_m', 'recording', 'value', 'max', 0.75, 'fail')");
  message = refusal({criteria}, out);
  EXPECT_NE(message.find(criteria + ": its criteria differ from those of " + out.string() +
                         " (1 against 1 criteria; criteria[0]: gospa_mean_m <= 0.75 per recording against "
                         "gospa_mean_m <= 0.5 per recording)"),
            std::string::npos)
      << message;
  // A second criterion more, over the campaign, passed if missing: the first difference is it.
  const std::string more = shard("b.sqlite", "more.sqlite");
  exec(more, criterion + "; INSERT INTO criteria VALUES (1, 'matched_fraction', 'campaign', 'p95', 'min', 0.9, 'pass')");
  message = refusal({more}, out);
  EXPECT_NE(message.find("(2 against 1 criteria; criteria[1]: p95(matched_fraction) >= 0.9 over the campaign, passed "
                         "if missing against none)"),
            std::string::npos)
      << message;
  EXPECT_EQ(dump(out), before);
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
}

TEST_F(ReportMerge, BenchesAreCopiedOnceEach) {
  const std::string a = shard("a.sqlite");
  exec(a, "INSERT INTO bench_runs VALUES (1, 1, 'cpu', '{}', '1.0', '2026-01-01T00:00:00Z');"
          "INSERT INTO bench_rows VALUES (1, 0, 'rec', '0123456789abcdef', 'full', 100, 0.5, 200.0, 0.9, 10, 11, 1.1, "
          "0, 0, 0, 0, NULL, 0)");
  const std::string b = (dir_ / "b_bench.sqlite").string();
  fs::copy_file(a, b);
  exec(b, "UPDATE bench_runs SET created_utc = '2026-01-02T00:00:00Z'");  // another bench
  const fs::path out = dir_ / "campaign.sqlite";
  MergeResult r = merge_reports({a, a, b}, out.string());
  EXPECT_EQ(r.inputs[0].benches_added, 1);
  EXPECT_EQ(r.inputs[1].benches, 1);
  EXPECT_EQ(r.inputs[1].benches_added, 0);
  EXPECT_EQ(r.inputs[2].benches_added, 1);
  EXPECT_EQ(count(out, "SELECT count(*) FROM bench_runs"), 2);
  EXPECT_EQ(count(out, "SELECT count(*) FROM bench_rows"), 2);
  EXPECT_EQ(count(out, "SELECT count(*) FROM bench_rows WHERE bench_id = 2 AND sensor_cycles = 100"), 1);
  r = merge_reports({b}, out.string());
  EXPECT_EQ(r.inputs[0].benches_added, 0);
  EXPECT_EQ(count(out, "SELECT count(*) FROM bench_runs"), 2);
}

std::string host_name() {
  std::array<char, 256> name{};
  ::gethostname(name.data(), name.size() - 1);
  std::string host(name.data());
  for (char& c : host) {
    if (c == '/' || c == '-') c = '_';
  }
  return host;
}

TEST_F(ReportMerge, TemporaryFilesOfKilledMergesAreRemovedAndThoseOfLiveOnesKept) {
  const fs::path out = dir_ / "campaign.sqlite";
  // A pid that is surely gone: a child's, waited for.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string stale = fmt::format(".campaign.sqlite.merge-{}-{}.tmp", host_name(), dead);
  const std::string live = fmt::format(".campaign.sqlite.merge-{}-{}.tmp", host_name(), ::getppid());
  const std::string other_host = fmt::format(".campaign.sqlite.merge-elsewhere-{}.tmp", dead);
  for (const std::string& name : {stale, stale + "-journal", live, other_host}) {
    std::ofstream((dir_ / name).string()) << "half a database";
  }
  const MergeResult r = merge_reports({shard("a.sqlite")}, out.string());
  EXPECT_EQ(r.stale_temporaries_removed, 1);
  std::vector<std::string> left = merge_files(dir_);
  std::sort(left.begin(), left.end());
  std::vector<std::string> expected{live, other_host};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(left, expected);
  EXPECT_EQ(r.runs_after, 2);
}

}  // namespace
}  // namespace rcsim::replay
