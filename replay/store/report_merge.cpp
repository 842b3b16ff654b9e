// `rcsim merge` (docs/merge.md). Two passes:
//  1. every input is opened read-only and checked (an rcsim report of the current schema
//     version; campaign and criteria agreeing), and the identities of its runs are read;
//  2. the output is built in a temporary file beside it, `.NAME.merge-HOST-PID.tmp`: a copy of
//     the existing output made with SQLite's backup API (which reads through its WAL), then each
//     input ATTACHed read-only and its new runs copied table by table with INSERT ... SELECT;
//     the file is set to WAL like every report, closed, fsynced and renamed over the output, and
//     the directory fsynced.
// Until the rename the output is untouched, so a refusal, a failure or a kill at any moment leaves
// it as it was; a later merge removes the temporary files of merges that died.
#include "replay/store/report_merge.hpp"

#include <SQLiteCpp/Backup.h>
#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
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
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay {

namespace {

namespace fs = std::filesystem;

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

// The name of the rcsim executable's host, for the temporary file's name: on a shared filesystem
// a merge judges only the temporary files of its own host by their pid.
std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) return "host";
  std::string host(name.data());
  for (char& c : host) {
    if (c == '/' || c == '-') c = '_';
  }
  return host.empty() ? "host" : host;
}

fs::path temporary_path(const fs::path& output) {
  return output.parent_path() / fmt::format(".{}.merge-{}-{}.tmp", output.filename().string(), host_name(), ::getpid());
}

void remove_with_companions(const fs::path& db) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(db.string() + suffix, ignored);
}

// Removes the temporary files `.NAME.merge-HOST-PID.tmp` (and their -wal, -shm, -journal) of
// merges into this output on this host whose process is gone. Returns how many it removed.
int remove_stale_temporaries(const fs::path& output) {
  const fs::path dir = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  const std::string prefix = fmt::format(".{}.merge-{}-", output.filename().string(), host_name());
  int removed = 0;
  std::error_code error;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // PID.tmp
    const std::size_t dot = rest.find(".tmp");
    if (dot == 0 || dot == std::string::npos || rest.substr(0, dot).find_first_not_of("0123456789") != std::string::npos ||
        rest.size() != dot + 4 || dot > 9) {
      continue;  // a companion (-wal, -shm) goes with its database, or not ours
    }
    const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dot)));
    // Our own pid: left by an earlier process that had it, since this one has not made its file yet.
    const bool alive = pid != ::getpid() && (::kill(pid, 0) == 0 || errno == EPERM);
    if (!alive) stale.push_back(entry.path());
  }
  for (const fs::path& path : stale) {
    remove_with_companions(path);
    ++removed;
  }
  return removed;
}

void fsync_path(const fs::path& path, int flags, const std::string& name_for_errors) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw InputError(name_for_errors, "", fmt::format("cannot sync {}: {}", path.string(), std::strerror(error)));
  }
  ::close(fd);
}

// The `file:` URI that opens an input read-only, so that it is never written. A report is in WAL
// mode; a read-only connection to it makes an empty -wal and -shm beside it where there are none,
// and cannot remove them. A shard with no -wal was closed by its last writer and has nobody
// writing it: it is read as immutable, leaving nothing behind (and readable from a read-only
// directory). One with a -wal (a writer killed after a commit, or still at work) is read with its
// WAL.
std::string read_only_uri(const std::string& path) {
  std::error_code error;
  const bool has_wal = fs::exists(path + "-wal", error);
  std::string uri = "file:";
  for (const unsigned char c : fs::absolute(path).lexically_normal().string()) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      uri += static_cast<char>(c);
    } else {
      uri += fmt::format("%{:02X}", c);
    }
  }
  return uri + (has_wal ? "?mode=ro" : "?mode=ro&immutable=1");
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

struct InputSnapshot {
  std::string file;
  std::vector<StoredRun> runs;
};

// Pass 1 for one input: read-only, checked, its runs' identities.
InputSnapshot read_input(const std::string& file, CampaignAgreement& agreement) {
  Header header = Header::empty;
  const auto db = open_existing(file, SQLite::OPEN_READONLY, header);
  if (header == Header::empty) throw InputError(file, "", "the database is empty: no replay has been stored in it");
  try {
    agreement.check(read_campaign(*db, "main", file), file);
    return {file, read_runs(*db)};
  } catch (const SQLite::Exception& e) {
    throw InputError(file, "", std::string("cannot read as a report database: ") + e.what());
  }
}

// Where the run kept for an identity came from.
struct KeptRun {
  std::string file;
  std::int64_t run_id = 0, output_run_id = 0;
};

// Pass 2: the temporary output and the statements that fill it.
class MergeTarget {
 public:
  MergeTarget(SQLite::Database& db, const std::string& output) : db_(db), output_(output) {
    tables_ = classify_report_tables(db_);
    if (!tables_.unknown.empty()) {
      throw std::logic_error(fmt::format("{}: rcsim merge does not know how to merge the table(s) {}", output,
                                         join(tables_.unknown, ", ")));
    }
    for (const auto& table : tables_.run_scoped) columns_[table] = table_columns(db_, "main", table);
    for (const auto& table : tables_.bench) columns_[table] = table_columns(db_, "main", table);
    for (const auto& table : tables_.campaign) columns_[table] = table_columns(db_, "main", table);
    summary_figures_.clear();
    for (const auto& column : columns_.at("summaries")) {
      if (column != "run_id" && kTimingColumns.count(column) == 0) summary_figures_.push_back(column);
    }
    db_.exec("CREATE TEMP TABLE merge_run_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
    db_.exec("CREATE TEMP TABLE merge_bench_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
    next_run_id_ = db_.execAndGet("SELECT coalesce(max(run_id), 0) + 1 FROM main.runs").getInt64();
    next_bench_id_ = db_.execAndGet("SELECT coalesce(max(bench_id), 0) + 1 FROM main.bench_runs").getInt64();
    SQLite::Statement benches(db_, "SELECT bench_id FROM main.bench_runs ORDER BY bench_id");
    while (benches.executeStep()) bench_fingerprints_.insert(bench_fingerprint("main", benches.getColumn(0).getInt64()));
  }

  // The output's own runs: the first of each identity is the one kept.
  void keep_output_runs(const std::vector<StoredRun>& runs, const std::string& label) {
    for (const StoredRun& run : runs) kept_.emplace(run.key, KeptRun{label, run.run_id, run.run_id});
  }

  // Copies the runs of one input (ATTACHed as `src`) that are not kept yet, and its benches.
  MergeInput add(const InputSnapshot& input, std::vector<MergeDuplicate>& duplicates) {
    check_columns(input.file);
    MergeInput result;
    result.file = input.file;
    result.runs = static_cast<long long>(input.runs.size());
    SQLite::Transaction transaction(db_);
    db_.exec("DELETE FROM temp.merge_run_map");
    SQLite::Statement map(db_, "INSERT INTO temp.merge_run_map VALUES (?, ?)");
    const std::size_t first_duplicate = duplicates.size();
    for (const StoredRun& run : input.runs) {
      const auto [it, added] = kept_.emplace(run.key, KeptRun{input.file, run.run_id, next_run_id_});
      if (added) {
        map.bind(1, run.run_id);
        map.bind(2, next_run_id_++);
        map.exec();
        map.reset();
        ++result.added;
      } else {
        MergeDuplicate d;
        d.file = input.file;
        d.run_id = run.run_id;
        d.kept_file = it->second.file;
        d.kept_run_id = it->second.run_id;
        d.output_run_id = it->second.output_run_id;
        d.recording_name = run.recording_name;
        d.seed = run.seed;
        d.identity = run.key;
        duplicates.push_back(std::move(d));
        ++result.duplicates;
      }
      result.run_ids.emplace_back(run.run_id, it->second.output_run_id);
    }
    for (const auto& table : tables_.run_scoped) db_.exec(copy_sql(table, "run_id", "merge_run_map"));
    add_benches(result);
    add_campaign();
    for (std::size_t i = first_duplicate; i < duplicates.size(); ++i) compare_summaries(duplicates[i]);
    transaction.commit();
    return result;
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

  std::string copy_sql(const std::string& table, const std::string& key, const std::string& map) const {
    const auto& columns = columns_.at(table);
    std::vector<std::string> selected;
    for (const auto& column : columns) selected.push_back(column == key ? "m.new_id" : "s." + quoted(column));
    std::vector<std::string> names;
    for (const auto& column : columns) names.push_back(quoted(column));
    return fmt::format("INSERT INTO main.{0} ({1}) SELECT {2} FROM src.{0} AS s JOIN temp.{3} AS m ON m.old_id = s.{4}",
                       quoted(table), join(names, ", "), join(selected, ", "), map, quoted(key));
  }

  // A bench as its rows say, its id aside: two benches with the same fingerprint are one.
  std::string bench_fingerprint(const std::string& schema, std::int64_t bench_id) {
    std::string out;
    for (const char* table : {"bench_runs", "bench_rows"}) {
      std::vector<std::string> columns;
      for (const auto& column : columns_.at(table)) {
        if (column != "bench_id") columns.push_back(quoted(column));
      }
      SQLite::Statement q(db_, fmt::format("SELECT {0} FROM {1}.{2} WHERE bench_id = ? ORDER BY {0}", join(columns, ", "),
                                           quoted(schema), table));
      q.bind(1, bench_id);
      while (q.executeStep()) out += row_exact(q) + '\n';
      out += '\x1e';
    }
    return out;
  }

  void add_benches(MergeInput& result) {
    db_.exec("DELETE FROM temp.merge_bench_map");
    SQLite::Statement map(db_, "INSERT INTO temp.merge_bench_map VALUES (?, ?)");
    std::vector<std::int64_t> ids;
    SQLite::Statement benches(db_, "SELECT bench_id FROM src.bench_runs ORDER BY bench_id");
    while (benches.executeStep()) ids.push_back(benches.getColumn(0).getInt64());
    for (const std::int64_t id : ids) {
      ++result.benches;
      if (!bench_fingerprints_.insert(bench_fingerprint("src", id)).second) continue;  // an exact duplicate
      map.bind(1, id);
      map.bind(2, next_bench_id_++);
      map.exec();
      map.reset();
      ++result.benches_added;
    }
    if (result.benches_added == 0) return;
    db_.exec(copy_sql("bench_runs", "bench_id", "merge_bench_map"));
    db_.exec(copy_sql("bench_rows", "bench_id", "merge_bench_map"));
  }

  // The campaign and criteria (checked to agree in pass 1) into an output that has none.
  void add_campaign() {
    for (const auto& table : tables_.campaign) {
      if (db_.execAndGet(fmt::format("SELECT count(*) FROM main.{}", quoted(table))).getInt64() > 0) continue;
      std::vector<std::string> names;
      for (const auto& column : columns_.at(table)) names.push_back(quoted(column));
      const int copied = db_.exec(fmt::format("INSERT INTO main.{0} ({1}) SELECT {1} FROM src.{0}", quoted(table),
                                              join(names, ", ")));
      campaign_copied_ = campaign_copied_ || copied > 0;
    }
  }

  void compare_summaries(MergeDuplicate& d) {
    std::vector<std::string> columns;
    for (const auto& column : summary_figures_) columns.push_back(quoted(column));
    const std::string select = join(columns, ", ");
    SQLite::Statement theirs(db_, fmt::format("SELECT {} FROM src.summaries WHERE run_id = ?", select));
    SQLite::Statement kept(db_, fmt::format("SELECT {} FROM main.summaries WHERE run_id = ?", select));
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
        d.differences.push_back({summary_figures_[static_cast<std::size_t>(c)], display(kept.getColumn(c)),
                                 display(theirs.getColumn(c))});
      }
    }
  }

 public:
  bool campaign_copied() const { return campaign_copied_; }

 private:
  SQLite::Database& db_;
  std::string output_;
  ReportTables tables_;
  std::map<std::string, std::vector<std::string>> columns_;
  std::vector<std::string> summary_figures_;
  std::map<std::string, KeptRun> kept_;  // by identity key
  std::set<std::string> bench_fingerprints_;
  std::int64_t next_run_id_ = 1, next_bench_id_ = 1;
  bool campaign_copied_ = false;
};

// The temporary output, removed unless it was renamed into place.
class TemporaryDatabase {
 public:
  explicit TemporaryDatabase(fs::path path) : path_(std::move(path)) { remove_with_companions(path_); }
  ~TemporaryDatabase() {
    if (!kept_) remove_with_companions(path_);
  }
  TemporaryDatabase(const TemporaryDatabase&) = delete;
  TemporaryDatabase& operator=(const TemporaryDatabase&) = delete;
  const fs::path& path() const { return path_; }
  void renamed() { kept_ = true; }

 private:
  fs::path path_;
  bool kept_ = false;
};

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
  // lies beside the new one after the rename), its runs' identities.
  std::unique_ptr<SQLite::Database> existing;
  CampaignAgreement agreement;
  std::vector<StoredRun> output_runs;
  if (fs::exists(output_path, error)) {
    Header header = Header::empty;
    existing = open_existing(output, SQLite::OPEN_READWRITE, header);
    try {
      if (header == Header::empty) {
        existing.reset();  // an empty database: made anew
      } else {
        SQLite::Statement checkpoint(*existing, "PRAGMA wal_checkpoint(TRUNCATE)");
        if (checkpoint.executeStep() && checkpoint.getColumn(0).getInt() != 0) {
          throw InputError(output, "", "in use by another process (its WAL cannot be checkpointed): merge into it "
                                       "when nothing else has it open");
        }
        agreement.check(read_campaign(*existing, "main", output), output);
        output_runs = read_runs(*existing);
        result.output_existed = true;
        result.runs_before = static_cast<long long>(output_runs.size());
      }
    } catch (const SQLite::Exception& e) {
      throw InputError(output, "", std::string("cannot read as a report database: ") + e.what());
    }
  }

  // Pass 1: every input checked before anything is written.
  std::vector<InputSnapshot> snapshots;
  snapshots.reserve(inputs.size());
  for (const std::string& input : inputs) snapshots.push_back(read_input(input, agreement));

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
    target.keep_output_runs(output_runs, output);
    for (const InputSnapshot& input : snapshots) {
      try {
        {
          SQLite::Statement attach(db, "ATTACH DATABASE ? AS src");
          attach.bind(1, read_only_uri(input.file));
          attach.exec();
        }
        // Checked in pass 1; again in case the file was replaced since.
        const int application_id = db.execAndGet("PRAGMA src.application_id").getInt();
        const int version = db.execAndGet("PRAGMA src.user_version").getInt();
        if (application_id != kReportApplicationId || version != kReportSchemaVersion) {
          throw InputError(input.file, "", fmt::format("changed during the merge (application_id {:#x}, report schema "
                                                       "version {}, expected {:#x} and {})",
                                                       static_cast<std::uint32_t>(application_id), version,
                                                       kReportApplicationId, kReportSchemaVersion));
        }
        result.inputs.push_back(target.add(input, result.duplicates));
      } catch (const SQLite::Exception& e) {
        throw InputError(input.file, "", fmt::format("cannot merge into {}: {}", output, e.what()));
      }
      db.exec("DETACH DATABASE src");
    }
    result.campaign_copied = target.campaign_copied();
    result.runs_after = db.execAndGet("SELECT count(*) FROM main.runs").getInt64();
    result.criteria = db.execAndGet("SELECT count(*) FROM main.criteria").getInt64();
    SQLite::Statement campaign(db, "SELECT name FROM main.campaign");
    if (campaign.executeStep()) result.campaign = campaign.getColumn(0).getString();
    campaign.reset();
    db.exec("PRAGMA foreign_keys = ON");
    if (db.execAndGet("PRAGMA journal_mode = WAL").getString() != "wal") {
      throw InputError(output, "", "cannot set the merged report to WAL");
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(output, "", std::string("cannot write the merged report: ") + e.what());
  }
  // Closed above (the last connection of a WAL database leaves no -wal, -shm); synced, renamed
  // over the output, and the directory synced so that the rename survives a power loss.
  fsync_path(temporary.path(), O_RDONLY, output);
  if (std::rename(temp.c_str(), output.c_str()) != 0) {
    throw InputError(output, "", std::string("cannot rename the merged report into place: ") + std::strerror(errno));
  }
  temporary.renamed();
  fsync_path(output_path.parent_path().empty() ? fs::path(".") : output_path.parent_path(), O_RDONLY | O_DIRECTORY,
             output);
  return result;
}

}  // namespace rcsim::replay
