#include "replay/store/bench_reader.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "replay/store/sql_column.hpp"
#include "common/input_error.hpp"

namespace rcsim::replay::report {

namespace {

}  // namespace

const std::vector<std::string>& bench_level_order() {
  static const std::vector<std::string> order{"reference",    "noise_floor", "full",
                                              "no_monopulse", "points_only", "no_tracking"};
  return order;
}

static std::size_t level_rank(const std::string& level) {
  const auto& order = bench_level_order();
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), level) - order.begin());
}

bool level_before(const std::string& a, const std::string& b) {
  const std::size_t ra = level_rank(a), rb = level_rank(b);
  return ra != rb ? ra < rb : a < b;
}

std::vector<int> BenchData::recordings() const {
  std::vector<int> out;
  for (const BenchRow& r : rows) {
    if (std::find(out.begin(), out.end(), r.recording) == out.end()) out.push_back(r.recording);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::int64_t> bench_ids(SQLite::Database& db) {
  std::vector<std::int64_t> ids;
  SQLite::Statement q(db, "SELECT bench_id FROM bench_runs ORDER BY bench_id");
  while (q.executeStep()) ids.push_back(q.getColumn(0).getInt64());
  return ids;
}

std::optional<std::int64_t> select_bench(SQLite::Database& db, const std::string& db_path,
                                         const std::optional<std::int64_t>& requested) {
  const std::vector<std::int64_t> all = bench_ids(db);
  if (!requested) {
    if (all.empty()) return std::nullopt;
    return all.back();
  }
  if (std::binary_search(all.begin(), all.end(), *requested)) return requested;
  if (all.empty())
    throw InputError(db_path, "", fmt::format("no bench with id {}: the database holds no bench", *requested));
  throw InputError(db_path, "",
                   fmt::format("no bench with id {} (the database holds benches {} to {}, {} in all)", *requested,
                               all.front(), all.back(), all.size()));
}

BenchData load_bench(SQLite::Database& db, std::int64_t bench_id) {
  BenchData bench;
  {
    SQLite::Statement q(
        db, "SELECT seed, machine, parameters, rcsim_version, created_utc FROM bench_runs WHERE bench_id = ?");
    q.bind(1, bench_id);
    if (!q.executeStep()) throw std::runtime_error(fmt::format("bench {} vanished from the database", bench_id));
    BenchInfo& i = bench.info;
    i.bench_id = bench_id;
    i.seed = q.getColumn(0).getInt64();
    i.machine = q.getColumn(1).getString();
    i.parameters = q.getColumn(2).getString();
    i.rcsim_version = q.getColumn(3).getString();
    i.created_utc = q.getColumn(4).getString();
  }
  SQLite::Statement q(
      db,
      "SELECT recording, recording_name, recording_checksum, level, sensor_cycles, cpu_s, "
      "sensor_cycles_per_cpu_s, gospa_mean_m, targets_recorded, targets_simulated, "
      "targets_per_cycle_ratio, merge_artefacts_recorded, merge_artefacts_found, merge_artefacts_missed, "
      "merge_artefacts_spurious, latency_difference_s, latency_pairs FROM bench_rows WHERE bench_id = ? "
      "ORDER BY recording, level");
  q.bind(1, bench_id);
  while (q.executeStep()) {
    BenchRow r;
    int c = 0;
    r.recording = q.getColumn(c++).getInt();
    r.recording_name = q.getColumn(c++).getString();
    r.recording_checksum = q.getColumn(c++).getString();
    r.level = q.getColumn(c++).getString();
    r.sensor_cycles = q.getColumn(c++).getInt64();
    r.cpu_s = optional_double(q.getColumn(c++));
    r.sensor_cycles_per_cpu_s = optional_double(q.getColumn(c++));
    r.gospa_mean_m = q.getColumn(c++).getDouble();
    r.targets_recorded = q.getColumn(c++).getInt64();
    r.targets_simulated = q.getColumn(c++).getInt64();
    r.targets_per_cycle_ratio = optional_double(q.getColumn(c++));
    r.merge_recorded = q.getColumn(c++).getInt64();
    r.merge_found = q.getColumn(c++).getInt64();
    r.merge_missed = q.getColumn(c++).getInt64();
    r.merge_spurious = q.getColumn(c++).getInt64();
    r.latency_difference_s = optional_double(q.getColumn(c++));
    r.latency_pairs = q.getColumn(c++).getInt64();
    bench.rows.push_back(std::move(r));
  }
  std::stable_sort(bench.rows.begin(), bench.rows.end(), [](const BenchRow& a, const BenchRow& b) {
    return a.recording != b.recording ? a.recording < b.recording : level_before(a.level, b.level);
  });
  return bench;
}

}  // namespace rcsim::replay::report
