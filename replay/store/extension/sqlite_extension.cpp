// rcsim's SQLite extension (docs/sql.md): loaded into sqlite3 (`.load build/lib/rcsim`), Python's
// sqlite3 or any SQLite client, it serves a report database's per-cycle, per-target and per-object
// rows, stored as compact blocks, as the read-only tables `cycles`, `targets` and `objects`, with
// the columns of `rcsim export` (replay/store/decoded_rows.hpp):
//   SELECT cycle, gospa_m FROM cycles WHERE run_id = 1;
// The rows are decoded a block of cycles at a time and held as the store's records (a row of values
// is made only for the row SQLite reads), so memory stays flat in a run's length; a
// constraint on run_id and on cycle (=, <, <=, >, >=) reads only the blocks it needs.
#include <sqlite3ext.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "replay/store/decoded_rows.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/report_store.hpp"

SQLITE_EXTENSION_INIT1

namespace rcsim::sqlite_extension {

namespace {

using replay::DecodedTable;
using replay::DecodedValue;

// Cycles decoded at a time: one stored block (replay/store/run_rows.hpp).
constexpr int kChunkCycles = replay::kBlockCycles;

// idxNum bits of a plan: which constraints xFilter receives, in this order.
constexpr int kRunEquals = 1, kCycleEquals = 2, kCycleLowest = 4, kCycleHighest = 8;

struct Table {
  sqlite3_vtab base{};  // first: SQLite hands back a pointer to it
  DecodedTable table = DecodedTable::cycles;
  std::string path;     // the connection's main database
};

struct Cursor {
  sqlite3_vtab_cursor base{};  // first
  std::unique_ptr<replay::ReportDatabase> db;
  std::vector<std::int64_t> runs;
  std::size_t run_index = 0;
  replay::CycleSpan wanted;  // from the cycle constraints
  int next_first_cycle = 0;  // of the current run's next chunk
  int last_cycle = -1;       // the current run's last stored cycle
  replay::DecodedChunk rows;  // the store's records, a row of values made for the current one only
  std::size_t row = 0;
  std::vector<DecodedValue> current;  // row `current_row` of `rows` as values, made when a column is asked for
  std::size_t current_row = static_cast<std::size_t>(-1);
  sqlite3_int64 rowid = 0;
};

Table& table_of(sqlite3_vtab* vtab) { return *reinterpret_cast<Table*>(vtab); }
Cursor& cursor_of(sqlite3_vtab_cursor* cursor) { return *reinterpret_cast<Cursor*>(cursor); }

int fail(sqlite3_vtab* vtab, const std::string& message) {
  sqlite3_free(vtab->zErrMsg);
  vtab->zErrMsg = sqlite3_mprintf("%s", message.c_str());
  return SQLITE_ERROR;
}

std::string declaration(DecodedTable table) {
  std::string sql = "CREATE TABLE x(";
  const auto& columns = replay::decoded_columns(table);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    sql += (i ? ", " : "") + columns[i].name + " " + std::string(columns[i].sql_type);
  }
  return sql + ")";
}

int connect(sqlite3* db, void* table_kind, int, const char* const*, sqlite3_vtab** out, char** error) {
  const DecodedTable table = *static_cast<const DecodedTable*>(table_kind);
  const char* path = sqlite3_db_filename(db, "main");
  if (path == nullptr || *path == '\0') {
    *error = sqlite3_mprintf("rcsim: %s reads the report database opened as main; this connection's is in memory",
                             std::string(replay::decoded_table_name(table)).c_str());
    return SQLITE_ERROR;
  }
  const int declared = sqlite3_declare_vtab(db, declaration(table).c_str());
  if (declared != SQLITE_OK) return declared;
  auto* t = new Table;
  t->table = table;
  t->path = path;
  *out = &t->base;
  return SQLITE_OK;
}

int disconnect(sqlite3_vtab* vtab) {
  delete &table_of(vtab);
  return SQLITE_OK;
}

// Uses `run_id = ?`, and `cycle = ?` or the last lower and upper bounds on cycle given, to narrow
// the runs and blocks read; SQLite checks every constraint again (omit = 0): a value that is not a
// number (`cycle <= 'zzz'`) or not a whole one (`run_id = 1.5`) narrows nothing here (issue 51).
int best_index(sqlite3_vtab*, sqlite3_index_info* info) {
  int run = -1, equals = -1, lowest = -1, highest = -1;
  for (int i = 0; i < info->nConstraint; ++i) {
    const auto& c = info->aConstraint[i];
    if (!c.usable) continue;
    if (c.iColumn == 0 && c.op == SQLITE_INDEX_CONSTRAINT_EQ) run = i;
    if (c.iColumn != 1) continue;
    if (c.op == SQLITE_INDEX_CONSTRAINT_EQ) equals = i;
    if (c.op == SQLITE_INDEX_CONSTRAINT_GE || c.op == SQLITE_INDEX_CONSTRAINT_GT) lowest = i;
    if (c.op == SQLITE_INDEX_CONSTRAINT_LE || c.op == SQLITE_INDEX_CONSTRAINT_LT) highest = i;
  }
  if (equals >= 0) lowest = highest = -1;
  int argument = 0;
  info->idxNum = 0;
  const auto use = [&](int constraint, int bit, bool omit) {
    if (constraint < 0) return;
    info->idxNum |= bit;
    info->aConstraintUsage[constraint].argvIndex = ++argument;
    info->aConstraintUsage[constraint].omit = omit ? 1 : 0;
  };
  use(run, kRunEquals, false);
  use(equals, kCycleEquals, false);
  use(lowest, kCycleLowest, false);
  use(highest, kCycleHighest, false);
  info->estimatedCost = (run >= 0 ? 1.0e4 : 1.0e6) / (info->idxNum > kRunEquals ? 10.0 : 1.0);
  info->estimatedRows = static_cast<sqlite3_int64>(info->estimatedCost);
  return SQLITE_OK;
}

int open_cursor(sqlite3_vtab*, sqlite3_vtab_cursor** out) {
  auto* c = new Cursor;
  *out = &c->base;
  return SQLITE_OK;
}

int close_cursor(sqlite3_vtab_cursor* cursor) {
  delete &cursor_of(cursor);
  return SQLITE_OK;
}

// Decodes the next chunk of cycles holding rows, moving on to the next run where one ends;
// leaves `rows` empty at the end.
void load_next_chunk(Cursor& c, DecodedTable table) {
  c.rows = replay::DecodedChunk{};
  c.row = 0;
  c.current_row = static_cast<std::size_t>(-1);
  const auto next_run = [&c] {
    if (++c.run_index < c.runs.size()) {
      c.last_cycle = replay::last_stored_cycle(*c.db, c.runs[c.run_index]);
      c.next_first_cycle = std::max(0, c.wanted.first);
    }
  };
  while (c.rows.size() == 0 && c.run_index < c.runs.size()) {
    const std::int64_t run = c.runs[c.run_index];
    const int last = std::min(c.last_cycle, c.wanted.last);
    // From the next cycle a stored block holds (the spans between are empty: never walked), in
    // 64 bits (a damaged report may claim 2^31 - 1 cycles): each call decodes one chunk at most.
    const int first = c.next_first_cycle > last ? -1 : replay::next_stored_cycle(*c.db, run, c.next_first_cycle);
    if (first < 0 || first > last) {
      next_run();
      continue;
    }
    const replay::CycleSpan chunk{first, static_cast<int>(std::min<std::int64_t>(last, std::int64_t{first} + kChunkCycles - 1))};
    c.rows.read(*c.db, table, run, chunk);
    if (chunk.last >= last) {
      next_run();
    } else {
      c.next_first_cycle = chunk.last + 1;
    }
  }
}

int clamp_to_int(sqlite3_int64 v) {
  return static_cast<int>(std::clamp<sqlite3_int64>(v, 0, std::numeric_limits<int>::max()));
}

// A constraint's value as a bound on cycle, rounded outwards (`upward` for an upper bound): only an
// integer or a real narrows what is read; text, a blob or NULL compare by SQLite's own rules, so
// they leave the bound open (nullopt) and SQLite's check of every row decides.
std::optional<int> cycle_bound(sqlite3_value* value, bool upward) {
  switch (sqlite3_value_type(value)) {
    case SQLITE_INTEGER:
      return clamp_to_int(sqlite3_value_int64(value));
    case SQLITE_FLOAT: {
      const double v = sqlite3_value_double(value);
      if (std::isnan(v)) return std::nullopt;
      const double rounded = std::clamp(upward ? std::ceil(v) : std::floor(v), 0.0, double{std::numeric_limits<int>::max()});
      return static_cast<int>(rounded);
    }
    default:
      return std::nullopt;
  }
}

// Whether run `id` may equal `value`: an integer or a whole real names a run; anything else leaves
// the runs to SQLite's check (a real with a fraction equals none, which SQLite finds).
bool may_be_run(std::int64_t id, sqlite3_value* value) {
  switch (sqlite3_value_type(value)) {
    case SQLITE_INTEGER:
      return sqlite3_value_int64(value) == id;
    case SQLITE_FLOAT:
      return sqlite3_value_double(value) == static_cast<double>(id);
    default:
      return true;
  }
}

int filter(sqlite3_vtab_cursor* cursor, int plan, const char*, int argc, sqlite3_value** argv) {
  Cursor& c = cursor_of(cursor);
  const Table& t = table_of(cursor->pVtab);
  try {
    if (!c.db) c.db = replay::open_report_database_read_only(t.path);
    int argument = 0;
    c.runs = replay::report::run_ids(*c.db);
    if ((plan & kRunEquals) != 0 && argument < argc) {
      sqlite3_value* run = argv[argument++];
      c.runs.erase(std::remove_if(c.runs.begin(), c.runs.end(), [&](std::int64_t id) { return !may_be_run(id, run); }), c.runs.end());
    }
    c.wanted = replay::CycleSpan{};
    // `cycle > 5` reads from cycle 5 on, `cycle < 9` to cycle 9: SQLite drops the bound itself.
    const auto bound = [&](int& field, bool upward) {
      if (const auto value = cycle_bound(argv[argument++], upward)) field = *value;
    };
    if ((plan & kCycleEquals) != 0 && argument < argc) {
      sqlite3_value* value = argv[argument++];
      if (const auto low = cycle_bound(value, false)) c.wanted.first = *low;
      if (const auto high = cycle_bound(value, true)) c.wanted.last = *high;
    }
    if ((plan & kCycleLowest) != 0 && argument < argc) bound(c.wanted.first, false);
    if ((plan & kCycleHighest) != 0 && argument < argc) bound(c.wanted.last, true);
    c.run_index = 0;
    c.rowid = 0;
    c.last_cycle = c.runs.empty() ? -1 : replay::last_stored_cycle(*c.db, c.runs.front());
    c.next_first_cycle = c.wanted.first;
    load_next_chunk(c, t.table);
    return SQLITE_OK;
  } catch (const InputError& e) {
    return fail(cursor->pVtab, std::string("rcsim: ") + e.what());  // names the file itself
  } catch (const std::exception& e) {
    return fail(cursor->pVtab, std::string("rcsim: ") + t.path + ": " + e.what());
  }
}

int next(sqlite3_vtab_cursor* cursor) {
  Cursor& c = cursor_of(cursor);
  ++c.rowid;
  if (++c.row < c.rows.size()) return SQLITE_OK;
  try {
    load_next_chunk(c, table_of(cursor->pVtab).table);
    return SQLITE_OK;
  } catch (const std::exception& e) {
    return fail(cursor->pVtab, std::string("rcsim: ") + table_of(cursor->pVtab).path + ": " + e.what());
  }
}

int eof(sqlite3_vtab_cursor* cursor) {
  const Cursor& c = cursor_of(cursor);
  return c.row >= c.rows.size() ? 1 : 0;
}

int column(sqlite3_vtab_cursor* cursor, sqlite3_context* context, int index) {
  Cursor& c = cursor_of(cursor);
  if (c.current_row != c.row) {
    try {
      c.current = c.rows.row(c.row);
    } catch (const std::exception& e) {
      sqlite3_result_error(context, e.what(), -1);
      return SQLITE_ERROR;
    }
    c.current_row = c.row;
  }
  const DecodedValue& value = c.current[static_cast<std::size_t>(index)];
  if (const auto* number = std::get_if<std::int64_t>(&value)) {
    sqlite3_result_int64(context, *number);
  } else if (const auto* real = std::get_if<double>(&value)) {
    sqlite3_result_double(context, *real);
  } else if (const auto* text = std::get_if<std::string>(&value)) {
    sqlite3_result_text(context, text->c_str(), static_cast<int>(text->size()), SQLITE_TRANSIENT);
  } else {
    sqlite3_result_null(context);
  }
  return SQLITE_OK;
}

int rowid(sqlite3_vtab_cursor* cursor, sqlite3_int64* out) {
  *out = cursor_of(cursor).rowid;
  return SQLITE_OK;
}

// Eponymous-only (no xCreate): the tables exist in every connection that loaded the extension.
sqlite3_module make_module() {
  sqlite3_module m{};
  m.iVersion = 0;
  m.xConnect = connect;
  m.xBestIndex = best_index;
  m.xDisconnect = disconnect;
  m.xOpen = open_cursor;
  m.xClose = close_cursor;
  m.xFilter = filter;
  m.xNext = next;
  m.xEof = eof;
  m.xColumn = column;
  m.xRowid = rowid;
  return m;
}

const sqlite3_module kModule = make_module();
const DecodedTable kTables[] = {DecodedTable::cycles, DecodedTable::targets, DecodedTable::objects};

}  // namespace

}  // namespace rcsim::sqlite_extension

// The entry point SQLite derives from the file name rcsim.so.
extern "C" __attribute__((visibility("default"))) int sqlite3_rcsim_init(sqlite3* db, char** error,
                                                                         const sqlite3_api_routines* api) {
  SQLITE_EXTENSION_INIT2(api);
  using namespace rcsim::sqlite_extension;
  for (const DecodedTable& table : kTables) {
    const std::string name(rcsim::replay::decoded_table_name(table));
    const int created = sqlite3_create_module(db, name.c_str(), &kModule, const_cast<DecodedTable*>(&table));
    if (created != SQLITE_OK) {
      *error = sqlite3_mprintf("rcsim: cannot create the table %s", name.c_str());
      return created;
    }
  }
  return SQLITE_OK;
}
