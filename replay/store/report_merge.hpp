#pragma once
// `rcsim merge SHARD.sqlite... -o CAMPAIGN.sqlite` (docs/merge.md): the runs of many report
// databases, a campaign's shards, copied into one. Runs get new ids in the output; a run whose
// identity (run_identity.hpp) is already in the output, or earlier in the merge, is a duplicate
// and is not copied again, so merging the same shards twice changes nothing. The inputs are only
// read. An existing output is written in one transaction holding its write lock from before it is
// read; a missing one is built in a temporary file beside it and moved into place if no output
// appeared meanwhile. A merge that fails or is killed leaves the output as it was, and a process
// writing the output during a merge loses nothing.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rcsim::replay {

// The report database's tables by what a merge does with them (read from the schema, so that a
// table added later is not forgotten).
struct ReportTables {
  std::vector<std::string> run_scoped;  // every table with a run_id column, `runs` first: copied per run
  std::vector<std::string> bench;       // bench_runs, bench_rows: copied per bench
  std::vector<std::string> campaign;    // campaign, criteria: must agree, copied once
  std::vector<std::string> unknown;     // none of these: a merge refuses to run (tested empty)
};
ReportTables classify_report_tables(SQLite::Database& db);

// A run not copied because a run of the same identity was kept.
struct MergeDuplicate {
  std::string file;                // the input holding it
  std::int64_t run_id = 0;         // its id there
  std::string kept_file;           // where the kept run came from: the output as it was, or an input
  std::int64_t kept_run_id = 0;    // its id there
  std::int64_t output_run_id = 0;  // its id in the output
  std::string recording_name;
  std::int64_t seed = 0;
  std::string identity;  // RunIdentity::key()
  // The summaries figures (timings aside) in which it differs from the kept run: the same run
  // gave other figures, a real inconsistency. Empty when they agree.
  struct Difference {
    std::string figure, kept, duplicate;
  };
  std::vector<Difference> differences;
};

struct MergeInput {
  std::string file;
  long long runs = 0;        // runs the input holds
  long long added = 0;       // copied into the output
  long long duplicates = 0;  // not copied
  long long benches = 0, benches_added = 0;  // benches held, and copied (not exact duplicates)
  // Every run of the input: (its id there, the id of it or of the run kept for it in the output).
  std::vector<std::pair<std::int64_t, std::int64_t>> run_ids;
};

struct MergeResult {
  std::string output;
  bool output_existed = false;  // with runs or benches to keep
  long long runs_before = 0;    // runs the output held before
  long long runs_after = 0;
  std::vector<MergeInput> inputs;
  std::vector<MergeDuplicate> duplicates;
  std::string campaign;        // the campaign's name, empty if none
  long long criteria = 0;      // rows of the table criteria in the output
  bool campaign_copied = false;  // campaign or criteria copied from an input
  int stale_temporaries_removed = 0;  // temporary files of killed merges into this output

  long long runs_merged() const;  // runs of all inputs
  long long added() const;
  long long inconsistent_duplicates() const;  // duplicates whose figures differ from the kept run's
};

// Merges the inputs, in order, into the output (created if missing). Refuses, naming the file,
// an input or output that is missing, not SQLite, empty, not an rcsim report, or of another
// schema version than kReportSchemaVersion; and inputs whose campaign or criteria disagree with
// each other or with the output's. Any refusal or failure leaves the output as it was. Waits up to
// 60 s for another process's write into the output (a replay, another merge) to end.
MergeResult merge_reports(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace rcsim::replay
