// The imaging radar's goals (issue 29, docs/imaging-radar.md), pinned on the frames nobody fitted:
// Astyx HiRes2019 frames 200-399 imported as `rcsim import --from astyx --frames 200-399` does,
// replayed with the built-in astyx_hires (fitted on frames 0-199) at the default seed. Reads the
// real data from ../shared/realdata/ and skips, saying so, where it is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "metrics/distribution_distance.hpp"
#include "replay/import/dataset_importer.hpp"
#include "replay/run/replay_run.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace astyx_held_out_test {
namespace {

namespace fs = std::filesystem;

const fs::path kHires = testing::kAstyxRaw / "dataset_astyx_hires2019";

// The object targets of cars 5-40 m from the radar, in the car's frame (the offsets goal).
class CarOffsets final : public ReplaySink {
 public:
  void begin_run(const Recording& recording, const ImportedScene&, const Scene&, const ReplayOptions&) override {
    is_car_.clear();
    for (const RecordingObject& o : recording.objects) is_car_.push_back(o.object_class == "passenger_car");
  }
  void add_cycle(const CycleComparison& cycle) override {
    for (int origin = 0; origin < 2; ++origin) {
      for (const ComparedTarget& t : origin == 0 ? cycle.recorded : cycle.simulated) {
        if (t.target_class != metrics::TargetClass::object || t.object < 0) continue;
        if (!is_car_[static_cast<std::size_t>(t.object)] || t.range_m < 5.0 || t.range_m >= 40.0) continue;
        x_m[origin].push_back(t.p_OT_O.x());
        y_m[origin].push_back(t.p_OT_O.y());
      }
    }
  }
  void end_run(const ReplaySummary&) override {}

  std::vector<double> x_m[2], y_m[2];  // [0] recorded, [1] simulated

 private:
  std::vector<bool> is_car_;
};

struct RangeBin {
  int cars = 0;  // car-bin rows: a car in view in a frame, binned by its nearest point's range
  long long targets_recorded = 0, targets_simulated = 0;
  int detected_recorded = 0, detected_simulated = 0;
};

TEST(AstyxHeldOut, FramesNobodyFittedMeetTheImagingGoals) {
  if (!fs::is_directory(kHires)) {
    GTEST_SKIP() << "real data absent (" << kHires.string() << "): the Astyx held-out goals are not checked";
  }
  DatasetImportOptions import;
  import.frames = "200-399";
  const DatasetRecording held_out = find_dataset_importer("astyx").import(kHires, import);
  ASSERT_EQ(held_out.recording.cycle_count(), 200);
  CarOffsets offsets;
  const ReplaySummary s = replay_recording(held_out.recording, ReplayOptions{}, offsets);

  // Object targets, simulated over recorded: goal [0.8, 1.25]; measured 0.91.
  const double object_ratio = static_cast<double>(s.classes.object[1]) / static_cast<double>(s.classes.object[0]);
  EXPECT_GE(object_ratio, 0.8);
  EXPECT_LE(object_ratio, 1.25);

  std::map<double, RangeBin> bins;
  for (const ObjectRangeRow& row : s.object_ranges) {
    if (held_out.recording.objects[static_cast<std::size_t>(row.object)].object_class != "passenger_car") continue;
    RangeBin& bin = bins[row.range_from_m];
    bin.cars += row.cycles_in_view;
    bin.targets_recorded += row.targets_recorded;
    bin.targets_simulated += row.targets_simulated;
    bin.detected_recorded += row.cycles_detected_recorded;
    bin.detected_simulated += row.cycles_detected_simulated;
  }
  int judged = 0;
  for (const auto& [from_m, bin] : bins) {
    if (bin.cars < 20) continue;  // the goal's bins: at least 20 cars
    ++judged;
    const double ratio = static_cast<double>(bin.targets_simulated) / static_cast<double>(bin.targets_recorded);
    // Detections per car within a factor of 1.5 (measured 0.78 to 1.42, docs/imaging-radar.md).
    EXPECT_GE(ratio, 1.0 / 1.5) << from_m << " m";
    EXPECT_LE(ratio, 1.5) << from_m << " m";
    // The share of cars detected within 0.15.
    const double share_recorded = static_cast<double>(bin.detected_recorded) / bin.cars;
    const double share_simulated = static_cast<double>(bin.detected_simulated) / bin.cars;
    EXPECT_LE(std::abs(share_simulated - share_recorded), 0.15) << from_m << " m";
  }
  EXPECT_EQ(judged, 10);  // 0-10 m to 90-100 m

  // The offsets in the car's frame at 5-40 m: KS of x and of y at most 0.25.
  ASSERT_GT(offsets.x_m[0].size(), 10'000u);
  ASSERT_GT(offsets.x_m[1].size(), 10'000u);
  const metrics::DistributionDistance x = metrics::distribution_distance(offsets.x_m[0], offsets.x_m[1]);
  const metrics::DistributionDistance y = metrics::distribution_distance(offsets.y_m[0], offsets.y_m[1]);
  EXPECT_LE(x.kolmogorov_smirnov, 0.25);
  EXPECT_LE(y.kolmogorov_smirnov, 0.25);
  RecordProperty("object_ratio", std::to_string(object_ratio));
  RecordProperty("ks_offset_x_5_40m", std::to_string(x.kolmogorov_smirnov));
  RecordProperty("ks_offset_y_5_40m", std::to_string(y.kolmogorov_smirnov));
  std::printf("astyx held-out: object targets %.3f x recorded; cars 5-40 m offsets KS x %.3f, y %.3f (W1 %.3f, %.3f m)\n",
              object_ratio, x.kolmogorov_smirnov, y.kolmogorov_smirnov, x.wasserstein1, y.wasserstein1);
}

}  // namespace
}  // namespace astyx_held_out_test
}  // namespace rcsim::replay
