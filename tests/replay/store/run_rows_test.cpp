// The per-cycle rows of a run in their blocks (replay/store/run_rows.hpp): what is written comes
// back in cycle order, the cycles and boxes bit for bit and the targets' reals at float32, across
// block boundaries, gaps and interleaved sensors; a summary run keeps its cycles without poses and
// nothing else; and the stored bytes per target of a bundled recording stay within a stated bound.
#include "replay/store/run_rows.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>
#include <tuple>

#include "io/recording.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

void insert_run(SQLite::Database& db, int run_id, const char* store) {
  SQLite::Statement q(db, "INSERT INTO runs VALUES (?, 'r', '/r', '0', '{}', 0.04, 600, 0, 'tracks', '{}', 'v', 't', ?)");
  q.bind(1, run_id);
  q.bind(2, store);
  q.exec();
  // Its five objects (RandomRun's): a cycle's object states are checked against them.
  for (int object = 0; object < 5; ++object) {
    SQLite::Statement o(db, "INSERT INTO run_objects VALUES (?, ?, ?, 'passenger_car', 4.5, 1.8, 7)");
    o.bind(1, run_id);
    o.bind(2, object);
    o.bind(3, "car_" + std::to_string(object));
    o.exec();
  }
}

double float32(double value) { return static_cast<double>(static_cast<float>(value)); }

// Random rows of two sensors over 600 cycles (three blocks), sensor 1 missing cycles 300 to 309.
struct RandomRun {
  std::vector<StoredCycle> cycles;  // in the order written: per cycle sensor 1, then 0
  std::vector<std::vector<StoredTarget>> recorded, simulated;
  std::vector<std::vector<StoredObjectState>> boxes;  // per cycle

  explicit RandomRun(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> small(0, 4);
    for (int k = 0; k < 600; ++k) {
      for (const int sensor : {1, 0}) {
        if (sensor == 1 && k >= 300 && k < 310) continue;
        StoredCycle c;
        c.cycle = k;
        c.sensor = sensor;
        c.t_s = 0.04 * k + 1e-9 * u(rng);
        c.X_WS = Pose2{300.0 + 10.0 * k * 0.04 + u(rng), -20.0 + u(rng), 3.0 * u(rng)};
        c.n_recorded = small(rng);
        c.n_simulated = small(rng);
        c.n_assigned = std::min(c.n_recorded, c.n_simulated);
        // Figures by the metric's formulas half the time, arbitrary otherwise: exact either way.
        c.gospa_localisation_mp = std::abs(u(rng)) * c.n_assigned;
        c.gospa_missed_mp = 2.0 * (c.n_recorded - c.n_assigned);
        c.gospa_false_mp = k % 2 ? 2.0 * (c.n_simulated - c.n_assigned) : u(rng);
        c.gospa_m = k % 2 ? std::pow(c.gospa_localisation_mp + c.gospa_missed_mp + c.gospa_false_mp, 0.5) : u(rng);
        c.ospa_m = std::abs(u(rng));
        c.merge_recorded = small(rng);
        c.merge_simulated = small(rng);
        c.merge_matched = std::min(c.merge_recorded, c.merge_simulated);
        c.classes = StoredCycle::Classes{small(rng), small(rng), small(rng), small(rng), k % 3 ? c.gospa_m : u(rng),
                                         std::abs(u(rng))};
        cycles.push_back(c);
        std::vector<StoredTarget> lists[2];
        for (int origin = 0; origin < 2; ++origin) {
          for (int i = 0; i < (origin ? c.n_simulated : c.n_recorded); ++i) {
            StoredTarget t;
            t.cycle = k;
            t.sensor = sensor;
            t.simulated = origin == 1;
            t.idx = i;
            t.track_id = small(rng) == 0 ? -1 : static_cast<int>(rng() % 1'000'000);
            t.range_m = 100.0 * std::abs(u(rng));
            t.azimuth_rad = u(rng);
            t.range_rate_mps = 30.0 * u(rng);
            t.amplitude_db = 40.0 * u(rng);
            t.object = small(rng) - 1;
            t.match_idx = small(rng) - 1;
            t.merge_artefact = small(rng) == 0;
            t.target_class = small(rng) == 0 ? metrics::TargetClass::stationary_background
                                             : (t.object >= 0 ? metrics::TargetClass::object : metrics::TargetClass::other);
            if (t.object >= 0) t.p_OT_O = Vec2{2.0 * u(rng), u(rng)};
            if (origin == 0 && k < 200) t.rcs_dbsm = 10.0 * u(rng);  // only in the first block
            lists[origin].push_back(t);
          }
        }
        recorded.push_back(lists[0]);
        simulated.push_back(lists[1]);
      }
      std::vector<StoredObjectState> states;
      for (int object = 0; object < 5; ++object) {
        if (small(rng) == 0) continue;
        states.push_back({k, object, Pose2{100.0 * object + 0.4 * k + 1e-3 * u(rng), 5.0 * u(rng), u(rng)}});
      }
      boxes.push_back(states);
    }
  }

  void write(SQLite::Database& db, int run_id, StoreLevel store) const {
    RunRowWriter rows(db, run_id, store, 2.0, 2.0);
    std::size_t written = 0;
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      while (written < cycles.size() && cycles[written].cycle == static_cast<int>(k)) {
        rows.add_cycle(cycles[written], recorded[written], simulated[written]);
        ++written;
      }
      rows.add_object_states(static_cast<int>(k), boxes[k]);
    }
    rows.finish();
  }
};

void expect_same(const StoredCycle& a, const StoredCycle& b, bool with_pose) {
  EXPECT_EQ(std::tuple(a.cycle, a.sensor, a.n_recorded, a.n_simulated, a.n_assigned, a.merge_recorded, a.merge_simulated,
                       a.merge_matched),
            std::tuple(b.cycle, b.sensor, b.n_recorded, b.n_simulated, b.n_assigned, b.merge_recorded, b.merge_simulated,
                       b.merge_matched));
  // EXPECT_EQ on doubles: bit for bit (none is NaN here).
  EXPECT_EQ(std::tuple(a.t_s, a.gospa_m, a.gospa_localisation_mp, a.gospa_missed_mp, a.gospa_false_mp, a.ospa_m),
            std::tuple(b.t_s, b.gospa_m, b.gospa_localisation_mp, b.gospa_missed_mp, b.gospa_false_mp, b.ospa_m))
      << "cycle " << a.cycle << " sensor " << a.sensor;
  ASSERT_EQ(b.X_WS.has_value(), with_pose);
  if (with_pose) {
    EXPECT_EQ(std::tuple(a.X_WS->x_m, a.X_WS->y_m, a.X_WS->yaw_rad), std::tuple(b.X_WS->x_m, b.X_WS->y_m, b.X_WS->yaw_rad));
  }
  ASSERT_TRUE(b.classes.has_value());
  EXPECT_EQ(std::tuple(a.classes->n_object_recorded, a.classes->n_object_simulated, a.classes->n_background_recorded,
                       a.classes->n_background_simulated, a.classes->gospa_object_m, a.classes->ospa_object_m),
            std::tuple(b.classes->n_object_recorded, b.classes->n_object_simulated, b.classes->n_background_recorded,
                       b.classes->n_background_simulated, b.classes->gospa_object_m, b.classes->ospa_object_m));
}

void expect_same(const StoredTarget& a, const StoredTarget& b) {
  EXPECT_EQ(std::tuple(a.cycle, a.sensor, a.simulated, a.idx, a.track_id, a.object, a.match_idx, a.merge_artefact),
            std::tuple(b.cycle, b.sensor, b.simulated, b.idx, b.track_id, b.object, b.match_idx, b.merge_artefact));
  EXPECT_EQ(a.target_class, b.target_class);
  // The reals at float32, exactly.
  EXPECT_EQ(std::tuple(float32(a.range_m), float32(a.azimuth_rad), float32(a.range_rate_mps), float32(a.amplitude_db)),
            std::tuple(b.range_m, b.azimuth_rad, b.range_rate_mps, b.amplitude_db));
  ASSERT_EQ(a.p_OT_O.has_value(), b.p_OT_O.has_value());
  if (a.p_OT_O) {
    EXPECT_EQ(float32(a.p_OT_O->x()), b.p_OT_O->x());
    EXPECT_EQ(float32(a.p_OT_O->y()), b.p_OT_O->y());
  }
  EXPECT_EQ(std::isnan(a.rcs_dbsm), std::isnan(b.rcs_dbsm));
  if (!std::isnan(a.rcs_dbsm)) {
    EXPECT_EQ(float32(a.rcs_dbsm), b.rcs_dbsm);
  }
  EXPECT_TRUE(std::isnan(b.snr_db) && std::isnan(b.elevation_rad));
}

class RunRows : public testing::ScratchDirTest {
 protected:
  RunRows() : ScratchDirTest("run_rows") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = open_report_database((dir_ / "r.sqlite").string(), true);
  }
  std::unique_ptr<replay::ReportDatabase> db_;
};

// Cycles, targets and boxes come back in (cycle, sensor) order, whatever the writing order, over
// three blocks and a gap.
TEST_F(RunRows, RoundTripIsExactAtTheStoredPrecision) {
  const RandomRun run(7);
  insert_run(*db_, 1, "full");
  run.write(*db_, 1, StoreLevel::full);
  EXPECT_GT(db_->execAndGet("SELECT count(*) FROM cycle_blocks WHERE run_id = 1").getInt(), 6);

  std::vector<std::size_t> order(run.cycles.size());  // the written rows by cycle, sensor
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::pair(run.cycles[a].cycle, run.cycles[a].sensor) < std::pair(run.cycles[b].cycle, run.cycles[b].sensor);
  });
  std::size_t n = 0;
  for_each_cycle(*db_, 1, {}, [&](const StoredCycle& c) {
    ASSERT_LT(n, order.size());
    expect_same(run.cycles[order[n++]], c, true);
  });
  EXPECT_EQ(n, run.cycles.size());

  std::vector<StoredTarget> expected;
  for (const std::size_t i : order) {
    expected.insert(expected.end(), run.recorded[i].begin(), run.recorded[i].end());
    expected.insert(expected.end(), run.simulated[i].begin(), run.simulated[i].end());
  }
  ASSERT_GT(expected.size(), 2000u);
  n = 0;
  for_each_target(*db_, 1, {}, [&](const StoredTarget& t) {
    ASSERT_LT(n, expected.size());
    expect_same(expected[n++], t);
  });
  EXPECT_EQ(n, expected.size());

  n = 0;
  std::size_t k = 0, i = 0;
  for_each_object_state(*db_, 1, {}, [&](const StoredObjectState& s) {
    while (i == run.boxes[k].size()) ++k, i = 0;
    const StoredObjectState& e = run.boxes[k][i++];
    EXPECT_EQ(std::tuple(e.cycle, e.object, e.X_WO.x_m, e.X_WO.y_m, e.X_WO.yaw_rad),
              std::tuple(s.cycle, s.object, s.X_WO.x_m, s.X_WO.y_m, s.X_WO.yaw_rad));
    ++n;
  });
  std::size_t boxes = 0;
  for (const auto& b : run.boxes) boxes += b.size();
  EXPECT_EQ(n, boxes);
}

TEST_F(RunRows, ASpanReadsItsCyclesAcrossABlockBoundary) {
  const RandomRun run(8);
  insert_run(*db_, 1, "full");
  run.write(*db_, 1, StoreLevel::full);
  std::vector<std::pair<int, int>> seen;
  for_each_cycle(*db_, 1, {250, 260}, [&](const StoredCycle& c) { seen.emplace_back(c.cycle, c.sensor); });
  ASSERT_EQ(seen.size(), 22u);
  EXPECT_EQ(seen.front(), std::pair(250, 0));
  EXPECT_EQ(seen[7], std::pair(253, 1));
  EXPECT_EQ(seen.back(), std::pair(260, 1));
  int targets = 0, outside = 0;
  for_each_target_list(*db_, 1, {255, 256}, [&](const StoredTargetList& l) {
    ++targets;
    outside += l.cycle < 255 || l.cycle > 256;
  });
  EXPECT_EQ(targets, 4);
  EXPECT_EQ(outside, 0);
  int boxes = 0;
  for_each_object_state(*db_, 1, {256, 256}, [&](const StoredObjectState& s) { boxes += s.cycle == 256; });
  EXPECT_EQ(static_cast<std::size_t>(boxes), run.boxes[256].size());
}

// A summary run: the same cycles, bit for bit, without their poses; no targets, no boxes.
TEST_F(RunRows, SummaryKeepsTheCyclesWithoutPosesAndNothingElse) {
  const RandomRun run(9);
  insert_run(*db_, 1, "summary");
  run.write(*db_, 1, StoreLevel::summary);
  EXPECT_EQ(run_store_level(*db_, 1), StoreLevel::summary);
  EXPECT_EQ(db_->execAndGet("SELECT count(*) FROM target_blocks").getInt(), 0);
  EXPECT_EQ(db_->execAndGet("SELECT count(*) FROM object_state_blocks").getInt(), 0);
  EXPECT_EQ(db_->execAndGet("SELECT count(*) FROM cycle_blocks WHERE sensor_x_m IS NOT NULL").getInt(), 0);
  std::map<std::pair<int, int>, const StoredCycle*> written;
  for (const auto& c : run.cycles) written[{c.cycle, c.sensor}] = &c;
  std::size_t n = 0;
  for_each_cycle(*db_, 1, {}, [&](const StoredCycle& c) {
    ++n;
    expect_same(*written.at({c.cycle, c.sensor}), c, false);
  });
  EXPECT_EQ(n, run.cycles.size());
  int targets = 0;
  for_each_target(*db_, 1, {}, [&](const StoredTarget&) { ++targets; });
  EXPECT_EQ(targets, 0);
}

// A sink that stores the run and keeps every cycle it was handed.
struct KeepingSink final : ReplaySink {
  explicit KeepingSink(SQLite::Database& db) : writer(db) {}
  void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions& o) override {
    writer.begin_run(r, i, s, o);
  }
  void add_cycle(const CycleComparison& c) override {
    writer.add_cycle(c);
    cycles.push_back(c);
  }
  void end_run(const ReplaySummary& s) override { writer.end_run(s); }
  ReportWriter writer;
  std::vector<CycleComparison> cycles;
};

// A full run of a bundled recording reads back as the replay handed it to the store: the cycles'
// figures and poses and the boxes bit for bit, the targets at float32; and the target blocks hold
// at most kMaxBytesPerTarget bytes of BLOB per target (measured 26.3 on city_drive_60s; the row
// table of schema v3 took about 124 bytes per target in its pages, schemas/report-database.md).
TEST_F(RunRows, ABundledRecordingReadsBackAsReplayedInFewBytesPerTarget) {
  constexpr double kMaxBytesPerTarget = 30.0;
  const Recording rec = read_recording(std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic/city_drive_60s");
  ReplayOptions options;
  options.seed = 7;
  KeepingSink sink(*db_);
  const ReplaySummary s = replay_recording(rec, options, sink);
  const std::int64_t run_id = sink.writer.run_id();
  std::map<std::pair<int, int>, const CycleComparison*> handed;
  for (const auto& c : sink.cycles) handed[{c.cycle, c.sensor}] = &c;

  std::size_t cycles = 0;
  for_each_cycle(*db_, run_id, {}, [&](const StoredCycle& c) {
    const CycleComparison& h = *handed.at({c.cycle, c.sensor});
    ++cycles;
    EXPECT_EQ(std::tuple(c.t_s, c.X_WS->x_m, c.X_WS->y_m, c.X_WS->yaw_rad), std::tuple(h.t_s, h.X_WS.x_m, h.X_WS.y_m, h.X_WS.yaw_rad));
    EXPECT_EQ(std::tuple(c.n_recorded, c.n_simulated, c.n_assigned, c.merge_matched),
              std::tuple(static_cast<int>(h.recorded.size()), static_cast<int>(h.simulated.size()), h.gospa.assigned,
                         h.merge_matched));
    EXPECT_EQ(std::tuple(c.gospa_m, c.gospa_localisation_mp, c.gospa_missed_mp, c.gospa_false_mp, c.ospa_m,
                         c.classes->gospa_object_m, c.classes->ospa_object_m),
              std::tuple(h.gospa.gospa_m, h.gospa.localisation_mp, h.gospa.missed_mp, h.gospa.false_mp, h.gospa.ospa_m,
                         h.gospa_object.gospa_m, h.gospa_object.ospa_m));
  });
  EXPECT_EQ(cycles, sink.cycles.size());
  long long recorded = 0, simulated = 0;
  for_each_target(*db_, run_id, {}, [&](const StoredTarget& t) {
    (t.simulated ? simulated : recorded) += 1;
    const CycleComparison& h = *handed.at({t.cycle, t.sensor});
    const ComparedTarget& e = (t.simulated ? h.simulated : h.recorded).at(static_cast<std::size_t>(t.idx));
    EXPECT_EQ(std::tuple(float32(e.range_m), float32(e.azimuth_rad), float32(e.range_rate_mps), float32(e.amplitude_db)),
              std::tuple(t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db));
    EXPECT_EQ(std::tuple(std::max(-1, e.track_id), std::max(-1, e.object), std::max(-1, e.match), e.merge_pair >= 0),
              std::tuple(t.track_id, t.object, t.match_idx, t.merge_artefact));
    EXPECT_EQ(t.target_class, e.target_class);
    if (e.object >= 0) {
      ASSERT_TRUE(t.p_OT_O.has_value());
      EXPECT_EQ(std::pair(float32(e.p_OT_O.x()), float32(e.p_OT_O.y())), std::pair(t.p_OT_O->x(), t.p_OT_O->y()));
    }
  });
  EXPECT_EQ(recorded, static_cast<long long>(rec.targets.size()));
  EXPECT_EQ(simulated, s.targets_simulated);
  std::size_t boxes = 0, handed_boxes = 0;
  for (const auto& c : sink.cycles) handed_boxes += c.sensor == 0 ? c.objects.size() : 0;
  for_each_object_state(*db_, run_id, {}, [&](const StoredObjectState& o) {
    const CycleComparison& h = *handed.at({o.cycle, 0});
    const auto it = std::find_if(h.objects.begin(), h.objects.end(), [&](const auto& b) { return b.object == o.object; });
    ASSERT_NE(it, h.objects.end());
    EXPECT_EQ(std::tuple(o.X_WO.x_m, o.X_WO.y_m, o.X_WO.yaw_rad), std::tuple(it->x_m, it->y_m, it->yaw_rad));
    ++boxes;
  });
  EXPECT_EQ(boxes, handed_boxes);

  std::string sum = "SELECT sum(0";
  for (const char* column : {"n_recorded", "n_simulated", "track_id", "range_m", "azimuth_rad", "range_rate_mps",
                             "amplitude_db", "object", "match_idx", "flags", "x_o_m", "y_o_m", "rcs_dbsm", "snr_db",
                             "elevation_rad"}) {
    sum += std::string(" + coalesce(length(") + column + "), 0)";
  }
  const double bytes = db_->execAndGet(sum + ") FROM target_blocks").getDouble();
  const double per_target = bytes / static_cast<double>(recorded + simulated);
  RecordProperty("target_blob_bytes_per_target", std::to_string(per_target));
  std::cout << "target blocks: " << per_target << " bytes per target\n";
  EXPECT_LE(per_target, kMaxBytesPerTarget) << bytes << " bytes for " << recorded + simulated << " targets";
  EXPECT_GE(per_target, 16.0);  // four float32 reals at least
}

}  // namespace
}  // namespace rcsim::replay
