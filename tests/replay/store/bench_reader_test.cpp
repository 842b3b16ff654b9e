// Reading a bench back (replay/store/bench_reader.hpp): the levels' order with unknown names
// after the known ones, the bench chosen by default or by id (an unknown id refused naming the
// database and the ids held), and the rows as stored (NULLs as nullopt), ordered by recording and
// level, for the hand-made rows of hand_bench_rows.hpp.
#include "replay/store/bench_reader.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "replay/evaluate/hand_bench_rows.hpp"
#include "replay/store/bench_store.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::bench_reader_test {

using namespace replay::report;

TEST(BenchReaderLevels, LevelsInTheirOrderAndUnknownNamesAfterAlphabetically) {
  EXPECT_EQ(bench_level_order(), (std::vector<std::string>{"reference", "noise_floor", "full", "no_monopulse",
                                                           "points_only", "no_tracking"}));
  EXPECT_TRUE(level_before("reference", "noise_floor"));
  EXPECT_TRUE(level_before("full", "no_tracking"));
  EXPECT_FALSE(level_before("no_tracking", "full"));
  EXPECT_FALSE(level_before("full", "full"));
  EXPECT_TRUE(level_before("no_tracking", "aaa")) << "a known level before any unknown one";
  EXPECT_TRUE(level_before("aaa", "zzz"));
  EXPECT_FALSE(level_before("zzz", "aaa"));
  EXPECT_EQ(std::string(kDefaultLevel), "full");
}

class BenchReader : public testing::ScratchDirTest {
 protected:
  BenchReader() : ScratchDirTest("bench_reader") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    path_ = (dir_ / "b.sqlite").string();
    db_ = replay::open_report_database(path_, true);
  }
  // The InputError's message of select_bench (empty if it returns).
  std::string refusal(std::int64_t requested) {
    try {
      select_bench(*db_, path_, requested);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  std::string path_;
  std::unique_ptr<replay::ReportDatabase> db_;
};

TEST_F(BenchReader, TheLatestBenchByDefaultAndAnUnknownIdRefused) {
  EXPECT_TRUE(bench_ids(*db_).empty());
  EXPECT_FALSE(select_bench(*db_, path_, std::nullopt).has_value());
  EXPECT_EQ(refusal(3), path_ + ": no bench with id 3: the database holds no bench");
  replay::BenchOptions options;
  options.seed = 9;
  EXPECT_EQ(replay::store_bench(*db_, options, "m", replay::hand_rows()), 1);
  EXPECT_EQ(replay::store_bench(*db_, options, "m", replay::hand_rows()), 2);
  EXPECT_EQ(bench_ids(*db_), (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(select_bench(*db_, path_, std::nullopt), std::optional<std::int64_t>(2));
  EXPECT_EQ(select_bench(*db_, path_, 1), std::optional<std::int64_t>(1));
  EXPECT_EQ(refusal(9), path_ + ": no bench with id 9 (the database holds benches 1 to 2, 2 in all)");
  EXPECT_EQ(refusal(0), path_ + ": no bench with id 0 (the database holds benches 1 to 2, 2 in all)");
}

TEST_F(BenchReader, RowsAsStoredByRecordingThenLevel) {
  replay::BenchOptions options;
  options.seed = 9;
  const std::int64_t id = replay::store_bench(*db_, options, "cpu <x>", replay::hand_rows());
  // Two levels the order does not know, stored alphabetically between the known ones.
  db_->exec("INSERT INTO bench_rows SELECT bench_id, recording, recording_name, recording_checksum, 'zz_level', "
            "sensor_cycles, cpu_s, sensor_cycles_per_cpu_s, gospa_mean_m, targets_recorded, targets_simulated, "
            "targets_per_cycle_ratio, merge_artefacts_recorded, merge_artefacts_found, merge_artefacts_missed, "
            "merge_artefacts_spurious, latency_difference_s, latency_pairs FROM bench_rows WHERE level = 'full'");
  db_->exec("UPDATE bench_rows SET level = 'aa_level' WHERE level = 'zz_level' AND recording = 1");
  const BenchData bench = load_bench(*db_, id);
  EXPECT_EQ(bench.info.bench_id, id);
  EXPECT_EQ(bench.info.seed, 9);
  EXPECT_EQ(bench.info.machine, "cpu <x>");
  EXPECT_EQ(bench.info.parameters, replay::bench_parameters_json(options).dump());
  EXPECT_EQ(bench.info.created_utc.size(), 20u) << bench.info.created_utc;  // 2025-01-02T03:04:05Z
  EXPECT_EQ(bench.recordings(), (std::vector<int>{0, 1}));
  std::vector<std::string> order;
  for (const BenchRow& r : bench.rows) order.push_back(std::to_string(r.recording) + " " + r.level);
  EXPECT_EQ(order, (std::vector<std::string>{"0 reference", "0 noise_floor", "0 full", "0 points_only", "0 zz_level",
                                             "1 reference", "1 noise_floor", "1 full", "1 points_only", "1 aa_level"}));
  // Recording 0 at level full (hand_rows()[2]): 100 cycles in 1e-4 s, 50 recorded and 60 simulated
  // targets, merge artefacts 5 / 3 / 2 / 1, latency -0.2 s over 2 pairs.
  const BenchRow& full = bench.rows[2];
  EXPECT_EQ(full.recording_name, "rec0");
  EXPECT_EQ(full.recording_checksum, "0000000000000000");
  EXPECT_EQ(full.sensor_cycles, 100);
  EXPECT_DOUBLE_EQ(*full.cpu_s, 1e-4);
  EXPECT_DOUBLE_EQ(*full.sensor_cycles_per_cpu_s, 1e6);
  EXPECT_DOUBLE_EQ(full.gospa_mean_m, 0.5);
  EXPECT_EQ(full.targets_recorded, 50);
  EXPECT_EQ(full.targets_simulated, 60);
  EXPECT_DOUBLE_EQ(*full.targets_per_cycle_ratio, 1.2);
  EXPECT_EQ(full.merge_recorded, 5);
  EXPECT_EQ(full.merge_found, 3);
  EXPECT_EQ(full.merge_missed, 2);
  EXPECT_EQ(full.merge_spurious, 1);
  EXPECT_DOUBLE_EQ(*full.latency_difference_s, -0.2);
  EXPECT_EQ(full.latency_pairs, 2);
  // The noise floor is not timed; nothing recorded gives no ratio; no latency pair, no difference.
  EXPECT_FALSE(bench.rows[1].cpu_s.has_value());
  EXPECT_FALSE(bench.rows[1].sensor_cycles_per_cpu_s.has_value());
  EXPECT_FALSE(bench.rows[1].latency_difference_s.has_value());
  EXPECT_EQ(bench.rows[7].targets_recorded, 0);
  EXPECT_FALSE(bench.rows[7].targets_per_cycle_ratio.has_value());
}

TEST_F(BenchReader, ABenchThatVanishedIsAnError) {
  try {
    load_bench(*db_, 5);
    ADD_FAILURE() << "bench 5 was loaded from an empty database";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "bench 5 vanished from the database");
  }
}

}  // namespace rcsim::bench_reader_test
