#include "replay/store/figure_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

#include "replay/store/run_rows.hpp"

namespace rcsim::replay::report {

namespace {

constexpr double kPi = 3.141592653589793, kTwoPi = 6.283185307179586;

// A value found per cycle: the largest, the earliest cycle of it on ties.
void keep_largest(std::optional<CycleFound>& found, int cycle, double value, int sensor = -1) {
  if (!found || value > found->value) found = CycleFound{cycle, value, sensor};
}

// Residuals of the assigned pairs of one cycle and sensor, simulated - recorded; azimuth wrapped
// to [-pi, pi].
template <class Visit>
void visit_residuals(const StoredTargetList& list, Visit&& visit) {
  for (const StoredTarget& r : list.recorded) {
    if (r.match_idx < 0 || r.match_idx >= static_cast<int>(list.simulated.size())) continue;
    const StoredTarget& s = list.simulated[static_cast<std::size_t>(r.match_idx)];
    double d_azimuth = s.azimuth_rad - r.azimuth_rad;
    if (d_azimuth > kPi) {
      d_azimuth -= kTwoPi;
    } else if (d_azimuth < -kPi) {
      d_azimuth += kTwoPi;
    }
    visit(Residuals{s.range_m - r.range_m, d_azimuth, s.range_rate_mps - r.range_rate_mps, s.amplitude_db - r.amplitude_db});
  }
}

std::string class_name(const std::optional<metrics::TargetClass>& c) {
  return c ? std::string(metrics::target_class_name(*c)) : std::string();
}

}  // namespace

CycleHighlights read_cycle_highlights(SQLite::Database& db, std::int64_t run_id) {
  CycleHighlights h;
  // Per cycle, summed over its sensors; the cycles come in order, each with all its sensors.
  int cycle = -1;
  double merges = 0.0, count_difference = 0.0;
  const auto close_cycle = [&] {
    if (cycle < 0) return;
    if (merges > 0.0) keep_largest(h.most_merge_artefacts, cycle, merges);
    if (count_difference > 0.0) keep_largest(h.largest_count_difference, cycle, count_difference);
  };
  for_each_cycle(db, run_id, {}, [&](const StoredCycle& c) {
    if (c.cycle != cycle) {
      close_cycle();
      cycle = c.cycle;
      merges = count_difference = 0.0;
    }
    keep_largest(h.largest_gospa, c.cycle, c.gospa_m, c.sensor);
    merges += c.merge_recorded + c.merge_simulated;
    count_difference += std::abs(c.n_recorded - c.n_simulated);
    if (c.n_recorded > 0 && !h.first_recorded) h.first_recorded = CycleFound{c.cycle, 0.0, -1};
    if (c.n_simulated > 0 && !h.first_simulated) h.first_simulated = CycleFound{c.cycle, 0.0, -1};
  });
  close_cycle();
  return h;
}

CycleWindow read_cycle_window(SQLite::Database& db, std::int64_t run_id, int first_cycle, int cycle) {
  CycleWindow w;
  w.first_cycle = first_cycle;
  w.cycle = cycle;
  for_each_cycle(db, run_id, {first_cycle, cycle}, [&](const StoredCycle& c) {
    w.cycles.push_back({c.cycle, c.sensor, c.t_s, c.X_WS.value_or(Pose2{}), c.n_recorded, c.n_simulated, c.gospa_m});
  });
  SQLite::Statement pairs(db, "SELECT object_a, object_b FROM merge_pairs WHERE run_id = ? AND cycle = ?");
  pairs.bind(1, run_id);
  pairs.bind(2, cycle);
  while (pairs.executeStep()) w.merge_pairs.emplace_back(pairs.getColumn(0).getInt(), pairs.getColumn(1).getInt());
  for_each_object_state(db, run_id, {cycle, cycle},
                        [&](const StoredObjectState& s) { w.objects.push_back({s.object, s.X_WO}); });
  for_each_target(db, run_id, {first_cycle, cycle}, [&](const StoredTarget& s) {
    TargetRow t;
    t.cycle = s.cycle;
    t.sensor = s.sensor;
    t.simulated = s.simulated;
    t.idx = s.idx;
    t.p_ST_S = s.p_ST_S();
    if (s.match_idx >= 0) t.match_idx = s.match_idx;
    t.merge_artefact = s.merge_artefact;
    t.target_class = class_name(s.target_class);
    w.targets.push_back(t);
  });
  return w;
}

std::vector<NearestTargetRow> read_nearest_targets(SQLite::Database& db, std::int64_t run_id, int stride) {
  stride = std::max(1, stride);
  std::map<std::pair<int, int>, double> t_s;  // (cycle, sensor) of every stride-th cycle
  for_each_cycle(db, run_id, {}, [&](const StoredCycle& c) {
    if (c.cycle % stride == 0) t_s[{c.cycle, c.sensor}] = c.t_s;
  });
  std::vector<NearestTargetRow> rows;
  for_each_target_list(db, run_id, {}, [&](const StoredTargetList& list) {
    if (list.cycle % stride != 0) return;
    const auto time = t_s.find({list.cycle, list.sensor});
    if (time == t_s.end()) return;
    for (const auto* side : {&list.recorded, &list.simulated}) {
      const StoredTarget* nearest = nullptr;
      for (const StoredTarget& t : *side) {
        // A target of an annotated object: the stationary background and other targets nearer
        // would hide the object the series follows (runs stored before classes: every target).
        const bool of_object = !t.target_class || *t.target_class == metrics::TargetClass::object;
        if (of_object && (nearest == nullptr || t.range_m < nearest->range_m)) nearest = &t;
      }
      if (nearest != nullptr) {
        rows.push_back({list.sensor, nearest->simulated, time->second, nearest->range_m, nearest->p_ST_S()});
      }
    }
  });
  return rows;
}

std::vector<CycleBucketRow> read_cycle_buckets(SQLite::Database& db, std::int64_t run_id, int stride) {
  stride = std::max(1, stride);
  struct Bucket {
    double t_s = 0.0, recorded = 0.0, simulated = 0.0, gospa = 0.0, gospa_max = 0.0;
    int cycles = 0;
  };
  std::map<std::pair<int, int>, Bucket> buckets;  // (sensor, bucket)
  for_each_cycle(db, run_id, {}, [&](const StoredCycle& c) {
    Bucket& b = buckets[{c.sensor, c.cycle / stride}];
    if (b.cycles == 0 || c.t_s < b.t_s) b.t_s = c.t_s;
    if (b.cycles == 0 || c.gospa_m > b.gospa_max) b.gospa_max = c.gospa_m;
    ++b.cycles;
    b.recorded += c.n_recorded;
    b.simulated += c.n_simulated;
    b.gospa += c.gospa_m;
  });
  std::vector<CycleBucketRow> rows;
  for (const auto& [key, b] : buckets) {
    const double n = static_cast<double>(b.cycles);
    rows.push_back({key.first, b.t_s, b.recorded / n, b.simulated / n, b.gospa / n, b.gospa_max});
  }
  return rows;
}

ResidualSampleStats read_residual_sample_stats(SQLite::Database& db, std::int64_t run_id, int stride) {
  stride = std::max(1, stride);
  ResidualSampleStats stats;
  Residuals sum{}, sum_square{};
  std::array<std::vector<double>, 4> values;  // for the percentiles: the sample is bounded by the stride
  for_each_target_list(db, run_id, {}, [&](const StoredTargetList& list) {
    if (list.cycle % stride != 0) return;
    visit_residuals(list, [&](const Residuals& r) {
      for (std::size_t k = 0; k < 4; ++k) {
        values[k].push_back(r[k]);
        if (stats.count == 0 || r[k] < stats.min[k]) stats.min[k] = r[k];
        if (stats.count == 0 || r[k] > stats.max[k]) stats.max[k] = r[k];
        sum[k] += r[k];
        sum_square[k] += r[k] * r[k];
      }
      ++stats.count;
    });
  });
  const auto percentile = [](std::vector<double>& v, double q) {
    const auto rank = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rank), v.end());
    return v[rank];
  };
  for (std::size_t k = 0; k < 4 && stats.count > 0; ++k) {
    stats.mean[k] = sum[k] / static_cast<double>(stats.count);
    stats.mean_square[k] = sum_square[k] / static_cast<double>(stats.count);
    stats.q1[k] = percentile(values[k], 0.25);
    stats.q3[k] = percentile(values[k], 0.75);
  }
  return stats;
}

std::int64_t for_each_residual(SQLite::Database& db, std::int64_t run_id, const std::function<void(const Residuals&)>& visit) {
  std::int64_t n = 0;
  for_each_target_list(db, run_id, {}, [&](const StoredTargetList& list) {
    visit_residuals(list, [&](const Residuals& r) {
      ++n;
      visit(r);
    });
  });
  return n;
}

std::map<int, std::vector<ObjectFrameTarget>> read_objects_frame_targets(SQLite::Database& db, std::int64_t run_id,
                                                                         const std::vector<int>& objects, int max_per_origin) {
  // Each object's targets of class object, by cycle, sensor and idx, per origin; then evenly
  // thinned by a stride.
  std::map<int, std::array<std::vector<ObjectFrameTarget>, 2>> all;
  for (const int object : objects) all[object];
  for_each_target(db, run_id, {}, [&](const StoredTarget& t) {
    if (t.target_class != metrics::TargetClass::object || !t.p_OT_O) return;
    const auto it = all.find(t.object);
    if (it == all.end()) return;
    it->second[t.simulated ? 1 : 0].push_back({t.sensor, t.simulated, *t.p_OT_O});
  });
  std::map<int, std::vector<ObjectFrameTarget>> rows;
  for (const auto& [object, sides] : all) {
    std::vector<ObjectFrameTarget>& out = rows[object];
    for (const auto& side : sides) {
      const auto count = static_cast<std::int64_t>(side.size());
      const std::int64_t stride = std::max<std::int64_t>(1, (count + max_per_origin - 1) / std::max(1, max_per_origin));
      for (std::int64_t k = 0; k < count; k += stride) out.push_back(side[static_cast<std::size_t>(k)]);
    }
  }
  return rows;
}

std::vector<ObjectFrameTarget> read_object_frame_targets(SQLite::Database& db, std::int64_t run_id, int object,
                                                         int max_per_origin) {
  return read_objects_frame_targets(db, run_id, {object}, max_per_origin)[object];
}

namespace {

BackgroundHistogram empty_histogram(const BackgroundBins& b) {
  BackgroundHistogram h;
  h.lo = b.lo;
  h.bin_width = b.bin_width;
  for (auto& counts : h.counts) counts.assign(static_cast<std::size_t>(std::max(0, b.bins)), 0);
  return h;
}

void count_in(BackgroundHistogram& h, int bins, double value, bool simulated) {
  if (bins <= 0) return;
  const auto b = std::clamp<std::int64_t>(static_cast<std::int64_t>((value - h.lo) / h.bin_width), 0, bins - 1);
  ++h.counts[simulated ? 1 : 0][static_cast<std::size_t>(b)];
}

}  // namespace

std::pair<BackgroundHistogram, BackgroundHistogram> read_background_histograms(SQLite::Database& db, std::int64_t run_id,
                                                                               const BackgroundBins& range_bins,
                                                                               const BackgroundBins& azimuth_bins) {
  std::pair<BackgroundHistogram, BackgroundHistogram> h{empty_histogram(range_bins), empty_histogram(azimuth_bins)};
  if (range_bins.bins <= 0 && azimuth_bins.bins <= 0) return h;
  for_each_target(db, run_id, {}, [&](const StoredTarget& t) {
    if (t.target_class != metrics::TargetClass::stationary_background) return;
    count_in(h.first, range_bins.bins, t.range_m, t.simulated);
    count_in(h.second, azimuth_bins.bins, t.azimuth_rad, t.simulated);
  });
  return h;
}

BackgroundHistogram read_background_histogram(SQLite::Database& db, std::int64_t run_id, BackgroundQuantity quantity,
                                              double lo, double bin_width, int bins) {
  const BackgroundBins some{lo, bin_width, bins}, none{lo, bin_width, 0};
  auto [range, azimuth] = read_background_histograms(db, run_id, quantity == BackgroundQuantity::range ? some : none,
                                                     quantity == BackgroundQuantity::azimuth ? some : none);
  return quantity == BackgroundQuantity::range ? range : azimuth;
}

}  // namespace rcsim::replay::report
