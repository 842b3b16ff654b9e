#include "replay/store/run_rows.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "replay/store/packed_columns.hpp"

namespace rcsim::replay {

namespace {

using packed::ColumnReader;
using packed::ColumnWriter;
using packed::LinearPrediction;

// ---- The columns of the blocks, in table order (report_schema.cpp) ----

enum CycleColumn {
  kTime, kSensorX, kSensorY, kSensorYaw, kNRecorded, kNSimulated, kNAssigned, kGospa, kLocalisation, kMissed,
  kFalse, kOspa, kMergeRecorded, kMergeSimulated, kMergeMatched, kNObjectRecorded, kNObjectSimulated,
  kNBackgroundRecorded, kNBackgroundSimulated, kGospaObject, kOspaObject, kCycleColumns
};
constexpr std::array<const char*, kCycleColumns> kCycleColumnNames{
    "t_s", "sensor_x_m", "sensor_y_m", "sensor_yaw_rad", "n_recorded", "n_simulated", "n_assigned", "gospa_m",
    "gospa_localisation_mp", "gospa_missed_mp", "gospa_false_mp", "ospa_m", "merge_recorded", "merge_simulated",
    "merge_matched", "n_object_recorded", "n_object_simulated", "n_background_recorded", "n_background_simulated",
    "gospa_object_m", "ospa_object_m"};

enum TargetColumn {
  kListRecorded, kListSimulated, kTrack, kRange, kAzimuth, kRangeRate, kAmplitude, kObject, kMatch, kFlags, kXo, kYo,
  kRcs, kSnr, kElevation, kTargetColumns
};
constexpr std::array<const char*, kTargetColumns> kTargetColumnNames{
    "n_recorded", "n_simulated", "track_id", "range_m", "azimuth_rad", "range_rate_mps", "amplitude_db", "object",
    "match_idx", "flags", "x_o_m", "y_o_m", "rcs_dbsm", "snr_db", "elevation_rad"};

enum ObjectColumn { kNObjects, kObjectIndex, kObjectX, kObjectY, kObjectYaw, kObjectColumns };
constexpr std::array<const char*, kObjectColumns> kObjectColumnNames{"n_objects", "object", "x_m", "y_m", "yaw_rad"};

template <std::size_t N>
std::string column_list(const std::array<const char*, N>& names) {
  std::string list;
  for (const char* name : names) list += fmt::format("{}{}", list.empty() ? "" : ", ", name);
  return list;
}

std::string placeholders(std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) text += i ? ", ?" : "?";
  return text;
}

// ---- Predictions (packed_columns.hpp: each operation rounded once) ----

double gospa_prediction(double localisation_mp, double missed_mp, double false_mp, double order_p) {
  const double sum = localisation_mp + missed_mp + false_mp;  // as metrics/gospa.cpp adds them
  if (order_p == 2.0) return std::sqrt(sum);
  if (order_p == 1.0) return sum;
  return 0.0;
}

// OSPA's sum is the localisation plus c^p for each of the n - assigned targets left over or cut.
double ospa_prediction(double localisation_mp, int n_recorded, int n_simulated, int n_assigned, double half_cutoff_p,
                       double order_p) {
  const int n = std::max(n_recorded, n_simulated);
  if (n == 0) return 0.0;
  const double mean =
      (localisation_mp + packed::rounded_product(2.0 * half_cutoff_p, static_cast<double>(n - n_assigned))) /
      static_cast<double>(n);
  if (order_p == 2.0) return std::sqrt(mean);
  if (order_p == 1.0) return mean;
  return 0.0;
}

double part_prediction(double half_cutoff_p, int n, int n_assigned) {
  return packed::rounded_product(half_cutoff_p, static_cast<double>(n - n_assigned));
}

// ---- Binding and reading BLOBs ----

void bind_column(SQLite::Statement& s, int index, const ColumnWriter& column) {
  static const std::uint8_t kNothing = 0;
  const auto& bytes = column.bytes();
  // A zero-length BLOB needs a pointer: SQLite binds NULL for a null one.
  s.bind(index, bytes.empty() ? static_cast<const void*>(&kNothing) : bytes.data(), static_cast<int>(bytes.size()));
}

ColumnReader reader_of(const SQLite::Column& column, const char* name) {
  return {column.getBlob(), static_cast<std::size_t>(column.getBytes()), name};
}

constexpr std::uint64_t kNoClass = 3;
constexpr std::uint64_t kMergeFlag = 4;

std::uint64_t class_code(const std::optional<metrics::TargetClass>& c) {
  if (!c) return kNoClass;
  switch (*c) {
    case metrics::TargetClass::object: return 0;
    case metrics::TargetClass::stationary_background: return 1;
    case metrics::TargetClass::other: return 2;
  }
  return 2;
}

std::optional<metrics::TargetClass> class_of_code(std::uint64_t code) {
  switch (code) {
    case 0: return metrics::TargetClass::object;
    case 1: return metrics::TargetClass::stationary_background;
    case 2: return metrics::TargetClass::other;
    default: return std::nullopt;
  }
}

bool has_offset(const StoredTarget& t) { return t.object >= 0 && t.target_class.has_value(); }

// ---- Decoding blocks ----

// A block's first cycle and count, checked before anything is allocated for it: a block holds 1 to
// kBlockCycles cycles of its run, whatever a damaged or forged database says.
void check_block_span(int first_cycle, int n, int run_cycles, const char* table) {
  if (n < 1 || n > kBlockCycles || first_cycle < 0 || first_cycle > run_cycles - n) {
    throw std::runtime_error(fmt::format("report database: a row of {} claims {} cycles from cycle {}, in a run of {} "
                                         "cycles stored in blocks of 1 to {} (damaged)",
                                         table, n, first_cycle, run_cycles, kBlockCycles));
  }
}

std::vector<StoredCycle> decode_cycle_block(SQLite::Statement& q, int run_cycles) {
  // SELECT first_cycle, sensor, cycles, half_cutoff_p, order_p, <the columns>
  const int first_cycle = q.getColumn(0).getInt(), sensor = q.getColumn(1).getInt(), n = q.getColumn(2).getInt();
  check_block_span(first_cycle, n, run_cycles, "cycle_blocks");
  const double half_cutoff_p = q.getColumn(3).getDouble(), order_p = q.getColumn(4).getDouble();
  const auto column = [&](int c) { return q.getColumn(5 + c); };
  std::vector<ColumnReader> r;
  r.reserve(kCycleColumns);
  for (int c = 0; c < kCycleColumns; ++c) r.push_back(reader_of(column(c), kCycleColumnNames[static_cast<std::size_t>(c)]));
  const bool with_pose = !column(kSensorX).isNull();
  const bool with_classes = !column(kNObjectRecorded).isNull();
  LinearPrediction t, x, y, yaw;
  std::vector<StoredCycle> rows(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    StoredCycle& c = rows[static_cast<std::size_t>(k)];
    c.cycle = first_cycle + k;
    c.sensor = sensor;
    c.t_s = r[kTime].get_exact(t.predict());
    t.push(c.t_s);
    if (with_pose) {
      Pose2 X_WS;
      X_WS.x_m = r[kSensorX].get_exact(x.predict());
      X_WS.y_m = r[kSensorY].get_exact(y.predict());
      X_WS.yaw_rad = r[kSensorYaw].get_exact(yaw.predict());
      x.push(X_WS.x_m);
      y.push(X_WS.y_m);
      yaw.push(X_WS.yaw_rad);
      c.X_WS = X_WS;
    }
    c.n_recorded = static_cast<int>(r[kNRecorded].get_unsigned());
    c.n_simulated = static_cast<int>(r[kNSimulated].get_unsigned());
    c.n_assigned = static_cast<int>(r[kNAssigned].get_unsigned());
    c.gospa_localisation_mp = r[kLocalisation].get_exact(0.0);
    c.gospa_missed_mp = r[kMissed].get_exact(part_prediction(half_cutoff_p, c.n_recorded, c.n_assigned));
    c.gospa_false_mp = r[kFalse].get_exact(part_prediction(half_cutoff_p, c.n_simulated, c.n_assigned));
    c.gospa_m = r[kGospa].get_exact(gospa_prediction(c.gospa_localisation_mp, c.gospa_missed_mp, c.gospa_false_mp, order_p));
    c.ospa_m = r[kOspa].get_exact(ospa_prediction(c.gospa_localisation_mp, c.n_recorded, c.n_simulated, c.n_assigned,
                                                   half_cutoff_p, order_p));
    c.merge_recorded = static_cast<int>(r[kMergeRecorded].get_unsigned());
    c.merge_simulated = static_cast<int>(r[kMergeSimulated].get_unsigned());
    c.merge_matched = static_cast<int>(r[kMergeMatched].get_unsigned());
    if (with_classes) {
      StoredCycle::Classes k3;
      k3.n_object_recorded = static_cast<int>(r[kNObjectRecorded].get_unsigned());
      k3.n_object_simulated = static_cast<int>(r[kNObjectSimulated].get_unsigned());
      k3.n_background_recorded = static_cast<int>(r[kNBackgroundRecorded].get_unsigned());
      k3.n_background_simulated = static_cast<int>(r[kNBackgroundSimulated].get_unsigned());
      k3.gospa_object_m = r[kGospaObject].get_exact(c.gospa_m);
      k3.ospa_object_m = r[kOspaObject].get_exact(c.ospa_m);
      c.classes = k3;
    }
  }
  return rows;
}

// One target block, decoded a cycle at a time into a list whose capacity is reused: a block of 256
// cycles of a point cloud's 4,000 targets a cycle was 120 MB decoded whole, allocated and faulted
// in again on every pass (half a report's time). The block's bytes are copied out of the query.
class TargetBlockCursor {
 public:
  TargetBlockCursor(SQLite::Statement& q, int run_cycles) {
    // SELECT first_cycle, sensor, cycles, <the columns>
    first_cycle_ = q.getColumn(0).getInt(), sensor_ = q.getColumn(1).getInt(), n_ = q.getColumn(2).getInt();
    check_block_span(first_cycle_, n_, run_cycles, "target_blocks");
    const auto column = [&](int c) { return q.getColumn(3 + c); };
    bytes_.resize(static_cast<std::size_t>(kTargetColumns));
    r_.reserve(kTargetColumns);
    for (int c = 0; c < kTargetColumns; ++c) {
      const SQLite::Column col = column(c);
      auto& bytes = bytes_[static_cast<std::size_t>(c)];
      const auto* data = static_cast<const std::uint8_t*>(col.getBlob());
      bytes.assign(data, data + col.getBytes());
      r_.emplace_back(bytes.data(), bytes.size(), kTargetColumnNames[static_cast<std::size_t>(c)]);
    }
    optional_[0] = !column(kRcs).isNull(), optional_[1] = !column(kSnr).isNull(), optional_[2] = !column(kElevation).isNull();
    counts_.resize(static_cast<std::size_t>(n_));
    // Every target has its four float32 reals: counts that disagree are damage, not lists to
    // allocate. Each count is checked against the bytes before it is added (a sum of counts near
    // 2^64 wraps to a small total).
    const auto damaged = [&] {
      return std::runtime_error(fmt::format("report database: the target block of cycle {}, sensor {} is damaged", first_cycle_, sensor_));
    };
    const std::uint64_t targets_in_bytes = static_cast<std::uint64_t>(column(kRange).getBytes()) / 4;
    std::uint64_t total = 0;
    for (auto& [recorded, simulated] : counts_) {
      recorded = r_[kListRecorded].get_unsigned();
      simulated = r_[kListSimulated].get_unsigned();
      if (recorded > targets_in_bytes - total || simulated > targets_in_bytes - total - recorded) throw damaged();
      total += recorded + simulated;
    }
    if (static_cast<std::uint64_t>(column(kRange).getBytes()) != 4 * total) throw damaged();
  }
  bool done() const { return next_ == n_; }
  int cycle() const { return first_cycle_ + next_; }  // of the next list
  int sensor() const { return sensor_; }
  // The next cycle's lists into `list` (its vectors' capacity kept).
  void decode_next(StoredTargetList& list) {
    list.cycle = cycle();
    list.sensor = sensor_;
    list.recorded.resize(counts_[static_cast<std::size_t>(next_)].first);
    list.simulated.resize(counts_[static_cast<std::size_t>(next_)].second);
    for (auto* side : {&list.recorded, &list.simulated}) {
      for (std::size_t i = 0; i < side->size(); ++i) {
        StoredTarget& t = (*side)[i];
        t = StoredTarget{};
        t.cycle = list.cycle;
        t.sensor = sensor_;
        t.simulated = side == &list.simulated;
        t.idx = static_cast<int>(i);
        t.track_id = static_cast<int>(r_[kTrack].get_signed());
        t.range_m = r_[kRange].get_float32();
        t.azimuth_rad = r_[kAzimuth].get_float32();
        t.range_rate_mps = r_[kRangeRate].get_float32();
        t.amplitude_db = r_[kAmplitude].get_float32();
        t.object = static_cast<int>(r_[kObject].get_signed());
        t.match_idx = static_cast<int>(r_[kMatch].get_signed());
        const std::uint64_t flags = r_[kFlags].get_unsigned();
        t.target_class = class_of_code(flags & 3);
        t.merge_artefact = (flags & kMergeFlag) != 0;
        if (has_offset(t)) {
          const double x_m = r_[kXo].get_float32();
          t.p_OT_O = Vec2{x_m, r_[kYo].get_float32()};
        }
        if (optional_[0]) t.rcs_dbsm = r_[kRcs].get_float32();
        if (optional_[1]) t.snr_db = r_[kSnr].get_float32();
        if (optional_[2]) t.elevation_rad = r_[kElevation].get_float32();
      }
    }
    ++next_;
  }

 private:
  int first_cycle_ = 0, sensor_ = 0, n_ = 0, next_ = 0;
  std::vector<std::vector<std::uint8_t>> bytes_;
  std::vector<ColumnReader> r_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> counts_;
  bool optional_[3] = {false, false, false};
};

std::vector<StoredObjectState> decode_object_block(SQLite::Statement& q, int run_cycles, int run_objects) {
  // SELECT first_cycle, cycles, <the columns>
  const int first_cycle = q.getColumn(0).getInt(), n = q.getColumn(1).getInt();
  check_block_span(first_cycle, n, run_cycles, "object_state_blocks");
  std::vector<ColumnReader> r;
  r.reserve(kObjectColumns);
  for (int c = 0; c < kObjectColumns; ++c) {
    r.push_back(reader_of(q.getColumn(2 + c), kObjectColumnNames[static_cast<std::size_t>(c)]));
  }
  std::vector<int> counts(static_cast<std::size_t>(n));
  for (int& count : counts) {
    const std::uint64_t stored = r[kNObjects].get_unsigned();
    // A cycle holds each of the run's objects once at most.
    if (stored > static_cast<std::uint64_t>(run_objects)) {
      throw std::runtime_error(fmt::format("report database: a row of object_state_blocks claims {} objects in a cycle "
                                           "of a run of {} objects (damaged)",
                                           stored, run_objects));
    }
    count = static_cast<int>(stored);
  }
  std::unordered_map<int, std::array<LinearPrediction, 3>> predictions;
  std::vector<StoredObjectState> states;
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < counts[static_cast<std::size_t>(k)]; ++i) {
      StoredObjectState s;
      s.cycle = first_cycle + k;
      s.object = static_cast<int>(r[kObjectIndex].get_unsigned());
      auto& p = predictions[s.object];
      s.X_WO.x_m = r[kObjectX].get_exact(p[0].predict());
      s.X_WO.y_m = r[kObjectY].get_exact(p[1].predict());
      s.X_WO.yaw_rad = r[kObjectYaw].get_exact(p[2].predict());
      p[0].push(s.X_WO.x_m);
      p[1].push(s.X_WO.y_m);
      p[2].push(s.X_WO.yaw_rad);
      states.push_back(s);
    }
  }
  return states;
}

// Visits the rows of blocks that arrive in the order of their first cycle, one sensor after the
// other, in cycle order and by sensor within a cycle: a row is released once no later block can
// hold its cycle.
template <class Row>
class CycleOrder {
 public:
  CycleOrder(CycleSpan span, const std::function<void(const Row&)>& visit) : span_(span), visit_(visit) {}
  void add_block(int first_cycle, std::vector<Row> rows) {
    release_before(first_cycle);
    for (Row& row : rows) {
      if (span_.contains(row.cycle)) pending_.push_back(std::move(row));
    }
  }
  void finish() { release_before(std::numeric_limits<int>::max()); }

 private:
  void release_before(int cycle) {
    std::stable_sort(pending_.begin(), pending_.end(), [](const Row& a, const Row& b) {
      return a.cycle != b.cycle ? a.cycle < b.cycle : a.sensor < b.sensor;
    });
    std::size_t released = 0;
    while (released < pending_.size() && pending_[released].cycle < cycle) visit_(pending_[released++]);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(released));
  }
  CycleSpan span_;
  const std::function<void(const Row&)>& visit_;
  std::vector<Row> pending_;
};

// The blocks of a run that overlap `span`, by first cycle and sensor. A block holds at most
// kBlockCycles cycles (checked as read), so the ones that overlap start no earlier than that
// before the span: the lower bound keeps the index's range to them (without it every query
// walked the run's blocks from its first, quadratic in the run's length).
SQLite::Statement block_query(SQLite::Database& db, const std::string& columns, const char* table, std::int64_t run_id,
                              CycleSpan span, bool by_sensor) {
  SQLite::Statement q(db, fmt::format("SELECT {} FROM {} WHERE run_id = ? AND first_cycle >= ? AND first_cycle <= ? "
                                      "AND first_cycle + cycles > ? ORDER BY first_cycle{}",
                                      columns, table, by_sensor ? ", sensor" : ""));
  q.bind(1, run_id);
  q.bind(2, static_cast<std::int64_t>(span.first) - kBlockCycles + 1);
  q.bind(3, span.last);
  q.bind(4, span.first);
  return q;
}

}  // namespace

std::string_view store_level_name(StoreLevel level) { return level == StoreLevel::full ? "full" : "summary"; }

StoreLevel store_level_from_name(std::string_view name) {
  if (name == "full") return StoreLevel::full;
  if (name == "summary") return StoreLevel::summary;
  throw std::invalid_argument("unknown store level '" + std::string(name) + "' (full, summary)");
}

Vec2 StoredTarget::p_ST_S() const { return point_from_polar(range_m, azimuth_rad); }

namespace {

// The cycles of a run as `runs` holds them: what its blocks are checked against.
int stored_run_cycles(SQLite::Database& db, std::int64_t run_id) {
  SQLite::Statement q(db, "SELECT cycles FROM runs WHERE run_id = ?");
  q.bind(1, run_id);
  if (!q.executeStep()) throw std::runtime_error(fmt::format("no run with id {} in the report database", run_id));
  return q.getColumn(0).getInt();
}

// The objects of a run as `run_objects` holds them.
int stored_run_objects(SQLite::Database& db, std::int64_t run_id) {
  SQLite::Statement q(db, "SELECT count(*) FROM run_objects WHERE run_id = ?");
  q.bind(1, run_id);
  q.executeStep();
  return q.getColumn(0).getInt();
}

}  // namespace

StoreLevel run_store_level(SQLite::Database& db, std::int64_t run_id) {
  SQLite::Statement q(db, "SELECT store FROM runs WHERE run_id = ?");
  q.bind(1, run_id);
  if (!q.executeStep()) throw std::runtime_error(fmt::format("no run with id {} in the report database", run_id));
  return store_level_from_name(q.getColumn(0).getString());
}

void for_each_cycle(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                    const std::function<void(const StoredCycle&)>& visit) {
  const int run_cycles = stored_run_cycles(db, run_id);
  auto q = block_query(db, "first_cycle, sensor, cycles, half_cutoff_p, order_p, " + column_list(kCycleColumnNames),
                       "cycle_blocks", run_id, span, true);
  CycleOrder<StoredCycle> order(span, visit);
  while (q.executeStep()) order.add_block(q.getColumn(0).getInt(), decode_cycle_block(q, run_cycles));
  order.finish();
}

void for_each_target_list(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                          const std::function<void(const StoredTargetList&)>& visit) {
  const int run_cycles = stored_run_cycles(db, run_id);
  auto q = block_query(db, "first_cycle, sensor, cycles, " + column_list(kTargetColumnNames), "target_blocks", run_id,
                       span, true);
  // The blocks' cycles in the order of (cycle, sensor), as CycleOrder gives decoded rows: a cycle
  // is visited once no block still to come can hold an earlier one (blocks come by first cycle).
  std::vector<std::unique_ptr<TargetBlockCursor>> open;
  StoredTargetList list;
  const auto release_before = [&](int cycle) {
    for (;;) {
      TargetBlockCursor* next = nullptr;
      for (const auto& c : open) {
        if (!c->done() && c->cycle() <= span.last && c->cycle() < cycle &&
            (next == nullptr || std::make_pair(c->cycle(), c->sensor()) < std::make_pair(next->cycle(), next->sensor()))) {
          next = c.get();
        }
      }
      if (next == nullptr) break;
      next->decode_next(list);
      if (span.contains(list.cycle)) visit(list);
    }
    std::erase_if(open, [&](const auto& c) { return c->done() || c->cycle() > span.last; });
  };
  while (q.executeStep()) {
    release_before(q.getColumn(0).getInt());
    open.push_back(std::make_unique<TargetBlockCursor>(q, run_cycles));
  }
  release_before(std::numeric_limits<int>::max());
}

void for_each_target(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                     const std::function<void(const StoredTarget&)>& visit) {
  for_each_target_list(db, run_id, span, [&](const StoredTargetList& list) {
    for (const StoredTarget& t : list.recorded) visit(t);
    for (const StoredTarget& t : list.simulated) visit(t);
  });
}

void for_each_object_state(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                           const std::function<void(const StoredObjectState&)>& visit) {
  const int run_cycles = stored_run_cycles(db, run_id);
  const int run_objects = stored_run_objects(db, run_id);
  auto q = block_query(db, "first_cycle, cycles, " + column_list(kObjectColumnNames), "object_state_blocks", run_id,
                       span, false);
  while (q.executeStep()) {
    for (const StoredObjectState& s : decode_object_block(q, run_cycles, run_objects)) {
      if (span.contains(s.cycle)) visit(s);
    }
  }
}

// ---- Writing ----

RunRowWriter::RunRowWriter(SQLite::Database& db, std::int64_t run_id, StoreLevel store, double cutoff_m, double order_p)
    : db_(db), run_id_(run_id), store_(store), half_cutoff_p_(0.5 * std::pow(cutoff_m, order_p)), order_p_(order_p) {
  // c^p / 2 as metrics/gospa.cpp computes it, so that the missed and false parts are predicted exactly.
  insert_cycles_ = std::make_unique<SQLite::Statement>(
      db_, fmt::format("INSERT INTO cycle_blocks (run_id, first_cycle, sensor, cycles, half_cutoff_p, order_p, {}) "
                       "VALUES ({})",
                       column_list(kCycleColumnNames), placeholders(6 + kCycleColumns)));
  if (store_ == StoreLevel::full) {
    insert_targets_ = std::make_unique<SQLite::Statement>(
        db_, fmt::format("INSERT INTO target_blocks (run_id, first_cycle, sensor, cycles, {}) VALUES ({})",
                         column_list(kTargetColumnNames), placeholders(4 + kTargetColumns)));
    insert_objects_ = std::make_unique<SQLite::Statement>(
        db_, fmt::format("INSERT INTO object_state_blocks (run_id, first_cycle, cycles, {}) VALUES ({})",
                         column_list(kObjectColumnNames), placeholders(3 + kObjectColumns)));
  }
}

RunRowWriter::~RunRowWriter() = default;

void RunRowWriter::add_cycle(const StoredCycle& cycle, const std::vector<StoredTarget>& recorded,
                             const std::vector<StoredTarget>& simulated) {
  if (store_ == StoreLevel::full && !cycle.X_WS) {
    throw std::invalid_argument(fmt::format("cycle {} of sensor {}: a full run stores the sensor pose", cycle.cycle, cycle.sensor));
  }
  SensorBlock& block = open_[cycle.sensor];
  if (!block.cycles.empty() && (cycle.cycle != block.cycles.back().cycle + 1 ||
                                block.cycles.size() == static_cast<std::size_t>(kBlockCycles) ||
                                cycle.classes.has_value() != block.cycles.back().classes.has_value())) {
    flush(cycle.sensor, block);
  }
  block.cycles.push_back(cycle);
  if (store_ == StoreLevel::full) block.targets.push_back({cycle.cycle, cycle.sensor, recorded, simulated});
}

void RunRowWriter::flush(int sensor, SensorBlock& block) {
  if (block.cycles.empty()) return;
  write_cycle_block(sensor, block.cycles);
  if (store_ == StoreLevel::full) write_target_block(sensor, block.cycles.front().cycle, block.targets);
  block.cycles.clear();
  block.targets.clear();
}

// One cycle_blocks row: each column predicted from what came before (time and pose linearly,
// GOSPA from its parts), so that only the residuals take room.
void RunRowWriter::write_cycle_block(int sensor, const std::vector<StoredCycle>& cycles) {
  const int first_cycle = cycles.front().cycle;
  const int n = static_cast<int>(cycles.size());
  const bool with_pose = store_ == StoreLevel::full;
  const bool with_classes = cycles.front().classes.has_value();
  std::array<ColumnWriter, kCycleColumns> w;
  LinearPrediction t, x, y, yaw;
  for (const StoredCycle& c : cycles) {
    w[kTime].put_exact(c.t_s, t.predict());
    t.push(c.t_s);
    if (with_pose) {
      w[kSensorX].put_exact(c.X_WS->x_m, x.predict());
      w[kSensorY].put_exact(c.X_WS->y_m, y.predict());
      w[kSensorYaw].put_exact(c.X_WS->yaw_rad, yaw.predict());
      x.push(c.X_WS->x_m);
      y.push(c.X_WS->y_m);
      yaw.push(c.X_WS->yaw_rad);
    }
    w[kNRecorded].put_unsigned(static_cast<std::uint64_t>(c.n_recorded));
    w[kNSimulated].put_unsigned(static_cast<std::uint64_t>(c.n_simulated));
    w[kNAssigned].put_unsigned(static_cast<std::uint64_t>(c.n_assigned));
    w[kLocalisation].put_exact(c.gospa_localisation_mp, 0.0);
    w[kMissed].put_exact(c.gospa_missed_mp, part_prediction(half_cutoff_p_, c.n_recorded, c.n_assigned));
    w[kFalse].put_exact(c.gospa_false_mp, part_prediction(half_cutoff_p_, c.n_simulated, c.n_assigned));
    w[kGospa].put_exact(c.gospa_m, gospa_prediction(c.gospa_localisation_mp, c.gospa_missed_mp, c.gospa_false_mp, order_p_));
    w[kOspa].put_exact(c.ospa_m, ospa_prediction(c.gospa_localisation_mp, c.n_recorded, c.n_simulated, c.n_assigned,
                                                 half_cutoff_p_, order_p_));
    w[kMergeRecorded].put_unsigned(static_cast<std::uint64_t>(c.merge_recorded));
    w[kMergeSimulated].put_unsigned(static_cast<std::uint64_t>(c.merge_simulated));
    w[kMergeMatched].put_unsigned(static_cast<std::uint64_t>(c.merge_matched));
    if (with_classes) {
      const StoredCycle::Classes& k = *c.classes;
      w[kNObjectRecorded].put_unsigned(static_cast<std::uint64_t>(k.n_object_recorded));
      w[kNObjectSimulated].put_unsigned(static_cast<std::uint64_t>(k.n_object_simulated));
      w[kNBackgroundRecorded].put_unsigned(static_cast<std::uint64_t>(k.n_background_recorded));
      w[kNBackgroundSimulated].put_unsigned(static_cast<std::uint64_t>(k.n_background_simulated));
      w[kGospaObject].put_exact(k.gospa_object_m, c.gospa_m);
      w[kOspaObject].put_exact(k.ospa_object_m, c.ospa_m);
    }
  }
  SQLite::Statement& s = *insert_cycles_;
  s.bind(1, run_id_);
  s.bind(2, first_cycle);
  s.bind(3, sensor);
  s.bind(4, n);
  s.bind(5, half_cutoff_p_);
  s.bind(6, order_p_);
  for (int c = 0; c < kCycleColumns; ++c) {
    const bool stored = (with_pose || (c != kSensorX && c != kSensorY && c != kSensorYaw)) &&
                        (with_classes || c < kNObjectRecorded);
    if (stored) {
      bind_column(s, 7 + c, w[static_cast<std::size_t>(c)]);
    } else {
      s.bind(7 + c);
    }
  }
  s.exec();
  s.reset();
}

// One target_blocks row; the optional columns (RCS, SNR, elevation) only where a target has them.
void RunRowWriter::write_target_block(int sensor, int first_cycle, const std::vector<StoredTargetList>& targets) {
  std::array<ColumnWriter, kTargetColumns> w;
  bool optional[3] = {false, false, false};
  for (const StoredTargetList& list : targets) {
    for (const auto* side : {&list.recorded, &list.simulated}) {
      for (const StoredTarget& t : *side) {
        optional[0] = optional[0] || !std::isnan(t.rcs_dbsm);
        optional[1] = optional[1] || !std::isnan(t.snr_db);
        optional[2] = optional[2] || !std::isnan(t.elevation_rad);
      }
    }
  }
  for (const StoredTargetList& list : targets) {
    w[kListRecorded].put_unsigned(list.recorded.size());
    w[kListSimulated].put_unsigned(list.simulated.size());
    for (const auto* side : {&list.recorded, &list.simulated}) {
      for (const StoredTarget& t : *side) {
        w[kTrack].put_signed(std::max(-1, t.track_id));
        w[kRange].put_float32(t.range_m);
        w[kAzimuth].put_float32(t.azimuth_rad);
        w[kRangeRate].put_float32(t.range_rate_mps);
        w[kAmplitude].put_float32(t.amplitude_db);
        w[kObject].put_signed(std::max(-1, t.object));
        w[kMatch].put_signed(std::max(-1, t.match_idx));
        w[kFlags].put_unsigned(class_code(t.target_class) + (t.merge_artefact ? kMergeFlag : 0));
        if (has_offset(t)) {
          if (!t.p_OT_O) {
            throw std::invalid_argument(fmt::format("cycle {}: a target of object {} has no offset in its frame",
                                                    list.cycle, t.object));
          }
          w[kXo].put_float32(t.p_OT_O->x());
          w[kYo].put_float32(t.p_OT_O->y());
        }
        if (optional[0]) w[kRcs].put_float32(t.rcs_dbsm);
        if (optional[1]) w[kSnr].put_float32(t.snr_db);
        if (optional[2]) w[kElevation].put_float32(t.elevation_rad);
      }
    }
  }
  SQLite::Statement& s = *insert_targets_;
  s.bind(1, run_id_);
  s.bind(2, first_cycle);
  s.bind(3, sensor);
  s.bind(4, static_cast<int>(targets.size()));
  for (int c = 0; c < kTargetColumns; ++c) {
    if (c >= kRcs && !optional[c - kRcs]) {
      s.bind(5 + c);
    } else {
      bind_column(s, 5 + c, w[static_cast<std::size_t>(c)]);
    }
  }
  s.exec();
  s.reset();
}

void RunRowWriter::add_object_states(int cycle, const std::vector<StoredObjectState>& states) {
  if (store_ != StoreLevel::full) return;
  if (!object_cycles_.empty() && (cycle != object_first_cycle_ + static_cast<int>(object_cycles_.size()) ||
                                  object_cycles_.size() == static_cast<std::size_t>(kBlockCycles))) {
    flush_object_states();
  }
  if (object_cycles_.empty()) object_first_cycle_ = cycle;
  object_cycles_.push_back(states);
}

void RunRowWriter::flush_object_states() {
  if (object_cycles_.empty()) return;
  std::array<ColumnWriter, kObjectColumns> w;
  std::unordered_map<int, std::array<LinearPrediction, 3>> predictions;
  for (const auto& states : object_cycles_) w[kNObjects].put_unsigned(states.size());
  for (const auto& states : object_cycles_) {
    for (const StoredObjectState& s : states) {
      w[kObjectIndex].put_unsigned(static_cast<std::uint64_t>(s.object));
      auto& p = predictions[s.object];
      w[kObjectX].put_exact(s.X_WO.x_m, p[0].predict());
      w[kObjectY].put_exact(s.X_WO.y_m, p[1].predict());
      w[kObjectYaw].put_exact(s.X_WO.yaw_rad, p[2].predict());
      p[0].push(s.X_WO.x_m);
      p[1].push(s.X_WO.y_m);
      p[2].push(s.X_WO.yaw_rad);
    }
  }
  SQLite::Statement& s = *insert_objects_;
  s.bind(1, run_id_);
  s.bind(2, object_first_cycle_);
  s.bind(3, static_cast<int>(object_cycles_.size()));
  for (int c = 0; c < kObjectColumns; ++c) bind_column(s, 4 + c, w[static_cast<std::size_t>(c)]);
  s.exec();
  s.reset();
  object_cycles_.clear();
}

void RunRowWriter::finish() {
  for (auto& [sensor, block] : open_) flush(sensor, block);
  flush_object_states();
}

}  // namespace rcsim::replay
