// The real-drive figures on the aiMotive sample in ../shared/realdata (never part of the
// project; skipped, saying so, where it is absent): imported with `rcsim import --from aimotive`
// and replayed at detection level. The classes split the recording as its README describes
// (most targets on no box), the object figures are consistent, the optional columns reach the
// report, and the object targets lie on their boxes.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "replay/import/aimotive_importer.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

using rcsim::testing::kAimotiveRaw;

class RealDriveReplay : public testing::ScratchDirTest {
 protected:
  RealDriveReplay() : ScratchDirTest("real_drive") {}
  void SetUp() override {
    if (!fs::is_directory(kAimotiveRaw)) GTEST_SKIP() << "real data absent (" << kAimotiveRaw.string() << "): real-drive replay tests skipped";
    ScratchDirTest::SetUp();
  }
};

TEST_F(RealDriveReplay, ClassesObjectFiguresAndOptionalColumnsOfTheSample) {
  const DatasetRecording imported = import_aimotive(kAimotiveRaw);
  write_recording(dir_ / "rec", imported.recording, imported.extra_files);
  const Recording rec = read_recording(dir_ / "rec");
  ReplayOptions options;
  options.fidelity = Fidelity::no_tracking;
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReportWriter writer(*db);
  const ReplaySummary s = replay_recording(rec, options, writer);

  ASSERT_EQ(s.targets_recorded, 3909);
  const ClassCounts& k = s.classes;
  EXPECT_EQ(k.object[0] + k.background[0] + k.other[0], s.targets_recorded);
  EXPECT_EQ(k.object[1] + k.background[1] + k.other[1], s.targets_simulated);
  // Most of the drive is the unannotated stationary world (the README: 88 % on no box).
  EXPECT_GT(k.background[0], 0.75 * static_cast<double>(s.targets_recorded));
  EXPECT_GT(k.object[0], 400);
  EXPECT_LT(k.object[0], 500);
  // The object subset is much closer than the whole list: the background no longer counts.
  EXPECT_LT(s.gospa_object_mean_m, 0.5 * s.gospa_mean_m);

  // Every annotated vehicle is in view of one radar or the other; the recorded detection rate
  // over all of them is high, and the aimotive_lrr profile's within 0.15 of it (issue 18's goal;
  // the placeholder with srr24's law had 20 %).
  long long in_view = 0, detected_recorded = 0, detected_simulated = 0, object_targets = 0;
  for (const ObjectFigureRow& o : s.objects) {
    in_view += o.cycles_in_view;
    detected_recorded += o.cycles_detected_recorded;
    detected_simulated += o.cycles_detected_simulated;
    object_targets += o.targets_recorded;
  }
  EXPECT_EQ(static_cast<int>(s.objects.size()), 8);
  EXPECT_GT(detected_recorded, 0.7 * static_cast<double>(in_view));
  EXPECT_NEAR(static_cast<double>(detected_simulated) / static_cast<double>(in_view),
              static_cast<double>(detected_recorded) / static_cast<double>(in_view), 0.15);
  EXPECT_LE(object_targets, k.object[0]);  // object targets of boxes out of view are not counted

  // The optional columns reach the report for the recorded targets only.
  std::map<int, std::pair<double, double>> size_m;  // object -> (length, width)
  SQLite::Statement objects(*db, "SELECT object, length_m, width_m FROM run_objects WHERE run_id = ?");
  objects.bind(1, writer.run_id());
  while (objects.executeStep()) {
    size_m[objects.getColumn(0).getInt()] = {objects.getColumn(1).getDouble(), objects.getColumn(2).getDouble()};
  }
  int recorded_with_all = 0, simulated_with_rcs = 0, n = 0;
  for_each_target(*db, writer.run_id(), {}, [&](const StoredTarget& t) {
    recorded_with_all += !t.simulated && !std::isnan(t.rcs_dbsm) && !std::isnan(t.snr_db) && !std::isnan(t.elevation_rad);
    simulated_with_rcs += t.simulated && !std::isnan(t.rcs_dbsm);
    if (t.target_class != metrics::TargetClass::object) return;
    ++n;
    ASSERT_TRUE(t.p_OT_O.has_value());
    EXPECT_LE(std::abs(t.p_OT_O->x()), 0.5 * size_m[t.object].first + options.association_gate_m);
    EXPECT_LE(std::abs(t.p_OT_O->y()), 0.5 * size_m[t.object].second + options.association_gate_m);
  });
  // The optional columns reach the report for the recorded targets only.
  EXPECT_EQ(recorded_with_all, 3909);
  EXPECT_EQ(simulated_with_rcs, 0);
  // Object targets lie within the association gate of their box, in the object's frame.
  EXPECT_EQ(n, k.object[0] + k.object[1]);
}

}  // namespace
}  // namespace rcsim::replay
