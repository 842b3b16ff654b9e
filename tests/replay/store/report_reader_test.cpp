// Reading a run back (replay/store/report_reader.hpp): every table of one stored run returns
// what the replay handed to the store, and the run selection refuses unknown ids naming them.
#include "replay/store/report_reader.hpp"

#include <gtest/gtest.h>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::report {
namespace {

// A sink that stores the run and keeps the cycles it saw.
struct StoringSink final : ReplaySink {
  explicit StoringSink(SQLite::Database& db) : writer(db) {}
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

class ReportReader : public rcsim::testing::ScratchDirTest {
 protected:
  ReportReader() : ScratchDirTest("report_reader") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    write_recording(dir_ / "rec", rcsim::testing::model_recording(rcsim::testing::two_cars_scene(2.0), 3, 0.02, 0.01));
    recording_ = read_recording(dir_ / "rec");
    db_ = open_report_database((dir_ / "r.sqlite").string(), true);
    StoringSink sink(*db_);
    ReplayOptions options;
    options.seed = 4;
    summary_ = replay_recording(recording_, options, sink);
    run_id_ = sink.writer.run_id();
    cycles_ = std::move(sink.cycles);
  }
  Recording recording_;
  std::unique_ptr<replay::ReportDatabase> db_;
  ReplaySummary summary_;
  std::int64_t run_id_ = 0;
  std::vector<CycleComparison> cycles_;
};

TEST_F(ReportReader, RunTablesReadBackAsStored) {
  const RunData run = load_run(*db_, run_id_);
  EXPECT_EQ(run.info.run_id, run_id_);
  EXPECT_EQ(run.info.recording_name, recording_.name);
  EXPECT_EQ(run.info.cycles, recording_.cycle_count());
  EXPECT_EQ(run.info.seed, 4);
  ASSERT_TRUE(run.summary.has_value());
  EXPECT_EQ(run.summary->targets_recorded, summary_.targets_recorded);
  EXPECT_EQ(run.summary->targets_simulated, summary_.targets_simulated);
  EXPECT_DOUBLE_EQ(run.summary->gospa_mean_m, summary_.gospa_mean_m);
  EXPECT_EQ(run.summary->merge_recorded, summary_.merge_artefacts_recorded);
  ASSERT_EQ(run.sensors.size(), 2u);
  EXPECT_EQ(run.sensors[1].id, "front_right");
  EXPECT_DOUBLE_EQ(run.sensors[1].X_VS.y_m, -0.7);
  ASSERT_EQ(run.objects.size(), 2u);
  EXPECT_EQ(run.object_label(0).find("left"), 0u);
  EXPECT_EQ(run.distances.size(), summary_.distances.size());
  EXPECT_EQ(run.latencies.size(), summary_.latencies.size());
  // Per-sensor totals: the sums of what the sink saw.
  ASSERT_EQ(run.sensor_totals.size(), 2u);
  std::int64_t recorded_0 = 0, cycles_0 = 0;
  for (const auto& c : cycles_) {
    if (c.sensor == 0) recorded_0 += static_cast<std::int64_t>(c.recorded.size()), ++cycles_0;
  }
  EXPECT_EQ(run.sensor_totals[0].recorded, recorded_0);
  EXPECT_EQ(run.sensor_totals[0].cycles, cycles_0);
}

TEST_F(ReportReader, SelectsTheLastRunsByDefaultAndRefusesUnknownIds) {
  EXPECT_EQ(run_ids(*db_), std::vector<std::int64_t>{run_id_});
  EXPECT_EQ(select_runs(*db_, "r.sqlite", {}, 3), std::vector<std::int64_t>{run_id_});
  try {
    select_runs(*db_, "r.sqlite", {run_id_ + 7}, 3);
    FAIL() << "an unknown run id was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("r.sqlite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(std::to_string(run_id_ + 7)), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsim::replay::report
