// `rcsim merge` (docs/merge.md). First every input is opened read-only and checked (an rcsim
// report of the current schema version), and what the merge needs of it read: the identities of
// its runs, its benches, its campaign and criteria (report_merge_read.cpp). Then
//  - into an existing output: the output is opened read-write and its write lock taken (BEGIN
//    IMMEDIATE) before its own snapshot is read; the campaigns and criteria are checked to agree,
//    the plan is made against that snapshot (which runs and benches are new, which are
//    duplicates, their ids in the output), and the new rows are copied from each input into the
//    output in that same transaction (report_merge_copy.cpp), then committed. SQLite's journal makes
//    it all or nothing: a refusal, a failure or a kill at any moment leaves the output as it was.
//    A process writing the output meanwhile (a replay into it) waits for the lock or gives up
//    ("database is locked"); what it committed is never lost, since the output is read under the
//    lock. With nothing new to add the transaction is rolled back: the file is not written;
//  - into a missing output: the new report is built in a temporary file beside it,
//    `.NAME.merge-HOST-PID.tmp`, with no journal and no syncs, synced once and moved into place
//    unless an output appeared meanwhile, which is never replaced (report_merge_files.cpp); a
//    later merge removes the temporary files of merges that died.
#include "replay/store/report_merge.hpp"

#include <fcntl.h>
#include <sqlite3.h>

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>
#include <stdexcept>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "replay/store/report_merge_copy.hpp"
#include "replay/store/report_merge_files.hpp"
#include "replay/store/report_merge_read.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay {

namespace {

namespace fs = std::filesystem;
using merge_copy::MergeStep;
using merge_copy::MergeTarget;
using merge_read::CampaignAgreement;
using merge_read::check_header;
using merge_read::Header;
using merge_read::Snapshot;
using merge_read::StoredRun;

const std::set<std::string> kBenchTables{"bench_runs", "bench_rows"};
const std::set<std::string> kCampaignTables{"campaign", "criteria"};

// How long a merge waits for the write lock of an existing output: a replay storing a run into
// it, or another merge, holds it for the length of one transaction (one run, one merge). Longer,
// the merge gives up, "database is locked", the output as it was.
constexpr int kOutputBusyTimeoutMs = 60000;

// Where the run kept for an identity came from.
struct KeptRun {
  std::string file;
  std::int64_t run_id = 0, output_run_id = 0;
};

// What the merge will do, decided from the snapshots (the output's read under its write lock)
// before anything is written.
struct Plan {
  std::vector<MergeStep> inputs;
  bool writes() const {
    return std::any_of(inputs.begin(), inputs.end(), [](const MergeStep& step) { return step.copies(); });
  }
};

Plan make_plan(const Snapshot& output, const std::vector<Snapshot>& inputs, MergeResult& result) {
  Plan plan;
  std::map<std::string, KeptRun> kept;  // by identity key; the first of each is kept
  std::int64_t next_run_id = 1, next_bench_id = 1;
  for (const StoredRun& run : output.runs) {
    kept.emplace(run.key, KeptRun{output.file, run.run_id, run.run_id});
    next_run_id = std::max(next_run_id, run.run_id + 1);
  }
  std::set<std::string> benches;
  for (const auto& [id, fingerprint] : output.benches) {
    benches.insert(fingerprint);
    next_bench_id = std::max(next_bench_id, id + 1);
  }
  bool has_campaign = output.campaign.campaign.has_value(), has_criteria = !output.campaign.criteria_exact.empty();
  for (const Snapshot& input : inputs) {
    MergeStep& step = plan.inputs.emplace_back();
    MergeInput& counts = result.inputs.emplace_back();
    counts.file = input.file;
    counts.runs = static_cast<long long>(input.runs.size());
    step.first_duplicate = result.duplicates.size();
    for (const StoredRun& run : input.runs) {
      const auto [it, added] = kept.emplace(run.key, KeptRun{input.file, run.run_id, next_run_id});
      if (added) {
        step.runs.emplace_back(run.run_id, next_run_id++);
        ++counts.added;
      } else {
        MergeDuplicate& d = result.duplicates.emplace_back();
        d.file = input.file;
        d.run_id = run.run_id;
        d.kept_file = it->second.file;
        d.kept_run_id = it->second.run_id;
        d.output_run_id = it->second.output_run_id;
        d.recording_name = run.recording_name;
        d.seed = run.seed;
        d.identity = run.key;
        ++counts.duplicates;
      }
      counts.run_ids.emplace_back(run.run_id, it->second.output_run_id);
    }
    step.end_duplicate = result.duplicates.size();
    for (const auto& [id, fingerprint] : input.benches) {
      ++counts.benches;
      if (!benches.insert(fingerprint).second) continue;  // an exact duplicate
      step.benches.emplace_back(id, next_bench_id++);
      ++counts.benches_added;
    }
    // Checked to agree with the output's and each other's: copied once, from the first that has them.
    step.campaign = !has_campaign && input.campaign.campaign.has_value();
    step.criteria = !has_criteria && !input.campaign.criteria_exact.empty();
    has_campaign = has_campaign || step.campaign;
    has_criteria = has_criteria || step.criteria;
    result.campaign_copied = result.campaign_copied || step.campaign || step.criteria;
  }
  return plan;
}

// The campaigns and criteria checked to agree (the output's first), and the plan.
Plan plan_merge(const Snapshot& output, const std::vector<Snapshot>& inputs, MergeResult& result) {
  CampaignAgreement agreement;
  agreement.check(output.campaign, output.file);
  for (const Snapshot& input : inputs) agreement.check(input.campaign, input.file);
  Plan plan = make_plan(output, inputs, result);
  result.campaign = output.campaign.campaign ? output.campaign.campaign->first : "";
  result.criteria = static_cast<long long>(output.campaign.criteria_exact.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (plan.inputs[i].campaign) result.campaign = inputs[i].campaign.campaign->first;
    if (plan.inputs[i].criteria) result.criteria = static_cast<long long>(inputs[i].campaign.criteria_exact.size());
  }
  return plan;
}

// Copies and compares what the plan says, through the output's connection.
void fill(SQLite::Database& db, const std::string& output, const std::vector<Snapshot>& inputs, const Plan& plan,
          merge_copy::Copying copying, MergeResult& result) {
  MergeTarget target(db, output, copying);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const MergeStep& step = plan.inputs[i];
    if (!step.copies() && !step.compares()) continue;
    try {
      target.add(inputs[i].file, step, result.duplicates);
    } catch (const SQLite::Exception& e) {
      throw InputError(inputs[i].file, "", fmt::format("cannot merge into {}: {}", output, e.what()));
    }
  }
  result.runs_after = db.execAndGet("SELECT count(*) FROM main.runs").getInt64();
}

// Into the existing output, in one transaction holding its write lock from before it is read.
void merge_in_place(const std::string& output, const std::vector<Snapshot>& inputs, MergeResult& result) {
  merge_read::check_regular_file(output);
  try {
    SQLite::Database db(output, SQLite::OPEN_READWRITE);
    db.setBusyTimeout(kOutputBusyTimeoutMs);
    // Another program's database, or another version's report, is refused before it is touched.
    // Its journal as it is: a finished report's rollback journal (or a live one's WAL) makes the
    // transaction all or nothing alike, and a merge that adds nothing leaves the file unwritten.
    check_header(db, output);
    db.exec("PRAGMA foreign_keys = ON");
    db.exec("PRAGMA synchronous = FULL");  // the commit synced: durable as soon as the merge says so
    db.exec("PRAGMA cache_size = -32768");
    SQLite::Transaction transaction(db, SQLite::TransactionBehavior::IMMEDIATE);
    // foreign_keys cannot change inside a transaction; checked at the commit instead of per row
    // (the runs are copied before the rows that refer to them anyway).
    db.exec("PRAGMA defer_foreign_keys = ON");
    Snapshot snapshot{output, {}, {}, {}};
    const Header header = check_header(db, output);  // again, under the lock
    if (header == Header::report) {
      snapshot = merge_read::read_snapshot(db, output);
      result.output_existed = true;
      result.runs_before = static_cast<long long>(snapshot.runs.size());
    }
    const Plan plan = plan_merge(snapshot, inputs, result);
    if (header == Header::empty) create_report_schema(db);  // an empty output is made a report
    fill(db, output, inputs, plan, merge_copy::Copying::rows, result);
    if (header == Header::empty || plan.writes()) {
      transaction.commit();
      // A finished report needs no -shm to be read (read-only storage): a rollback journal, unless
      // another connection has it open (then it stays as it is, and that one switches it).
      try {
        db.setBusyTimeout(0);
        db.exec("PRAGMA journal_mode = DELETE");
      } catch (const SQLite::Exception&) {
      }
    }
    // else rolled back: nothing new, the output not written
  } catch (const SQLite::Exception& e) {
    if (e.getErrorCode() == SQLITE_NOTADB) merge_read::throw_named(e, output);
    if (e.getErrorCode() == SQLITE_BUSY) {
      throw InputError(output, "", fmt::format("another process kept it locked for {} s ({}): nothing merged; merge "
                                               "again when it is done",
                                               kOutputBusyTimeoutMs / 1000, e.what()));
    }
    throw InputError(output, "", std::string("cannot merge into it: ") + e.what());
  }
}

// Into a missing output: built in a temporary file, moved into place if no output appeared.
void merge_into_new(const fs::path& output_path, const std::vector<Snapshot>& inputs, MergeResult& result) {
  const std::string output = output_path.string();
  const Plan plan = plan_merge(Snapshot{output, {}, {}, {}}, inputs, result);
  merge_files::TemporaryDatabase temporary(merge_files::temporary_path(output_path));
  try {
    SQLite::Database db(temporary.path().string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    // Private until moved into place: a crash discards it whole, so no journal on disk and no
    // syncs while filling; it is synced once before the move.
    db.exec("PRAGMA journal_mode = MEMORY");
    db.exec("PRAGMA synchronous = OFF");
    db.exec("PRAGMA foreign_keys = ON");  // checked at each input's commit (defer_foreign_keys)
    db.exec("PRAGMA cache_size = -32768");
    db.exec("PRAGMA temp_store = MEMORY");
    {
      SQLite::Transaction transaction(db);
      create_report_schema(db);
      transaction.commit();
    }
    // Each input ATTACHed and copied with INSERT ... SELECT in a transaction of its own: the
    // fastest copy, for a file nobody else sees yet.
    fill(db, output, inputs, plan, merge_copy::Copying::attach, result);
    // A finished report like every other: a rollback journal, readable without a -shm.
    if (db.execAndGet("PRAGMA journal_mode = DELETE").getString() != "delete") {
      throw InputError(output, "", "cannot set the merged report's journal");
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(output, "", std::string("cannot write the merged report: ") + e.what());
  }
  merge_files::fsync_path(temporary.path(), O_RDONLY, output);
  merge_files::install_new(temporary.path(), output_path);
  temporary.installed();
}

}  // namespace

ReportTables classify_report_tables(SQLite::Database& db) {
  ReportTables tables;
  // In the order they were created (runs first), the report's own tables only.
  SQLite::Statement q(db,
                      "SELECT name, EXISTS (SELECT 1 FROM pragma_table_info(s.name) WHERE name = 'run_id') FROM "
                      "sqlite_schema AS s WHERE type = 'table' AND name NOT LIKE 'sqlite\\_%' ESCAPE '\\' ORDER BY rowid");
  while (q.executeStep()) {
    const std::string name = q.getColumn(0).getString();
    if (q.getColumn(1).getInt() != 0) {
      tables.run_scoped.push_back(name);
    } else if (kBenchTables.count(name) != 0) {
      tables.bench.push_back(name);
    } else if (kCampaignTables.count(name) != 0) {
      tables.campaign.push_back(name);
    } else {
      tables.unknown.push_back(name);
    }
  }
  const auto runs = std::find(tables.run_scoped.begin(), tables.run_scoped.end(), "runs");
  if (runs != tables.run_scoped.end()) std::rotate(tables.run_scoped.begin(), runs, runs + 1);
  // bench_runs before bench_rows (the rows refer to it)
  std::sort(tables.bench.begin(), tables.bench.end(),
            [](const auto& a, const auto& b) { return a == "bench_runs" && b != "bench_runs"; });
  return tables;
}

long long MergeResult::runs_merged() const {
  long long n = 0;
  for (const auto& input : inputs) n += input.runs;
  return n;
}

long long MergeResult::added() const {
  long long n = 0;
  for (const auto& input : inputs) n += input.added;
  return n;
}

long long MergeResult::inconsistent_duplicates() const {
  return std::count_if(duplicates.begin(), duplicates.end(), [](const auto& d) { return !d.differences.empty(); });
}

MergeResult merge_reports(const std::vector<std::string>& inputs, const std::string& output) {
  if (inputs.empty()) throw std::invalid_argument("rcsim merge: no input report");
  MergeResult result;
  result.output = output;
  const fs::path output_path(output);
  std::error_code error;
  if (!output_path.parent_path().empty() && !fs::is_directory(output_path.parent_path(), error)) {
    throw InputError(output, "", "no such directory");
  }
  // A symbolic link (a loop too) or a device is refused before anything is read or written.
  check_output_file(output_path);
  result.stale_temporaries_removed = merge_files::remove_stale_temporaries(output_path);
  // Every input checked, and read, before the output is touched.
  std::vector<Snapshot> snapshots;
  snapshots.reserve(inputs.size());
  for (const std::string& input : inputs) {
    Header header = Header::empty;
    const auto db = merge_read::open_input(input, header);
    if (header == Header::empty) throw InputError(input, "", "the database is empty: no replay has been stored in it");
    snapshots.push_back(merge_read::read_snapshot(*db, input));
  }
  if (fs::exists(output_path, error)) {
    merge_in_place(output, snapshots, result);
  } else {
    merge_into_new(output_path, snapshots, result);
  }
  return result;
}

}  // namespace rcsim::replay
