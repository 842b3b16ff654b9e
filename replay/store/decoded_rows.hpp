#pragma once
// A run's per-cycle, per-target and per-object rows decoded from the report's compact blocks
// (schemas/report-database.md, "Plain rows"): the one definition of their columns, which
// `rcsim export` writes as CSV or JSON Lines and the SQLite extension (app/sqlite/) serves as the
// tables `cycles`, `targets` and `objects`.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "replay/store/report_database.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

enum class DecodedTable { cycles, targets, objects };

// "cycles", "targets", "objects"; nullopt for any other name.
std::optional<DecodedTable> decoded_table_from_name(std::string_view name);
std::string_view decoded_table_name(DecodedTable table);

// A value: nothing (SQL NULL, an empty CSV field, JSON null), a whole number, a real or a text.
using DecodedValue = std::variant<std::monostate, std::int64_t, double, std::string>;

// A column: its name and its SQL type (INTEGER, REAL or TEXT).
struct DecodedColumn {
  std::string name;
  std::string_view sql_type;
};

// A value as JSON: null, a whole number, a real or a text (rcsim export --format jsonl, the MCAP
// figures).
nlohmann::ordered_json decoded_value_json(const DecodedValue& value);

// The columns of `table`, in order; the first is always run_id, the second cycle.
const std::vector<DecodedColumn>& decoded_columns(DecodedTable table);

// The rows of `table` for `run_id` within `span`, in cycle order, each as values in the order of
// decoded_columns(table). A run stored with --store summary has cycles but no targets or objects.
void for_each_decoded_row(SQLite::Database& db, DecodedTable table, std::int64_t run_id, CycleSpan span,
                          const std::function<void(const std::vector<DecodedValue>&)>& visit);

// The rows of `table` for `run_id` within `span`, held as the store's own records (some 130 bytes
// a target, where its row of values takes some 850) and each made into values when asked for: what
// the SQLite extension holds between its steps (issue 51: a decoded 256-cycle block of the Astyx
// report's targets held as rows took 1 GB).
class DecodedChunk {
 public:
  // Replaces what the chunk holds with the rows of `table` for `run_id` within `span`.
  void read(SQLite::Database& db, DecodedTable table, std::int64_t run_id, CycleSpan span);
  std::size_t size() const;
  // Row `i` (< size()) as values in the order of decoded_columns(table).
  std::vector<DecodedValue> row(std::size_t i) const;

 private:
  DecodedTable table_ = DecodedTable::cycles;
  std::int64_t run_id_ = 0;
  std::vector<StoredCycle> cycles_;
  std::vector<StoredTarget> targets_;
  std::vector<StoredObjectState> objects_;
};

// The last cycle index stored for `run_id`, or -1 if it has none; throws for a run not stored.
int last_stored_cycle(SQLite::Database& db, std::int64_t run_id);

// The first cycle >= `from` that a stored block of `run_id` holds, or -1 if none does: a reader
// walks the blocks that are there, never every span a damaged report's cycle count claims (a
// report may say 2^31 - 1 cycles and hold one block).
int next_stored_cycle(SQLite::Database& db, std::int64_t run_id, std::int64_t from);

}  // namespace rcsim::replay
