// How `rcsim merge` writes (replay/store/report_merge_copy.hpp): both ways of copying (rows in
// the caller's transaction, an ATTACHed input) copy exactly the runs and benches a step names,
// every value as stored (a zero-length BLOB stays one, never NULL), under their new ids, and the
// campaign and criteria; a duplicate's summaries figures are compared with its kept run's, the
// timings aside; an output table merge does not know, an input whose header changed or whose
// columns differ are refused, naming them.
#include "replay/store/report_merge_copy.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "replay/evaluate/hand_bench_rows.hpp"
#include "replay/store/bench_store.hpp"
#include "replay/store/campaign_store.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::report_merge_copy_test {

namespace fs = std::filesystem;
using replay::MergeDuplicate;
using replay::merge_copy::compare_summaries;
using replay::merge_copy::Copying;
using replay::merge_copy::MergeStep;
using replay::merge_copy::MergeTarget;

// Every row of `table` whose `key` is `id`, the key left out, each value as quote() writes it
// (type and value: X'' for an empty BLOB, NULL for NULL), in order.
std::string rows_of(SQLite::Database& db, const std::string& table, const std::string& key, std::int64_t id) {
  std::vector<std::string> columns;
  SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?)");
  info.bind(1, table);
  while (info.executeStep()) {
    if (info.getColumn(0).getString() != key) columns.push_back("quote(" + info.getColumn(0).getString() + ")");
  }
  std::string select = "SELECT " + columns[0];
  for (std::size_t c = 1; c < columns.size(); ++c) select += " || ',' || " + columns[c];
  SQLite::Statement q(db, fmt::format("{} FROM {} WHERE {} = ? ORDER BY 1", select, table, key));
  q.bind(1, id);
  std::string text;
  while (q.executeStep()) text += q.getColumn(0).getString() + '\n';
  return text;
}

// A run's rows in every table that refers to a run.
std::string run_rows(SQLite::Database& db, std::int64_t run_id) {
  std::string text;
  for (const std::string& table : replay::classify_report_tables(db).run_scoped) {
    text += "== " + table + '\n' + rows_of(db, table, "run_id", run_id);
  }
  return text;
}

class ReportMergeCopy : public testing::ScratchDirTest {
 protected:
  ReportMergeCopy() : ScratchDirTest("report_merge_copy") {}

  // A report with run 1 (seed 1, full store, one column of its cycle blocks made zero-length
  // BLOBs), run 2 (seed 2, summary store), bench 1 and the campaign q3 with one criterion.
  std::string make_input(const std::string& name) {
    const std::string path = (dir_ / name).string();
    const auto db = replay::open_report_database(path, true);
    for (const std::uint64_t seed : {1u, 2u}) {
      replay::ReplayOptions options;
      options.seed = seed;
      replay::ReportWriter writer(*db, seed == 1 ? replay::StoreLevel::full : replay::StoreLevel::summary);
      replay::replay_recording_dir(testing::kBundledRecordings / "front_approach", options, writer);
    }
    db->exec("UPDATE cycle_blocks SET merge_matched = X'' WHERE run_id = 1");
    replay::store_bench(*db, replay::BenchOptions{}, "m", replay::hand_rows());
    replay::claim_campaign(*db, "q3", "{}", {{"gospa_mean_m", "recording", "value", "max", 1.5, "fail"}});
    return path;
  }

  // A copy of `from` as `name`, changed by `sql`.
  std::string changed_copy(const std::string& from, const std::string& name, const std::string& sql) {
    const std::string path = (dir_ / name).string();
    fs::copy_file(from, path);
    SQLite::Database(path, SQLite::OPEN_READWRITE).exec(sql);
    return path;
  }

  // Adds the step with a MergeTarget copying as `copying`, as merge_reports does: rows inside one
  // transaction, attach outside any.
  void add(replay::ReportDatabase& out, Copying copying, const std::string& input, const MergeStep& step,
           std::vector<MergeDuplicate>& duplicates) {
    if (copying == Copying::attach) {
      MergeTarget(out, "out.sqlite", copying).add(input, step, duplicates);
      return;
    }
    SQLite::Transaction transaction(out);
    out.exec("PRAGMA defer_foreign_keys = ON");
    MergeTarget(out, "out.sqlite", copying).add(input, step, duplicates);
    transaction.commit();
  }
};

TEST_F(ReportMergeCopy, BothWaysCopyTheStepsRunsBenchesAndCampaignAsStored) {
  const std::string input = make_input("in.sqlite");
  SQLite::Database in(input, SQLite::OPEN_READONLY);
  const std::string run_1 = run_rows(in, 1);
  EXPECT_NE(run_1.find("X''"), std::string::npos) << "the zero-length BLOBs are there to copy";
  const std::string bench_1 = rows_of(in, "bench_rows", "bench_id", 1) + rows_of(in, "bench_runs", "bench_id", 1);
  for (const Copying copying : {Copying::rows, Copying::attach}) {
    SCOPED_TRACE(copying == Copying::rows ? "rows" : "attach");
    const auto out = replay::open_report_database((dir_ / (copying == Copying::rows ? "rows.sqlite" : "attach.sqlite")).string(), true);
    MergeStep step;
    step.runs = {{1, 7}};
    step.benches = {{1, 3}};
    step.campaign = step.criteria = true;
    std::vector<MergeDuplicate> duplicates;
    add(*out, copying, input, step, duplicates);
    EXPECT_EQ(out->execAndGet("SELECT group_concat(run_id) FROM runs").getString(), "7") << "run 2 not named";
    EXPECT_EQ(run_rows(*out, 7), run_1);
    EXPECT_EQ(out->execAndGet("SELECT count(*) FROM cycle_blocks WHERE typeof(merge_matched) = 'blob' AND "
                              "length(merge_matched) = 0")
                  .getInt(),
              in.execAndGet("SELECT count(*) FROM cycle_blocks WHERE run_id = 1").getInt());
    EXPECT_EQ(rows_of(*out, "bench_rows", "bench_id", 3) + rows_of(*out, "bench_runs", "bench_id", 3), bench_1);
    EXPECT_EQ(out->execAndGet("SELECT count(*) FROM bench_runs").getInt(), 1);
    EXPECT_EQ(replay::read_campaign_name(*out), std::optional<std::string>("q3"));
    ASSERT_EQ(replay::read_criterion_rows(*out).size(), 1u);
    EXPECT_EQ(replay::read_criterion_rows(*out)[0].threshold, 1.5);
    EXPECT_TRUE(duplicates.empty());
    EXPECT_EQ(out->execAndGet("SELECT count(*) FROM pragma_foreign_key_check").getInt(), 0);
  }
}

TEST_F(ReportMergeCopy, ADuplicatesFiguresAreComparedTheTimingsAside) {
  const std::string input = make_input("in.sqlite");
  const auto out = replay::open_report_database((dir_ / "out.sqlite").string(), true);
  MergeStep copy;
  copy.runs = {{1, 1}};
  std::vector<MergeDuplicate> none;
  add(*out, Copying::rows, input, copy, none);
  const std::string kept_gospa = fmt::format("{}", out->execAndGet("SELECT gospa_mean FROM summaries").getDouble());

  // The same run stored again with another GOSPA and other timings: found by comparing, not copied.
  const std::string again = changed_copy(input, "again.sqlite", "UPDATE summaries SET gospa_mean = 1.25, "
                                         "total_wall_s = total_wall_s + 1, simulate_cpu_s = 0 WHERE run_id = 1");
  std::vector<MergeDuplicate> duplicates(2);
  duplicates[0].run_id = 1;
  duplicates[0].output_run_id = 1;
  duplicates[1].run_id = 99;  // neither has a row: nothing to compare
  duplicates[1].output_run_id = 99;
  MergeStep compare;
  compare.first_duplicate = 0;
  compare.end_duplicate = 2;
  EXPECT_FALSE(compare.copies());
  EXPECT_TRUE(compare.compares());
  add(*out, Copying::rows, again, compare, duplicates);
  ASSERT_EQ(duplicates[0].differences.size(), 1u);
  EXPECT_EQ(duplicates[0].differences[0].figure, "gospa_mean");
  EXPECT_EQ(duplicates[0].differences[0].kept, kept_gospa);
  EXPECT_EQ(duplicates[0].differences[0].duplicate, "1.25");
  EXPECT_TRUE(duplicates[1].differences.empty());
  EXPECT_EQ(out->execAndGet("SELECT count(*) FROM runs").getInt(), 1);

  // A duplicate without its row of summaries.
  const std::string rowless = changed_copy(input, "rowless.sqlite", "DELETE FROM summaries WHERE run_id = 1");
  SQLite::Database lacking(rowless, SQLite::OPEN_READONLY);
  MergeDuplicate d;
  d.run_id = 1;
  d.output_run_id = 1;
  compare_summaries(*out, lacking, d);
  ASSERT_EQ(d.differences.size(), 1u);
  EXPECT_EQ(d.differences[0].figure, "summaries");
  EXPECT_EQ(d.differences[0].kept, "a row");
  EXPECT_EQ(d.differences[0].duplicate, "no row");
}

TEST_F(ReportMergeCopy, WhatCannotBeMergedIsRefusedNamingIt) {
  const std::string input = make_input("in.sqlite");
  const auto out = replay::open_report_database((dir_ / "out.sqlite").string(), true);
  MergeStep step;
  step.runs = {{1, 1}};
  std::vector<MergeDuplicate> duplicates;
  const auto refusal = [&](const std::string& file) -> std::string {
    try {
      add(*out, Copying::rows, file, step, duplicates);
    } catch (const InputError& e) {
      return e.what();
    }
    return "copied";
  };
  const std::string older = changed_copy(input, "older.sqlite", "PRAGMA user_version = 5");
  EXPECT_EQ(refusal(older), older + ": changed during the merge (application_id 0x52435352, report schema version 5, "
                                    "expected 0x52435352 and 6)");
  const std::string wider = changed_copy(input, "wider.sqlite", "ALTER TABLE criteria ADD COLUMN note TEXT");
  EXPECT_EQ(refusal(wider), wider + ": table criteria has the columns (criterion, figure, scope, statistic, bound, "
                                    "threshold, if_missing, note), the output (criterion, figure, scope, statistic, "
                                    "bound, threshold, if_missing): not a report of this rcsim's schema");
  EXPECT_EQ(out->execAndGet("SELECT count(*) FROM runs").getInt(), 0) << "refused before copying";
  // A table of the output that a merge would not know what to do with.
  out->exec("CREATE TABLE notes (text TEXT)");
  try {
    MergeTarget(*out, "out.sqlite", Copying::attach);
    ADD_FAILURE() << "an unknown table was accepted";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "out.sqlite: rcsim merge does not know how to merge the table(s) notes");
  }
}

}  // namespace rcsim::report_merge_copy_test
