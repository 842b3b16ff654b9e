#include "replay/store/decoded_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "metrics/target_class.hpp"

namespace rcsim::replay {

namespace {

using Row = std::vector<DecodedValue>;

constexpr std::string_view kInteger = "INTEGER", kReal = "REAL", kText = "TEXT";

DecodedValue real(double v) { return std::isfinite(v) ? DecodedValue(v) : DecodedValue(); }
DecodedValue whole(std::int64_t v) { return DecodedValue(v); }
DecodedValue index_or_none(int v) { return v < 0 ? DecodedValue() : DecodedValue(std::int64_t{v}); }
template <typename T>
DecodedValue whole_if(bool has, T v) {
  return has ? DecodedValue(static_cast<std::int64_t>(v)) : DecodedValue();
}

const std::vector<DecodedColumn> kCycleColumns = {
    {"run_id", kInteger},
    {"cycle", kInteger},
    {"sensor", kInteger},
    {"t_s", kReal},
    {"sensor_x_m", kReal},
    {"sensor_y_m", kReal},
    {"sensor_yaw_rad", kReal},
    {"n_recorded", kInteger},
    {"n_simulated", kInteger},
    {"n_assigned", kInteger},
    {"gospa_m", kReal},
    {"gospa_localisation_mp", kReal},
    {"gospa_missed_mp", kReal},
    {"gospa_false_mp", kReal},
    {"ospa_m", kReal},
    {"merge_recorded", kInteger},
    {"merge_simulated", kInteger},
    {"merge_matched", kInteger},
    {"n_object_recorded", kInteger},
    {"n_object_simulated", kInteger},
    {"n_background_recorded", kInteger},
    {"n_background_simulated", kInteger},
    {"gospa_object_m", kReal},
    {"ospa_object_m", kReal}};

Row cycle_row(std::int64_t run_id, const StoredCycle& c) {
  const auto classes = c.classes.value_or(StoredCycle::Classes{});
  const bool has = c.classes.has_value();
  return {whole(run_id),
          whole(c.cycle),
          whole(c.sensor),
          real(c.t_s),
          c.X_WS ? real(c.X_WS->x_m) : DecodedValue(),
          c.X_WS ? real(c.X_WS->y_m) : DecodedValue(),
          c.X_WS ? real(c.X_WS->yaw_rad) : DecodedValue(),
          whole(c.n_recorded),
          whole(c.n_simulated),
          whole(c.n_assigned),
          real(c.gospa_m),
          real(c.gospa_localisation_mp),
          real(c.gospa_missed_mp),
          real(c.gospa_false_mp),
          real(c.ospa_m),
          whole(c.merge_recorded),
          whole(c.merge_simulated),
          whole(c.merge_matched),
          whole_if(has, classes.n_object_recorded),
          whole_if(has, classes.n_object_simulated),
          whole_if(has, classes.n_background_recorded),
          whole_if(has, classes.n_background_simulated),
          has ? real(classes.gospa_object_m) : DecodedValue(),
          has ? real(classes.ospa_object_m) : DecodedValue()};
}

const std::vector<DecodedColumn> kTargetColumns = {
    {"run_id", kInteger},
    {"cycle", kInteger},
    {"sensor", kInteger},
    {"origin", kText},
    {"idx", kInteger},
    {"track_id", kInteger},
    {"range_m", kReal},
    {"azimuth_rad", kReal},
    {"range_rate_mps", kReal},
    {"amplitude_db", kReal},
    {"x_s_m", kReal},
    {"y_s_m", kReal},
    {"object", kInteger},
    {"match_idx", kInteger},
    {"merge_artefact", kInteger},
    {"target_class", kText},
    {"x_o_m", kReal},
    {"y_o_m", kReal},
    {"rcs_dbsm", kReal},
    {"snr_db", kReal},
    {"elevation_rad", kReal}};

Row target_row(std::int64_t run_id, const StoredTarget& t) {
  const Vec2 p_ST_S = t.p_ST_S();
  return {whole(run_id),
          whole(t.cycle),
          whole(t.sensor),
          DecodedValue(std::string(t.simulated ? "simulated" : "recorded")),
          whole(t.idx),
          index_or_none(t.track_id),
          real(t.range_m),
          real(t.azimuth_rad),
          real(t.range_rate_mps),
          real(t.amplitude_db),
          real(p_ST_S.x()),
          real(p_ST_S.y()),
          index_or_none(t.object),
          index_or_none(t.match_idx),
          whole(t.merge_artefact ? 1 : 0),
          t.target_class ? DecodedValue(std::string(metrics::target_class_name(*t.target_class))) : DecodedValue(),
          t.p_OT_O ? real(t.p_OT_O->x()) : DecodedValue(),
          t.p_OT_O ? real(t.p_OT_O->y()) : DecodedValue(),
          real(t.rcs_dbsm),
          real(t.snr_db),
          real(t.elevation_rad)};
}

const std::vector<DecodedColumn> kObjectColumns = {
    {"run_id", kInteger},
    {"cycle", kInteger},
    {"object", kInteger},
    {"x_m", kReal},
    {"y_m", kReal},
    {"yaw_rad", kReal}};

Row object_row(std::int64_t run_id, const StoredObjectState& s) {
  return {whole(run_id), whole(s.cycle), whole(s.object), real(s.X_WO.x_m), real(s.X_WO.y_m), real(s.X_WO.yaw_rad)};
}

}  // namespace

std::optional<DecodedTable> decoded_table_from_name(std::string_view name) {
  if (name == "cycles") return DecodedTable::cycles;
  if (name == "targets") return DecodedTable::targets;
  if (name == "objects") return DecodedTable::objects;
  return std::nullopt;
}

std::string_view decoded_table_name(DecodedTable table) {
  switch (table) {
    case DecodedTable::cycles: return "cycles";
    case DecodedTable::targets: return "targets";
    case DecodedTable::objects: return "objects";
  }
  return "";
}

nlohmann::ordered_json decoded_value_json(const DecodedValue& value) {
  return std::visit(
      [](const auto& x) -> nlohmann::ordered_json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>) {
          return nullptr;
        } else {
          return x;
        }
      },
      value);
}

const std::vector<DecodedColumn>& decoded_columns(DecodedTable table) {
  switch (table) {
    case DecodedTable::cycles: return kCycleColumns;
    case DecodedTable::targets: return kTargetColumns;
    case DecodedTable::objects: return kObjectColumns;
  }
  return kObjectColumns;
}

void for_each_decoded_row(SQLite::Database& db, DecodedTable table, std::int64_t run_id, CycleSpan span,
                          const std::function<void(const std::vector<DecodedValue>&)>& visit) {
  switch (table) {
    case DecodedTable::cycles:
      for_each_cycle(db, run_id, span, [&](const StoredCycle& c) { visit(cycle_row(run_id, c)); });
      return;
    case DecodedTable::targets:
      for_each_target(db, run_id, span, [&](const StoredTarget& t) { visit(target_row(run_id, t)); });
      return;
    case DecodedTable::objects:
      for_each_object_state(db, run_id, span, [&](const StoredObjectState& s) { visit(object_row(run_id, s)); });
      return;
  }
}

void DecodedChunk::read(SQLite::Database& db, DecodedTable table, std::int64_t run_id, CycleSpan span) {
  table_ = table;
  run_id_ = run_id;
  cycles_.clear();
  targets_.clear();
  objects_.clear();
  // Their capacity too: a chunk of many targets is not kept for one of few.
  cycles_.shrink_to_fit();
  targets_.shrink_to_fit();
  objects_.shrink_to_fit();
  switch (table) {
    case DecodedTable::cycles:
      for_each_cycle(db, run_id, span, [&](const StoredCycle& c) { cycles_.push_back(c); });
      return;
    case DecodedTable::targets:
      for_each_target(db, run_id, span, [&](const StoredTarget& t) { targets_.push_back(t); });
      return;
    case DecodedTable::objects:
      for_each_object_state(db, run_id, span, [&](const StoredObjectState& s) { objects_.push_back(s); });
      return;
  }
}

std::size_t DecodedChunk::size() const {
  switch (table_) {
    case DecodedTable::cycles: return cycles_.size();
    case DecodedTable::targets: return targets_.size();
    case DecodedTable::objects: return objects_.size();
  }
  return 0;
}

std::vector<DecodedValue> DecodedChunk::row(std::size_t i) const {
  switch (table_) {
    case DecodedTable::cycles: return cycle_row(run_id_, cycles_.at(i));
    case DecodedTable::targets: return target_row(run_id_, targets_.at(i));
    case DecodedTable::objects: return object_row(run_id_, objects_.at(i));
  }
  return {};
}

int last_stored_cycle(SQLite::Database& db, std::int64_t run_id) {
  // From the blocks' rows, never their decoded columns (issue 51: decoding every block at each
  // call made each xFilter of a join read the whole run, quadratic in its length): the last
  // block's start on the primary key, then the ends of the blocks that may reach furthest (a
  // block holds at most kBlockCycles cycles, which its decoding checks).
  SQLite::Statement q(db, "SELECT cycles, (SELECT MAX(first_cycle + cycles - 1) FROM cycle_blocks WHERE run_id = ?1 AND "
                          "first_cycle >= (SELECT MAX(first_cycle) FROM cycle_blocks WHERE run_id = ?1) - ?2) "
                          "FROM runs WHERE run_id = ?1");
  q.bind(1, static_cast<std::int64_t>(run_id));
  q.bind(2, static_cast<std::int64_t>(kBlockCycles));
  if (!q.executeStep()) throw std::runtime_error(fmt::format("no run with id {} in the report database", run_id));
  if (q.getColumn(1).isNull()) return -1;
  // Within the cycles the run says it has, as its blocks are checked when decoded.
  const std::int64_t last = std::min(q.getColumn(1).getInt64(), q.getColumn(0).getInt64() - 1);
  return static_cast<int>(std::clamp<std::int64_t>(last, -1, std::numeric_limits<int>::max()));
}

int next_stored_cycle(SQLite::Database& db, std::int64_t run_id, std::int64_t from) {
  // Two lookups on the primary key (run_id, first_cycle, sensor), never a scan of the run's blocks
  // (an own-clocks run stores a block per cycle: a scan per call made an export quadratic): the
  // blocks that start at or before `from` and reach it (a short scan back: blocks of one cycle
  // range, one per sensor), else the first block after it.
  SQLite::Statement covering(db, "SELECT MAX(first_cycle + cycles - 1) FROM cycle_blocks WHERE run_id = ?1 AND first_cycle <= ?2 AND "
                                 "first_cycle > ?2 - ?3");
  covering.bind(1, static_cast<std::int64_t>(run_id));
  covering.bind(2, static_cast<std::int64_t>(from));
  covering.bind(3, static_cast<std::int64_t>(kBlockCycles));
  if (covering.executeStep() && !covering.getColumn(0).isNull() && covering.getColumn(0).getInt64() >= from) {
    return from >= 0 && from <= std::numeric_limits<int>::max() ? static_cast<int>(from) : -1;
  }
  SQLite::Statement after(db, "SELECT MIN(first_cycle) FROM cycle_blocks WHERE run_id = ?1 AND first_cycle > ?2");
  after.bind(1, static_cast<std::int64_t>(run_id));
  after.bind(2, static_cast<std::int64_t>(from));
  if (!after.executeStep() || after.getColumn(0).isNull()) return -1;
  const long long cycle = after.getColumn(0).getInt64();
  return cycle >= 0 && cycle <= std::numeric_limits<int>::max() ? static_cast<int>(cycle) : -1;
}

}  // namespace rcsim::replay
