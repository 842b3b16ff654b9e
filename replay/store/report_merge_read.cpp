// What `rcsim merge` reads of a report database before it writes (report_merge_read.hpp).
#include "replay/store/report_merge_read.hpp"

#include <sqlite3.h>

#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "replay/store/report_merge_files.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay::merge_read {

namespace {

namespace fs = std::filesystem;

std::string row_exact(SQLite::Statement& q) {
  std::string out;
  for (int c = 0; c < q.getColumnCount(); ++c) out += exact(q.getColumn(c)) + '\x1f';
  return out;
}

// A criterion as schemas/campaign.md writes it: `gospa_mean_m <= 1.5 per recording`,
// `p95(gospa_mean_m) <= 1.2 over the campaign`.
std::string criterion_text(SQLite::Statement& q) {
  const std::string figure = q.getColumn("figure").getString(), scope = q.getColumn("scope").getString(),
                    statistic = q.getColumn("statistic").getString();
  const bool campaign = scope == "campaign";
  std::string text = campaign || statistic != "value" ? fmt::format("{}({})", statistic, figure) : figure;
  text += fmt::format(" {} {}", q.getColumn("bound").getString() == "max" ? "<=" : ">=",
                      display(q.getColumn("threshold")));
  text += campaign ? " over the campaign" : scope == "recording" ? " per recording" : " per " + scope;
  if (q.getColumn("if_missing").getString() == "pass") text += ", passed if missing";
  return text;
}

CampaignRows read_campaign(SQLite::Database& db, const std::string& path) {
  CampaignRows rows;
  SQLite::Statement campaign(db, "SELECT name, manifest FROM main.campaign");
  int n = 0;
  while (campaign.executeStep()) {
    if (++n > 1) throw InputError(path, "", "the table campaign holds more than one row");
    rows.campaign.emplace(campaign.getColumn(0).getString(), campaign.getColumn(1).getString());
  }
  SQLite::Statement criteria(db, "SELECT * FROM main.criteria ORDER BY criterion");
  while (criteria.executeStep()) {
    rows.criteria_exact.push_back(row_exact(criteria));
    rows.criteria_text.push_back(criterion_text(criteria));
  }
  return rows;
}

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
    for (const auto& column : table_columns(db, table)) {
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

// A JSON value in one line, cut to a length a message can hold.
std::string short_json(const nlohmann::ordered_json& value) {
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// Equal as JSON: objects whatever the order of their members.
bool same_json(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b) {
  return nlohmann::json::parse(a.dump()) == nlohmann::json::parse(b.dump());
}

}  // namespace

std::string quoted(const std::string& identifier) {
  std::string out = "\"";
  for (const char c : identifier) {
    out += c;
    if (c == '"') out += '"';
  }
  return out + '"';
}

std::vector<std::string> table_columns(SQLite::Database& db, const std::string& table) {
  SQLite::Statement q(db, "SELECT name FROM pragma_table_info(?, 'main') ORDER BY cid");
  q.bind(1, table);
  std::vector<std::string> columns;
  while (q.executeStep()) columns.push_back(q.getColumn(0).getString());
  return columns;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

std::string display(const SQLite::Column& v) {
  switch (v.getType()) {
    case SQLITE_INTEGER: return std::to_string(v.getInt64());
    case SQLITE_FLOAT: return fmt::format("{}", v.getDouble());
    case SQLITE_TEXT: return v.getString();
    case SQLITE_BLOB: return fmt::format("<{} bytes>", v.getBytes());
    default: return "NULL";
  }
}

std::string exact(const SQLite::Column& v) {
  if (v.getType() != SQLITE_BLOB) return fmt::format("{}{}", v.getType(), display(v));
  const auto* bytes = static_cast<const unsigned char*>(v.getBlob());
  std::string out = "b";
  for (int i = 0; i < v.getBytes(); ++i) out += fmt::format("{:02x}", bytes[i]);
  return out;
}

Header check_header(SQLite::Database& db, const std::string& path) {
  const SchemaState state = read_schema_state(db, path);
  if (state == SchemaState::older) {
    throw InputError(path, "", fmt::format("report schema version {}, expected {}; open it once with `rcsim report {} "
                                           "-o REPORT.html` to migrate it, then merge again",
                                           db.execAndGet("PRAGMA user_version").getInt(), kReportSchemaVersion, path));
  }
  return state == SchemaState::empty ? Header::empty : Header::report;
}

void throw_named(const SQLite::Exception& e, const std::string& path) {
  if (e.getErrorCode() == SQLITE_NOTADB) throw InputError(path, "", "not an SQLite database (file is not a database)");
  throw InputError(path, "", std::string("cannot read as a report database: ") + e.what());
}

void check_regular_file(const std::string& path) {
  std::error_code error;
  if (!fs::exists(path, error)) throw InputError(path, "", "no such report database");
  if (!fs::is_regular_file(path, error)) throw InputError(path, "", "not a regular file");
}

namespace {

// Refuses, naming it, a database whose pages or indexes are damaged (SQLite's quick_check: every
// page and record well-formed, linear in the file): a merge must not copy damage into a clean file.
void check_intact(SQLite::Database& db, const std::string& path) {
  SQLite::Statement check(db, "PRAGMA quick_check(5)");
  std::vector<std::string> problems;
  while (check.executeStep()) problems.push_back(check.getColumn(0).getString());
  if (problems.size() == 1 && problems.front() == "ok") return;
  std::string joined;
  for (const std::string& p : problems) joined += (joined.empty() ? "" : "; ") + p;
  throw InputError(path, "", "the database is damaged (PRAGMA quick_check: " + joined +
                                 "); restore it from a copy, or replay its recordings again");
}

}  // namespace

std::unique_ptr<ReportDatabase> open_input(const std::string& path, Header& header) {
  check_regular_file(path);
  try {
    auto db = std::make_unique<ReportDatabase>(merge_files::read_only_uri(path),
                                                 SQLite::OPEN_READONLY | SQLite::OPEN_URI);
    db->setBusyTimeout(5000);
    header = check_header(*db, path);
    check_intact(*db, path);
    return db;
  } catch (const SQLite::Exception& e) {
    throw_named(e, path);
  }
}

Snapshot read_snapshot(SQLite::Database& db, const std::string& file) {
  try {
    return {file, read_runs(db), read_benches(db), read_campaign(db, file)};
  } catch (const SQLite::Exception& e) {
    throw InputError(file, "", std::string("cannot read as a report database: ") + e.what());
  }
}

std::string first_manifest_difference(const std::string& theirs, const std::string& kept) {
  if (theirs == kept) return "";
  const auto t = parse_stored_json(theirs);
  const auto k = parse_stored_json(kept);
  if (t.is_discarded() || k.is_discarded()) return "the texts differ, and one is not JSON (or nests deeper than rcsim reads)";
  if (same_json(t, k)) return "";
  if (!t.is_object() || !k.is_object()) return fmt::format("{} against {}", short_json(t), short_json(k));
  for (const auto& [field, value] : k.items()) {
    if (!t.contains(field)) return fmt::format("field \"{}\": missing against {}", field, short_json(value));
    if (!same_json(t.at(field), value)) {
      return fmt::format("field \"{}\": {} against {}", field, short_json(t.at(field)), short_json(value));
    }
  }
  for (const auto& [field, value] : t.items()) {
    if (!k.contains(field)) return fmt::format("field \"{}\": {} against missing", field, short_json(value));
  }
  return "";  // not reached: the objects differ in a field
}

void CampaignAgreement::check(const CampaignRows& rows, const std::string& file) {
  if (rows.campaign) {
    if (!campaign_) {
      campaign_ = rows.campaign;
      campaign_file_ = file;
    } else if (campaign_->first != rows.campaign->first) {
      throw InputError(file, "", fmt::format("campaign '{}' differs from campaign '{}' of {}: the reports of two "
                                             "different campaigns are not merged",
                                             rows.campaign->first, campaign_->first, campaign_file_));
    } else if (const std::string difference = first_manifest_difference(rows.campaign->second, campaign_->second);
               !difference.empty()) {
      throw InputError(file, "", fmt::format("the manifest of campaign '{}' differs from that of {} ({}): the reports "
                                             "of two different campaigns are not merged",
                                             campaign_->first, campaign_file_, difference));
    }
  }
  if (rows.criteria_exact.empty()) return;
  if (!criteria_) {
    criteria_ = rows;
    criteria_file_ = file;
    return;
  }
  const auto& kept = criteria_->criteria_exact;
  if (kept == rows.criteria_exact) return;
  std::size_t k = 0;
  while (k < kept.size() && k < rows.criteria_exact.size() && kept[k] == rows.criteria_exact[k]) ++k;
  const auto shown = [k](const std::vector<std::string>& texts) { return k < texts.size() ? texts[k] : "none"; };
  throw InputError(file, "", fmt::format("its criteria differ from those of {} ({} against {} criteria; criteria[{}]: "
                                         "{} against {}): the reports of two different campaigns are not merged",
                                         criteria_file_, rows.criteria_exact.size(), kept.size(), k,
                                         shown(rows.criteria_text), shown(criteria_->criteria_text)));
}

}  // namespace rcsim::replay::merge_read
