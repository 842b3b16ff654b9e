// How `rcsim merge` writes (report_merge_copy.hpp).
#include "replay/store/report_merge_copy.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <fmt/format.h>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "common/input_error.hpp"
#include "replay/store/report_merge_files.hpp"
#include "replay/store/report_merge_read.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay::merge_copy {

namespace {

using merge_read::display;
using merge_read::exact;
using merge_read::join;
using merge_read::quoted;
using merge_read::table_columns;

// The summaries columns that time a replay on its machine: two runs of one identity differ there.
const std::set<std::string> kTimingColumns{"simulate_cpu_s", "total_wall_s"};

// A statement of the C API, for what SQLiteCpp does not offer: a value handed from one
// statement to another as stored (sqlite3_column_value, sqlite3_bind_value). Failures are
// SQLite::Exception, as SQLiteCpp's.
class RawStatement {
 public:
  RawStatement(SQLite::Database& db, const std::string& sql) : db_(db.getHandle()) {
    check(sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement_, nullptr));
  }
  ~RawStatement() { sqlite3_finalize(statement_); }
  RawStatement(const RawStatement&) = delete;
  RawStatement& operator=(const RawStatement&) = delete;

  sqlite3_stmt* get() const { return statement_; }
  // One step: true with a row, false when done.
  bool step() {
    const int rc = sqlite3_step(statement_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) throw SQLite::Exception(db_, rc);
    return false;
  }
  void reset() { sqlite3_reset(statement_); }  // its error was thrown by step()
  void check(int rc) const {
    if (rc != SQLITE_OK) throw SQLite::Exception(db_, rc);
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

// Binds a value of the row a statement stands on as it is stored (type and bytes). Texts and
// blobs are not copied: valid until that statement steps again, after the insert.
int bind_as_stored(sqlite3_stmt* to, int parameter, sqlite3_stmt* from, int column) {
  switch (sqlite3_column_type(from, column)) {
    case SQLITE_INTEGER: return sqlite3_bind_int64(to, parameter, sqlite3_column_int64(from, column));
    case SQLITE_FLOAT: return sqlite3_bind_double(to, parameter, sqlite3_column_double(from, column));
    case SQLITE_TEXT: {
      const unsigned char* text = sqlite3_column_text(from, column);
      return sqlite3_bind_text(to, parameter, reinterpret_cast<const char*>(text), sqlite3_column_bytes(from, column),
                               SQLITE_STATIC);
    }
    case SQLITE_BLOB: {
      const void* blob = sqlite3_column_blob(from, column);
      const int bytes = sqlite3_column_bytes(from, column);
      // An empty blob comes as a null pointer, which would bind NULL.
      return bytes == 0 ? sqlite3_bind_zeroblob(to, parameter, 0)
                        : sqlite3_bind_blob(to, parameter, blob, bytes, SQLITE_STATIC);
    }
    default: return sqlite3_bind_null(to, parameter);
  }
}

// ATTACHes an input read-only as `src` for the scope (outside a transaction: SQLite detaches
// nothing inside one).
class AttachedInput {
 public:
  AttachedInput(SQLite::Database& db, const std::string& file) : db_(db) {
    SQLite::Statement attach(db_, "ATTACH DATABASE ? AS src");
    attach.bind(1, merge_files::read_only_uri(file));
    attach.exec();
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

}  // namespace

MergeTarget::MergeTarget(SQLite::Database& db, const std::string& output, Copying copying)
    : db_(db), copying_(copying) {
  tables_ = classify_report_tables(db_);
  if (!tables_.unknown.empty()) {
    throw std::logic_error(fmt::format("{}: rcsim merge does not know how to merge the table(s) {}", output,
                                       join(tables_.unknown, ", ")));
  }
  for (const auto* group : {&tables_.run_scoped, &tables_.bench, &tables_.campaign}) {
    for (const auto& table : *group) columns_[table] = table_columns(db_, table);
  }
  if (copying_ == Copying::attach) {
    db_.exec("CREATE TEMP TABLE merge_run_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
    db_.exec("CREATE TEMP TABLE merge_bench_map (old_id INTEGER PRIMARY KEY, new_id INTEGER NOT NULL)");
  }
}

void MergeTarget::add(const std::string& file, const MergeStep& step, std::vector<MergeDuplicate>& duplicates) {
  SQLite::Database input(merge_files::read_only_uri(file), SQLite::OPEN_READONLY | SQLite::OPEN_URI);
  input.setBusyTimeout(5000);
  // Checked when its snapshot was read; again in case the file was replaced since. A read
  // transaction for the whole copy: one state of the input, even if it is being written.
  SQLite::Transaction reading(input);
  const int application_id = input.execAndGet("PRAGMA application_id").getInt();
  const int version = input.execAndGet("PRAGMA user_version").getInt();
  if (application_id != kReportApplicationId || version != kReportSchemaVersion) {
    throw InputError(file, "", fmt::format("changed during the merge (application_id {:#x}, report schema version {}, "
                                           "expected {:#x} and {})",
                                           static_cast<std::uint32_t>(application_id), version, kReportApplicationId,
                                           kReportSchemaVersion));
  }
  check_columns(input, file);
  if (copying_ == Copying::attach) {
    copy_attached(file, step);
  } else {
    if (!step.runs.empty()) {
      for (const auto& table : tables_.run_scoped) copy_rows(input, table, "run_id", step.runs);
    }
    if (!step.benches.empty()) {
      for (const auto& table : tables_.bench) copy_rows(input, table, "bench_id", step.benches);
    }
    if (step.campaign) copy_rows(input, "campaign", "", {});
    if (step.criteria) copy_rows(input, "criteria", "", {});
  }
  for (std::size_t i = step.first_duplicate; i < step.end_duplicate; ++i) compare_summaries(db_, input, duplicates[i]);
}

// The inputs have the output's schema version, so the same columns; said plainly if not.
void MergeTarget::check_columns(SQLite::Database& input, const std::string& file) const {
  for (const auto& [table, columns] : columns_) {
    const auto theirs = table_columns(input, table);
    if (theirs != columns) {
      throw InputError(file, "", fmt::format("table {} has the columns ({}), the output ({}): not a report of this "
                                             "rcsim's schema",
                                             table, join(theirs, ", "), join(columns, ", ")));
    }
  }
}

void MergeTarget::copy_rows(SQLite::Database& input, const std::string& table, const std::string& key,
                            const IdPairs& ids) {
  const std::vector<std::string>& columns = columns_.at(table);
  std::vector<std::string> names, placeholders;
  int key_column = -1;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    names.push_back(quoted(columns[c]));
    placeholders.emplace_back("?");
    if (columns[c] == key) key_column = static_cast<int>(c);
  }
  if (!key.empty() && key_column < 0) throw std::logic_error(fmt::format("table {} has no column {}", table, key));
  const std::unordered_map<std::int64_t, std::int64_t> new_ids(ids.begin(), ids.end());
  // The whole table in its order, the rows of other runs skipped: one pass over the input, where
  // a lookup by run would visit the index and the table for each row.
  RawStatement select(input, fmt::format("SELECT {} FROM main.{}", join(names, ", "), quoted(table)));
  RawStatement insert(db_, fmt::format("INSERT INTO main.{} ({}) VALUES ({})", quoted(table), join(names, ", "),
                                       join(placeholders, ", ")));
  const int n = static_cast<int>(columns.size());
  while (select.step()) {
    std::int64_t new_id = 0;
    if (key_column >= 0) {
      const auto it = new_ids.find(sqlite3_column_int64(select.get(), key_column));
      if (it == new_ids.end()) continue;
      new_id = it->second;
    }
    for (int c = 0; c < n; ++c) {
      insert.check(c == key_column ? sqlite3_bind_int64(insert.get(), c + 1, new_id)
                                   : bind_as_stored(insert.get(), c + 1, select.get(), c));
    }
    insert.step();
    insert.reset();
  }
}

void MergeTarget::copy_attached(const std::string& file, const MergeStep& step) {
  if (!step.copies()) return;
  const AttachedInput attached(db_, file);
  SQLite::Transaction transaction(db_);
  db_.exec("PRAGMA defer_foreign_keys = ON");  // switched off again by every commit
  const auto fill_map = [this](const char* map, const IdPairs& ids) {
    db_.exec(fmt::format("DELETE FROM temp.{}", map));
    SQLite::Statement insert(db_, fmt::format("INSERT INTO temp.{} VALUES (?, ?)", map));
    for (const auto& [from, to] : ids) {
      insert.bind(1, from);
      insert.bind(2, to);
      insert.exec();
      insert.reset();
    }
  };
  if (!step.runs.empty()) {
    fill_map("merge_run_map", step.runs);
    for (const auto& table : tables_.run_scoped) db_.exec(insert_select_sql(table, "run_id", "merge_run_map"));
  }
  if (!step.benches.empty()) {
    fill_map("merge_bench_map", step.benches);
    for (const auto& table : tables_.bench) db_.exec(insert_select_sql(table, "bench_id", "merge_bench_map"));
  }
  if (step.campaign) db_.exec(insert_select_sql("campaign", "", ""));
  if (step.criteria) db_.exec(insert_select_sql("criteria", "", ""));
  transaction.commit();
}

// The rows of src's `table` whose `key` is in the temporary `map`, each under its new id; every
// row when `key` is empty.
std::string MergeTarget::insert_select_sql(const std::string& table, const std::string& key,
                                           const std::string& map) const {
  std::vector<std::string> names, selected;
  for (const auto& column : columns_.at(table)) {
    names.push_back(quoted(column));
    selected.push_back(column == key ? "m.new_id" : "s." + quoted(column));
  }
  if (key.empty()) {
    return fmt::format("INSERT INTO main.{0} ({1}) SELECT {1} FROM src.{0}", quoted(table), join(names, ", "));
  }
  return fmt::format("INSERT INTO main.{0} ({1}) SELECT {2} FROM src.{0} AS s JOIN temp.{3} AS m ON m.old_id = s.{4}",
                     quoted(table), join(names, ", "), join(selected, ", "), map, quoted(key));
}

void compare_summaries(SQLite::Database& output, SQLite::Database& input, MergeDuplicate& d) {
  std::vector<std::string> figures;
  for (const auto& column : table_columns(output, "summaries")) {
    if (column != "run_id" && kTimingColumns.count(column) == 0) figures.push_back(column);
  }
  std::vector<std::string> columns;
  for (const auto& figure : figures) columns.push_back(quoted(figure));
  const std::string sql = fmt::format("SELECT {} FROM main.summaries WHERE run_id = ?", join(columns, ", "));
  SQLite::Statement theirs(input, sql), kept(output, sql);
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

}  // namespace rcsim::replay::merge_copy
