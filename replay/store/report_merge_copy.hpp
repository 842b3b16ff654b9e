#pragma once
// How `rcsim merge` (report_merge.cpp) writes: the rows of the runs, benches, campaign and criteria
// its plan picked, copied from each input into the output, and the duplicates' figures compared
// with the kept runs'. Two ways to copy:
//  - rows: from the input (opened read-only) through the application into the output, inside the
//    caller's one transaction, whatever the number of inputs (SQLite attaches at most 10
//    databases and detaches none inside a transaction): a merge into an existing report;
//  - attach: the input ATTACHed, INSERT ... SELECT, a transaction per input; two thirds of the
//    time of `rows` (the rows never leave SQLite), for a private database: a new report's
//    temporary file.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "replay/store/report_merge.hpp"

namespace rcsim::replay::merge_copy {

using IdPairs = std::vector<std::pair<std::int64_t, std::int64_t>>;  // id in the input, id in the output

// What the merge does with one input.
struct MergeStep {
  IdPairs runs, benches;                               // to copy
  bool campaign = false, criteria = false;             // to copy its table campaign, criteria
  std::size_t first_duplicate = 0, end_duplicate = 0;  // its duplicates in MergeResult::duplicates
  bool copies() const { return !runs.empty() || !benches.empty() || campaign || criteria; }
  bool compares() const { return first_duplicate != end_duplicate; }
};

enum class Copying { rows, attach };

// The output as the merge writes it: the report's tables by what a merge does with them, their
// columns, and the copying of an input's rows into it.
class MergeTarget {
 public:
  // `db`: the output's connection, holding a report's schema; with Copying::rows in the caller's
  // transaction, with Copying::attach outside any. A table the merge does not know how to merge
  // is a std::logic_error (a test keeps them none).
  MergeTarget(SQLite::Database& db, const std::string& output, Copying copying);

  // Copies from the input what the step says, then compares its duplicates' figures with those of
  // the runs kept for them (in the output, copied there earlier in this merge or before).
  void add(const std::string& file, const MergeStep& step, std::vector<MergeDuplicate>& duplicates);

 private:
  void check_columns(SQLite::Database& input, const std::string& file) const;
  // The rows of `table` whose `key` column holds an id of `ids`, each under its new id; every row
  // when `key` is empty. In the input's order.
  void copy_rows(SQLite::Database& input, const std::string& table, const std::string& key, const IdPairs& ids);
  // What the step copies, from the input ATTACHed as `src`, in a transaction of its own.
  void copy_attached(const std::string& file, const MergeStep& step);
  std::string insert_select_sql(const std::string& table, const std::string& key, const std::string& map) const;

  SQLite::Database& db_;
  Copying copying_;
  ReportTables tables_;
  std::map<std::string, std::vector<std::string>> columns_;
};

// The summaries figures (timings aside) in which a duplicate (run d.run_id of `input`) differs from
// its kept run (run d.output_run_id of `output`), into d.differences.
void compare_summaries(SQLite::Database& output, SQLite::Database& input, MergeDuplicate& d);

}  // namespace rcsim::replay::merge_copy
