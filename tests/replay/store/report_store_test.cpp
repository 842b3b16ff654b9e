// The report database (replay/store/report_store.hpp): a run is one transaction, so a run that
// fails midway leaves the earlier runs as they were; a database of another program is refused.
#include "replay/store/report_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

class ReportStore : public testing::ScratchDirTest {
 protected:
  ReportStore() : ScratchDirTest("report_store") {}

  Recording write_and_read(const Recording& rec, const std::string& name) { return testing::write_and_read(rec, dir_ / name); }
};

TEST_F(ReportStore, FailedRunLeavesEarlierRunsIntact) {
  const Scene scene = testing::two_cars_scene(1.0);
  const Recording rec = write_and_read(testing::model_recording(scene, 1), "a");
  const auto path = (dir_ / "r.sqlite").string();
  ReplayOptions options;
  options.import.effects = {};
  {
    const auto db = open_report_database(path, true);
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
  }
  // A sink that fails midway, like a replay that meets a full disk.
  struct Failing final : ReplaySink {
    explicit Failing(SQLite::Database& db) : inner(db) {}
    void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions& o) override {
      inner.begin_run(r, i, s, o);
    }
    void add_cycle(const CycleComparison& c) override {
      if (++cycles == 10) throw std::runtime_error("disk full");
      inner.add_cycle(c);
    }
    void end_run(const ReplaySummary& s) override { inner.end_run(s); }
    ReportWriter inner;
    int cycles = 0;
  };
  {
    const auto db = open_report_database(path, true);
    Failing failing(*db);
    EXPECT_THROW(replay_recording(rec, options, failing), std::runtime_error);
  }
  const auto db = open_report_database(path, false);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(DISTINCT run_id) FROM cycles").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM summaries").getInt(), 1);
  EXPECT_EQ(db->execAndGet("PRAGMA integrity_check").getString(), "ok");
}

TEST_F(ReportStore, RefusesAForeignDatabase) {
  const auto path = (dir_ / "other.sqlite").string();
  {
    SQLite::Database other(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    other.exec("CREATE TABLE t (x INTEGER)");
  }
  EXPECT_THROW(open_report_database(path, true), InputError);
  std::ofstream(dir_ / "junk.sqlite") << "this is not a database, just text that is long enough to matter......";
  EXPECT_THROW(open_report_database((dir_ / "junk.sqlite").string(), true), InputError);
}

}  // namespace
}  // namespace rcsim::replay
