// `rcsim merge` (docs/merge.md). Two passes:
//  1. every input is opened read-only and checked (an rcsim report of the current schema
//     version; campaign and criteria agreeing), and the identities of its runs and its benches
//     are read; from them a plan: which runs and benches are new, which are duplicates, and their
//     ids in the output. With nothing new the output is left as it is (only read, to compare the
//     duplicates' figures);
//  2. the output is built in a temporary file beside it, `.NAME.merge-HOST-PID.tmp`: a copy of
//     the existing output made with SQLite's backup API (which reads through its WAL), then each
//     input ATTACHed read-only and its new runs copied table by table with INSERT ... SELECT;
//     the file is set to WAL like every report, closed, fsynced and renamed over the output, and
//     the directory fsynced.
// Until the rename the output is untouched, so a refusal, a failure or a kill at any moment leaves
// it as it was; a later merge removes the temporary files of merges that died. The files
// themselves (the temporary output, syncs, read-only URIs) are handled in report_merge_files.cpp.
#include "replay/store/report_merge.hpp"

#include <SQLiteCpp/Backup.h>
#include <fcntl.h>
#include <sqlite3.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>

#include "common/input_error.hpp"
#include "replay/store/report_merge_files.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay {

namespace {

namespace fs = std::filesystem;
using merge_files::file_state;
using merge_files::FileState;
using merge_files::fsync_path;
using merge_files::read_only_uri;
using merge_files::remove_stale_temporaries;
using merge_files::temporary_path;
using merge_files::TemporaryDatabase;

const std::set<std::string> kBenchTables{"bench_runs", "bench_rows"};
const std::set<std::string> kCampaignTables{"campaign", "criteria"};
// The summaries columns that time a replay on its machine: two runs of one identity differ there.
const std::set<std::string> kTimingColumns{"simulate_cpu_s", "total_wall_s"};

std::string quoted(const std::string& identifier) {
  std::string out = "\"";
  for (const char c : identifier) {
    out += c;
    if (c == '"') out += '"';
  }
  return out + '"';
}

std::vector<std::string> table_columns(SQLite::Database& db, const std::string& schema, const std::string& table) {
  SQLite::Statement q(db, "SELECT name FROM pragma_table_info(?, ?) ORDER BY cid");
  q.bind(1, table);
  q.bind(2, schema);
  std::vector<std::string> columns;
  while (q.executeStep()) columns.push_back(q.getColumn(0).getString());
  return columns;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

// A value as a person reads it; reals in the shortest text that reads back to the same double.
std::string display(const SQLite::Column& v) {
  switch (v.getType()) {
    case SQLITE_INTEGER: return std::to_string(v.getInt64());
    case SQLITE_FLOAT: return fmt::format("{}", v.getDouble());
    case SQLITE_TEXT: return v.getString();
    case SQLITE_BLOB: return fmt::format("<{} bytes>", v.getBytes());
    default: return "NULL";
  }
}

// A value exactly, with its type: equal texts are equal values.
std::string exact(const SQLite::Column& v) {
  if (v.getType() != SQLITE_BLOB) return fmt::format("{}{}", v.getType(), display(v));
  const auto* bytes = static_cast<const unsigned char*>(v.getBlob());
  std::string out = "b";
  for (int i = 0; i < v.getBytes(); ++i) out += fmt::format("{:02x}", bytes[i]);
  return out;
}

std::string row_exact(SQLite::Statement& q) {
  std::string out;
  for (int c = 0; c < q.getColumnCount(); ++c) out += exact(q.getColumn(c)) + '\x1f';
  return out;
}

std::string row_display(SQLite::Statement& q) {
  std::vector<std::string> values;
  for (int c = 0; c < q.getColumnCount(); ++c) values.push_back(display(q.getColumn(c)));
  return join(values, " ");
}

enum class Header { empty, report };

// Refuses, naming the file, what is not an rcsim report of this schema version.
Header check_header(SQLite::Database& db, const std::string& path) {
  const int application_id = db.execAndGet("PRAGMA application_id").getInt();
  const int user_version = db.execAndGet("PRAGMA user_version").getInt();
  const int tables = db.execAndGet("SELECT count(*) FROM sqlite_schema").getInt();
  if (application_id == 0 && user_version == 0 && tables == 0) return Header::empty;
  if (application_id != kReportApplicationId) {
    throw InputError(path, "", fmt::format("not an rcsim report database (application_id {:#x}, expected {:#x})",
                                           static_cast<std::uint32_t>(application_id), kReportApplicationId));
  }
  if (user_version < kReportSchemaVersion) {
    throw InputError(path, "", fmt::format("report schema version {}, expected {}; open it once with `rcsim report {} "
                                           "-o REPORT.html` to migrate it, then merge again",
                                           user_version, kReportSchemaVersion, path));
  }
  if (user_version != kReportSchemaVersion) {
    throw InputError(path, "", fmt::format("report schema version {}, expected {}: written by a newer rcsim",
                                           user_version, kReportSchemaVersion));
  }
  return Header::report;
}

// An existing database opened as flags say, its header checked; SQLite's failures named by file.
std::unique_ptr<SQLite::Database> open_existing(const std::string& path, int flags, Header& header) {
  std::error_code error;
  if (!fs::exists(path, error)) throw InputError(path, "", "no such report database");
  if (!fs::is_regular_file(path, error)) throw InputError(path, "", "not a regular file");
  try {
    const bool read_only = (flags & SQLite::OPEN_READONLY) != 0;
    auto db = std::make_unique<SQLite::Database>(read_only ? read_only_uri(path) : path,
                                                 read_only ? flags | SQLite::OPEN_URI : flags);
    db->setBusyTimeout(5000);
    header = check_header(*db, path);
    return db;
  } catch (const SQLite::Exception& e) {
    if (e.getErrorCode() == SQLITE_NOTADB) throw InputError(path, "", "not an SQLite database (file is not a database)");
    throw InputError(path, "", std::string("cannot read as a report database: ") + e.what());
  }
}

// The campaign a database belongs to and its criteria (schema v5), as stored.
struct CampaignRows {
  std::optional<std::pair<std::string, std::string>> campaign;  // name, manifest
  std::vector<std::string> criteria_exact, criteria_display;    // rows by criterion
};

CampaignRows read_campaign(SQLite::Database& db, const std::string& schema, const std::string& path) {
  CampaignRows rows;
  SQLite::Statement campaign(db, fmt::format("SELECT name, manifest FROM {}.campaign", quoted(schema)));
  int n = 0;
  while (campaign.executeStep()) {
    if (++n > 1) throw InputError(path, "", "the table campaign holds more than one row");
    rows.campaign.emplace(campaign.getColumn(0).getString(), campaign.getColumn(1).getString());
  }
  SQLite::Statement criteria(db, fmt::format("SELECT * FROM {}.criteria ORDER BY criterion", quoted(schema)));
  while (criteria.executeStep()) {
    rows.criteria_exact.push_back(row_exact(criteria));
    rows.criteria_display.push_back(row_display(criteria));
  }
  return rows;
}

bool same_manifest(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const auto ja = nlohmann::json::parse(a, nullptr, false), jb = nlohmann::json::parse(b, nullptr, false);
  return !ja.is_discarded() && !jb.is_discarded() && ja == jb;
}

// The campaign and criteria every database of the merge must agree on: the output's, else those
// of the first input that has them.
class CampaignAgreement {
 public:
  void check(const CampaignRows& rows, const std::string& file) {
    if (rows.campaign) {
      if (!campaign_) {
        campaign_ = rows.campaign;
        campaign_file_ = file;
      } else if (campaign_->first != rows.campaign->first) {
        throw InputError(file, "", fmt::format("campaign '{}' differs from campaign '{}' of {}: the reports of two "
                                               "different campaigns are not merged",
                                               rows.campaign->first, campaign_->first, campaign_file_));
      } else if (!same_manifest(campaign_->second, rows.campaign->second)) {
        throw InputError(file, "", fmt::format("the manifest of campaign '{}' differs from that of {}: the reports of "
                                               "two different campaigns are not merged",
                                               campaign_->first, campaign_file_));
      }
    }
    if (!rows.criteria_exact.empty()) {
      if (!criteria_) {
        criteria_ = rows;
        criteria_file_ = file;
      } else if (criteria_->criteria_exact != rows.criteria_exact) {
        const auto& mine = criteria_->criteria_exact;
        std::size_t k = 0;
        while (k < mine.size() && k < rows.criteria_exact.size() && mine[k] == rows.criteria_exact[k]) ++k;
        const auto shown = [k](const std::vector<std::string>& v) { return k < v.size() ? "(" + v[k] + ")" : "none"; };
        throw InputError(file, "", fmt::format("its criteria differ from those of {} ({} against {} criteria; the "
                                               "first difference: {} against {}): the reports of two different "
                                               "campaigns are not merged",
                                               criteria_file_, rows.criteria_exact.size(), mine.size(),
                                               shown(rows.criteria_display), shown(criteria_->criteria_display)));
      }
    }
  }

 private:
  std::optional<std::pair<std::string, std::string>> campaign_;
  std::string campaign_file_;
  std::optional<CampaignRows> criteria_;
  std::string criteria_file_;
};

struct StoredRun {
  std::int64_t run_id = 0;
  std::string key, recording_name;
  std::int64_t seed = 0;
};

// The runs of a database, by run id, with their identity keys.
std::vector<StoredRun> read_runs(SQLite::Database& db) {
  const std::map<std::int64_t, RunIdentity> identities = stored_run_identities(db);
  std::vector<StoredRun> runs;
  SQLite::Statement q(db, "SELECT run_id, recording_name, seed FROM runs ORDER BY run_id");
  while (q.executeStep()) {
    StoredRun run;
    run.run_id = q.getColumn(0).getInt64();
    run.recording_name = q.getColumn(1).getString();
    run.seed = q.getColumn(2).getInt64();
    run.key = identities.at(run.run_id).key();
    runs.push_back(std::move(run));
  }
  return runs;
}

// A bench as its rows say, its id aside: two benches with the same fingerprint are one.
std::string bench_fingerprint(SQLite::Database& db, std::int64_t bench_id) {
  std::string out;
  for (const char* table : {"bench_runs", "bench_rows"}) {
    std::vector<std::string> columns;
    for (const auto& column : table_columns(db, "main", table)) {
      if (column != "bench_id") columns.push_back(quoted(column));
    }
    SQLite::Statement q(db, fmt::format("SELECT {0} FROM main.{1} WHERE bench_id = ? ORDER BY {0}", join(columns, ", "),
                                        table));
    q.bind(1, bench_id);
    while (q.executeStep()) out += row_exact(q) + '\n';
    out += '\x1e';
  }
  return out;
}

// The benches of a database, by bench id, with their fingerprints.
std::vector<std::pair<std::int64_t, std::string>> read_benches(SQLite::Database& db) {
  std::vector<std::int64_t> ids;
  SQLite::Statement q(db, "SELECT bench_id FROM bench_runs ORDER BY bench_id");
  while (q.executeStep()) ids.push_back(q.getColumn(0).getInt64());
  std::vector<std::pair<std::int64_t, std::string>> benches;
  for (const std::int64_t id : ids) benches.emplace_back(id, bench_fingerprint(db, id));
  return benches;
}

// What pass 1 reads of a database.
struct Snapshot {
  std::string file;
  std::vector<StoredRun> runs;
  std::vector<std::pair<std::int64_t, std::string>> benches;  // id, fingerprint
  CampaignRows campaign;
};

Snapshot read_snapshot(SQLite::Database& db, const std::string& file) {
  try {
    return {file, read_runs(db), read_benches(db), read_campaign(db, "main", file)};
  } catch (const SQLite::Exception& e) {
    throw InputError(file, "", std::string("cannot read as a report database: ") + e.what());
  }
}

// Where the run kept for an identity came from.
struct KeptRun {
  std::string file;
  std::int64_t run_id = 0, output_run_id = 0;
};

// What the merge will do, decided from the snapshots before anything is written.
struct Plan {
  struct Input {
    std::vector<std::pair<std::int64_t, std::int64_t>> runs, benches;  // to copy: id there, id in the output
    bool campaign = false, criteria = false;                          // to copy from it
    std::size_t first_duplicate = 0, end_duplicate = 0;               // its duplicates in MergeResult::duplicates
  };
  std::vector<Input> inputs;
  bool writes() const {
    return std::any_of(inputs.begin(), inputs.end(), [](const Input& i) {
      return !i.runs.empty() || !i.benches.empty() || i.campaign || i.criteria;
    });
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
    Plan::Input& step = plan.inputs.emplace_back();
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

// ATTACHes an input read-only as `src` for the scope.
class AttachedInput {
 public:
  AttachedInput(SQLite::Database& db, const std::string& file) : db_(db) {
    SQLite::Statement attach(db_, "ATTACH DATABASE ? AS src");
    attach.bind(1, read_only_uri(file));
    attach.exec();
    // Checked in pass 1; again in case the file was replaced since.
    const int application_id = db_.execAndGet("PRAGMA src.application_id").getInt();
    const int version = db_.execAndGet("PRAGMA src.user_version").getInt();
    if (application_id != kReportApplicationId || version != kReportSchemaVersion) {
      throw InputError(file, "", fmt::format("changed during the merge (application_id {:#x}, report schema version {}, "
                                             "expected {:#x} and {})",
                                             static_cast<std::uint32_t>(application_id), version, kReportApplicationId,
                                             kReportSchemaVersion));
    }
  }
  ~AttachedInput() {
    try {
      db_.exec("DETACH DATABASE src");
    } catch (const SQLite::Exception&) {
      // only while unwinding from an error: the connection is closed next
    }
  }
  AttachedInput(const AttachedInput&) = delete;
  AttachedInput& operator=(const AttachedInput&) = delete;

 private:
  SQLite::Database& db_;
};

// The summaries figures (timings aside) in which a duplicate (in src) differs from its kept run (in main).
void compare_summaries(SQLite::Database& db, MergeDuplicate& d) {
  std::vector<std::string> figures;
  for (const auto& column : table_columns(db, "main", "summaries")) {
    if (column != "run_id" && kTimingColumns.count(column) == 0) figures.push_back(column);
  }
  std::vector<std::string> columns;
  for (const auto& figure : figures) columns.push_back(quoted(figure));
  SQLite::Statement theirs(db, fmt::format("SELECT {} FROM src.summaries WHERE run_id = ?", join(columns, ", ")));
  SQLite::Statement kept(db, fmt::format("SELECT {} FROM main.summaries WHERE run_id = ?", join(columns, ", ")));
  theirs.bind(1, d.run_id);
  kept.bind(1, d.output_run_id);
  const bool has_theirs = theirs.executeStep(), has_kept = kept.executeStep();
  if (!has_theirs || !has_kept) {
    if (has_theirs != has_kept) {
      d.differences.push_back({"summaries", has_kept ? "a row" : "no row", has_theirs ? "a row" : "no row"});
    }
    return;
  }
  for (int c = 0; c < theirs.getColumnCount(); ++c) {
    if (exact(theirs.getColumn(c)) != exact(kept.getColumn(c))) {
      d.differences.push_back({figures[static_cast<std::size_t>(c)], display(kept.getColumn(c)),
                               display(theirs.getColumn(c))});
    }
  }
}

// Pass 2: the temporary output and the statements that fill it.
class MergeTarget {
 public:
  MergeTarget(SQLite::Database& db, const std::string& output) : db_(db) {
    tables_ = classify_report_tables(db_);
    if (!tables_.unknown.empty()) {
      throw std::logic_error(fmt::format("{}: rcsim merge does not know how to merge the table(s) {}", output,
                                         join(tables_.unknown, ", ")));
    }
    for (const auto* group : {&tables_.run_scoped, &tables_.bench, &tables_.campaign}) {
      for (const auto& table : *group) columns_[table] = table_columns(db_, "main", table);
    }
    db_.exec("CREATE TEMP TABLE merge_run_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
    db_.exec("CREATE TEMP TABLE merge_bench_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
  }

  // Copies from the input ATTACHed as `src` what the plan says, then compares its duplicates.
  void add(const std::string& file, const Plan::Input& step, std::vector<MergeDuplicate>& duplicates) {
    check_columns(file);
    SQLite::Transaction transaction(db_);
    if (fill_map("merge_run_map", step.runs)) {
      for (const auto& table : tables_.run_scoped) db_.exec(copy_sql(table, "run_id", "merge_run_map"));
    }
    if (fill_map("merge_bench_map", step.benches)) {
      for (const auto& table : tables_.bench) db_.exec(copy_sql(table, "bench_id", "merge_bench_map"));
    }
    if (step.campaign) copy_all("campaign");
    if (step.criteria) copy_all("criteria");
    for (std::size_t i = step.first_duplicate; i < step.end_duplicate; ++i) compare_summaries(db_, duplicates[i]);
    transaction.commit();
  }

 private:
  // The inputs have the output's schema version, so the same columns; said plainly if not.
  void check_columns(const std::string& file) {
    for (const auto& [table, columns] : columns_) {
      const auto theirs = table_columns(db_, "src", table);
      if (theirs != columns) {
        throw InputError(file, "", fmt::format("table {} has the columns ({}), the output ({}): not a report of this "
                                               "rcsim's schema",
                                               table, join(theirs, ", "), join(columns, ", ")));
      }
    }
  }

  bool fill_map(const char* map, const std::vector<std::pair<std::int64_t, std::int64_t>>& ids) {
    db_.exec(fmt::format("DELETE FROM temp.{}", map));
    SQLite::Statement insert(db_, fmt::format("INSERT INTO temp.{} VALUES (?, ?)", map));
    for (const auto& [from, to] : ids) {
      insert.bind(1, from);
      insert.bind(2, to);
      insert.exec();
      insert.reset();
    }
    return !ids.empty();
  }

  std::string copy_sql(const std::string& table, const std::string& key, const std::string& map) const {
    std::vector<std::string> names, selected;
    for (const auto& column : columns_.at(table)) {
      names.push_back(quoted(column));
      selected.push_back(column == key ? "m.new_id" : "s." + quoted(column));
    }
    return fmt::format("INSERT INTO main.{0} ({1}) SELECT {2} FROM src.{0} AS s JOIN temp.{3} AS m ON m.old_id = s.{4}",
                       quoted(table), join(names, ", "), join(selected, ", "), map, quoted(key));
  }

  void copy_all(const std::string& table) {
    std::vector<std::string> names;
    for (const auto& column : columns_.at(table)) names.push_back(quoted(column));
    db_.exec(fmt::format("INSERT INTO main.{0} ({1}) SELECT {1} FROM src.{0}", quoted(table), join(names, ", ")));
  }

  SQLite::Database& db_;
  ReportTables tables_;
  std::map<std::string, std::vector<std::string>> columns_;
};

// Nothing to add (every run a duplicate, every bench there, the campaign too): the output is left
// as it is, only read to compare the duplicates' figures.
void compare_only(const std::string& output, const std::vector<Snapshot>& inputs, const Plan& plan,
                  MergeResult& result) {
  try {
    SQLite::Database db(read_only_uri(output), SQLite::OPEN_READONLY | SQLite::OPEN_URI);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const Plan::Input& step = plan.inputs[i];
      if (step.first_duplicate == step.end_duplicate) continue;
      try {
        AttachedInput attached(db, inputs[i].file);
        for (std::size_t d = step.first_duplicate; d < step.end_duplicate; ++d) compare_summaries(db, result.duplicates[d]);
      } catch (const SQLite::Exception& e) {
        throw InputError(inputs[i].file, "", std::string("cannot read as a report database: ") + e.what());
      }
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(output, "", std::string("cannot read as a report database: ") + e.what());
  }
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
  result.stale_temporaries_removed = remove_stale_temporaries(output_path);

  // The output as it is: checked, its WAL checkpointed into it (so that no -wal of the old file
  // lies beside the new one after the rename), what it holds.
  std::unique_ptr<SQLite::Database> existing;
  Snapshot output_snapshot{output, {}, {}, {}};
  FileState output_state;  // as the merge found it, its WAL checkpointed: it must stay so until the rename
  if (fs::exists(output_path, error)) {
    Header header = Header::empty;
    existing = open_existing(output, SQLite::OPEN_READWRITE, header);
    if (header == Header::empty) {
      existing.reset();  // an empty database: made anew
    } else {
      try {
        SQLite::Statement checkpoint(*existing, "PRAGMA wal_checkpoint(TRUNCATE)");
        if (checkpoint.executeStep() && checkpoint.getColumn(0).getInt() != 0) {
          throw InputError(output, "", "in use by another process (its WAL cannot be checkpointed): merge into it "
                                       "when nothing else has it open");
        }
      } catch (const SQLite::Exception& e) {
        throw InputError(output, "", std::string("cannot read as a report database: ") + e.what());
      }
      output_snapshot = read_snapshot(*existing, output);
      result.output_existed = true;
      result.runs_before = static_cast<long long>(output_snapshot.runs.size());
    }
    output_state = file_state(output_path);
  }

  // Pass 1: every input checked, and agreeing with the output, before anything is written.
  CampaignAgreement agreement;
  agreement.check(output_snapshot.campaign, output);
  std::vector<Snapshot> snapshots;
  snapshots.reserve(inputs.size());
  for (const std::string& input : inputs) {
    Header header = Header::empty;
    const auto db = open_existing(input, SQLite::OPEN_READONLY, header);
    if (header == Header::empty) throw InputError(input, "", "the database is empty: no replay has been stored in it");
    snapshots.push_back(read_snapshot(*db, input));
    agreement.check(snapshots.back().campaign, input);
  }
  const Plan plan = make_plan(output_snapshot, snapshots, result);
  result.campaign = output_snapshot.campaign.campaign ? output_snapshot.campaign.campaign->first : "";
  result.criteria = static_cast<long long>(output_snapshot.campaign.criteria_exact.size());
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    if (plan.inputs[i].campaign) result.campaign = snapshots[i].campaign.campaign->first;
    if (plan.inputs[i].criteria) result.criteria = static_cast<long long>(snapshots[i].campaign.criteria_exact.size());
  }
  if (existing && !plan.writes()) {
    existing.reset();
    compare_only(output, snapshots, plan, result);
    result.runs_after = result.runs_before;
    return result;
  }

  // Pass 2: the temporary output.
  TemporaryDatabase temporary(temporary_path(output_path));
  const std::string temp = temporary.path().string();
  try {
    if (!existing) open_report_database(temp, true);  // a new report: the schema, WAL
    SQLite::Database db(temp, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE | SQLite::OPEN_URI);
    if (existing) {
      {
        SQLite::Backup backup(db, "main", *existing, "main");
        backup.executeStep();  // every page, read through the output's WAL
      }
      existing.reset();
    }
    // Private until renamed: a crash discards it whole, so no journal and no syncs while filling;
    // the file is synced once before the rename.
    db.exec("PRAGMA journal_mode = MEMORY");
    db.exec("PRAGMA synchronous = OFF");
    db.exec("PRAGMA foreign_keys = OFF");  // the runs are copied before the rows that refer to them
    db.exec("PRAGMA cache_size = -32768");
    db.exec("PRAGMA temp_store = MEMORY");
    MergeTarget target(db, output);
    for (std::size_t i = 0; i < snapshots.size(); ++i) {
      const Plan::Input& step = plan.inputs[i];
      if (step.runs.empty() && step.benches.empty() && !step.campaign && !step.criteria &&
          step.first_duplicate == step.end_duplicate) {
        continue;  // nothing to copy or compare
      }
      try {
        AttachedInput attached(db, snapshots[i].file);
        target.add(snapshots[i].file, step, result.duplicates);
      } catch (const SQLite::Exception& e) {
        throw InputError(snapshots[i].file, "", fmt::format("cannot merge into {}: {}", output, e.what()));
      }
    }
    result.runs_after = db.execAndGet("SELECT count(*) FROM main.runs").getInt64();
    db.exec("PRAGMA foreign_keys = ON");
    if (db.execAndGet("PRAGMA journal_mode = WAL").getString() != "wal") {
      throw InputError(output, "", "cannot set the merged report to WAL");
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(output, "", std::string("cannot write the merged report: ") + e.what());
  }
  // Closed above (the last connection of a WAL database leaves no -wal, -shm); given the old
  // output's permissions, synced, renamed over the output, and the directory synced so that the
  // rename survives a power loss.
  if (output_state.exists) fs::permissions(temporary.path(), fs::status(output_path).permissions(), error);
  fsync_path(temporary.path(), O_RDONLY, output);
  if (file_state(output_path) != output_state) {
    throw InputError(output, "", "changed while it was being merged into (written by another process): nothing "
                                 "merged; merge again when nothing else writes it");
  }
  if (std::rename(temp.c_str(), output.c_str()) != 0) {
    throw InputError(output, "", std::string("cannot rename the merged report into place: ") + std::strerror(errno));
  }
  temporary.renamed();
  fsync_path(output_path.parent_path().empty() ? fs::path(".") : output_path.parent_path(), O_RDONLY | O_DIRECTORY,
             output);
  return result;
}

}  // namespace rcsim::replay
