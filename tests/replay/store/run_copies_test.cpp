// Copies of a stored run with its figures varied (replay/store/run_copies.hpp): every table that
// refers to a run copied under the new id, the copy renamed, each variation of the figures by
// hand from figures set by hand, nothing left without commit(); and the source figures the
// generated criteria start from.
#include "replay/store/run_copies.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::run_copies_test {

using replay::RunCopier;
using replay::RunVariation;

class RunCopies : public testing::ScratchDirTest {
 protected:
  RunCopies() : ScratchDirTest("run_copies") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = replay::open_report_database((dir_ / "r.sqlite").string(), true);
    replay::ReportWriter writer(*db_, replay::StoreLevel::summary);
    replay::replay_recording_dir(testing::kBundledRecordings / "front_approach", replay::ReplayOptions{}, writer);
  }

  // Every table with a run_id column but runs.
  std::vector<std::string> run_tables() {
    std::vector<std::string> out;
    SQLite::Statement q(*db_, "SELECT m.name FROM sqlite_schema m WHERE m.type = 'table' AND m.name <> 'runs' AND "
                              "EXISTS (SELECT 1 FROM pragma_table_info(m.name) WHERE name = 'run_id') ORDER BY m.name");
    while (q.executeStep()) out.push_back(q.getColumn(0).getString());
    return out;
  }
  long long count(const std::string& sql) { return db_->execAndGet(sql).getInt64(); }
  double real(const std::string& sql) { return db_->execAndGet(sql).getDouble(); }

  // The source run's figures set to round values: 100 recorded targets, 80 simulated, 50 matched;
  // GOSPA 2 m, OSPA 1 m, residuals 0.5 m, 0.01 rad, 0.2 m/s, 1 dB; 3 latency pairs of -0.1 s;
  // 4 s CPU, 10 s wall; one object in view 40 cycles, detected in 30; W1 of the range 0.6 m, KS 0.25.
  void set_round_figures() {
    db_->exec("UPDATE summaries SET targets_recorded = 100, targets_simulated = 80, targets_matched = 50, "
              "gospa_mean = 2, ospa_mean = 1, gospa_object_mean = 2, ospa_object_mean = 1, residual_range_rms_m = 0.5, "
              "residual_azimuth_rms_rad = 0.01, residual_range_rate_rms_mps = 0.2, residual_amplitude_mean_db = 1, "
              "latency_difference_mean_s = -0.1, latency_pairs = 3, simulate_cpu_s = 4, total_wall_s = 10");
    db_->exec("DELETE FROM object_figures WHERE rowid NOT IN (SELECT min(rowid) FROM object_figures)");
    db_->exec("UPDATE object_figures SET cycles_in_view = 40, cycles_detected_recorded = 35, cycles_detected_simulated = 30");
    db_->exec("UPDATE distribution_distances SET wasserstein1 = 0.6, kolmogorov_smirnov = 0.25");
  }

  std::unique_ptr<replay::ReportDatabase> db_;
};

TEST_F(RunCopies, EveryTableOfTheRunIsCopiedUnderTheNewIdAndTheCopyRenamed) {
  {
    RunCopier copier(*db_, 1);
    copier.copy(2);
    copier.copy(5);
    copier.rename(5, "drive 5", "/drives/5", 42, "00000000000000ff");
    copier.commit();
  }
  EXPECT_EQ(count("SELECT count(*) FROM runs"), 3);
  const auto tables = run_tables();
  EXPECT_GE(tables.size(), 10u);
  for (const std::string& table : tables) {
    const long long source = count(fmt::format("SELECT count(*) FROM {} WHERE run_id = 1", table));
    EXPECT_EQ(count(fmt::format("SELECT count(*) FROM {} WHERE run_id = 2", table)), source) << table;
    EXPECT_EQ(count(fmt::format("SELECT count(*) FROM {} WHERE run_id = 5", table)), source) << table;
  }
  EXPECT_GT(count("SELECT count(*) FROM summaries WHERE run_id = 5"), 0);
  // The copy is its source but for the new name, directory, seed and checksum.
  const auto ids = replay::stored_run_identities(*db_);
  EXPECT_EQ(ids.at(2), ids.at(1));
  EXPECT_EQ(ids.at(5).seed, 42);
  EXPECT_EQ(ids.at(5).recording_checksum, "00000000000000ff");
  EXPECT_EQ(ids.at(5).parameters, ids.at(1).parameters);
  EXPECT_EQ(db_->execAndGet("SELECT recording_name || ' ' || recording_dir FROM runs WHERE run_id = 5").getString(),
            "drive 5 /drives/5");
  EXPECT_EQ(db_->execAndGet("SELECT recording_name FROM runs WHERE run_id = 1").getString(), "front_approach");
  EXPECT_EQ(count("SELECT count(*) FROM pragma_foreign_key_check"), 0) << "no row refers to a missing run";
}

TEST_F(RunCopies, EachVariationByHand) {
  set_round_figures();
  {
    RunCopier copier(*db_, 1);
    copier.copy(2);
    RunVariation worse;
    worse.quality = 4.0;                    // GOSPA x4, OSPA x2, residuals x4, matched 50 / 2 = 25
    worse.amplitude_shift_db = 0.5;         // 1 + 0.5 dB
    worse.simulated_targets_factor = 1.5;   // 80 x 1.5 = 120
    worse.latency_difference_s = 0.3;       // 3 pairs kept
    worse.time_factor = 2.0;                // 8 s CPU, 20 s wall
    worse.detection_factor = 2.0;           // 30 x 2 = 60, at most the 40 in view
    worse.distance_factor = 9.0;            // W1 0.6 x 9 = 5.4, KS 0.25 x 3 = 0.75
    copier.vary(2, worse);
    copier.copy(3);
    RunVariation better;
    better.quality = 0.01;                  // matched 50 / 0.1 = 500, at most the 100 recorded
    better.no_latency_pair = true;          // no difference, 0 pairs
    better.detection_factor = 0.5;          // 15
    better.distance_factor = 100.0;         // KS 0.25 x 10, at most 1
    copier.vary(3, better);
    copier.commit();
  }
  const auto summary = [&](const char* column, int run) {
    return real(fmt::format("SELECT {} FROM summaries WHERE run_id = {}", column, run));
  };
  EXPECT_DOUBLE_EQ(summary("gospa_mean", 2), 8.0);
  EXPECT_DOUBLE_EQ(summary("ospa_mean", 2), 2.0);
  EXPECT_DOUBLE_EQ(summary("gospa_object_mean", 2), 8.0);
  EXPECT_DOUBLE_EQ(summary("residual_range_rms_m", 2), 2.0);
  EXPECT_DOUBLE_EQ(summary("residual_azimuth_rms_rad", 2), 0.04);
  EXPECT_DOUBLE_EQ(summary("residual_amplitude_mean_db", 2), 1.5);
  EXPECT_EQ(count("SELECT targets_simulated FROM summaries WHERE run_id = 2"), 120);
  EXPECT_EQ(count("SELECT targets_matched FROM summaries WHERE run_id = 2"), 25);
  EXPECT_DOUBLE_EQ(summary("latency_difference_mean_s", 2), 0.3);
  EXPECT_EQ(count("SELECT latency_pairs FROM summaries WHERE run_id = 2"), 3);
  EXPECT_DOUBLE_EQ(summary("simulate_cpu_s", 2), 8.0);
  EXPECT_DOUBLE_EQ(summary("total_wall_s", 2), 20.0);
  EXPECT_EQ(count("SELECT cycles_detected_simulated FROM object_figures WHERE run_id = 2"), 40);
  EXPECT_DOUBLE_EQ(real("SELECT max(wasserstein1) FROM distribution_distances WHERE run_id = 2"), 5.4);
  EXPECT_DOUBLE_EQ(real("SELECT max(kolmogorov_smirnov) FROM distribution_distances WHERE run_id = 2"), 0.75);

  EXPECT_DOUBLE_EQ(summary("gospa_mean", 3), 0.02);
  EXPECT_EQ(count("SELECT targets_matched FROM summaries WHERE run_id = 3"), 100);
  EXPECT_EQ(count("SELECT latency_difference_mean_s IS NULL AND latency_pairs = 0 FROM summaries WHERE run_id = 3"), 1);
  EXPECT_EQ(count("SELECT cycles_detected_simulated FROM object_figures WHERE run_id = 3"), 15);
  EXPECT_DOUBLE_EQ(real("SELECT max(kolmogorov_smirnov) FROM distribution_distances WHERE run_id = 3"), 1.0);
  // The source is as it was.
  EXPECT_DOUBLE_EQ(summary("gospa_mean", 1), 2.0);
  EXPECT_EQ(count("SELECT cycles_detected_simulated FROM object_figures WHERE run_id = 1"), 30);
}

TEST_F(RunCopies, NothingIsLeftWithoutCommit) {
  {
    RunCopier copier(*db_, 1);
    copier.copy(2);
    copier.vary(2, RunVariation{});
    EXPECT_EQ(count("SELECT count(*) FROM runs"), 2) << "inside the copier's transaction";
  }
  EXPECT_EQ(count("SELECT count(*) FROM runs"), 1);
  EXPECT_EQ(count("SELECT count(*) FROM summaries"), 1);
  // A second copy under an id in use breaks the primary key: refused, nothing kept.
  RunCopier copier(*db_, 1);
  EXPECT_THROW(copier.copy(1), replay::StoreError);
}

TEST_F(RunCopies, TheSourceFiguresOfTheGeneratedCriteria) {
  set_round_figures();
  const replay::SourceRunFigures f = replay::source_run_figures(*db_, 1);
  EXPECT_DOUBLE_EQ(f.gospa_mean_m, 2.0);
  EXPECT_DOUBLE_EQ(f.object_detection_rate_simulated, 30.0 / 40.0);
  EXPECT_DOUBLE_EQ(f.wasserstein1_range_m, 0.6);
  // A W1 that is NULL reads 0; a run of nothing, zeros.
  db_->exec("UPDATE distribution_distances SET wasserstein1 = NULL WHERE quantity = 'range'");
  EXPECT_DOUBLE_EQ(replay::source_run_figures(*db_, 1).wasserstein1_range_m, 0.0);
  const replay::SourceRunFigures none = replay::source_run_figures(*db_, 99);
  EXPECT_DOUBLE_EQ(none.gospa_mean_m, 0.0);
  EXPECT_DOUBLE_EQ(none.object_detection_rate_simulated, 0.0);
  EXPECT_DOUBLE_EQ(none.wasserstein1_range_m, 0.0);
}

}  // namespace rcsim::run_copies_test
