// End-to-end: every recording of recordings_synthetic/ (made by the signal-level reference)
// replayed through the reflection-center model. The bounds are what the model must keep to stay
// useful, with the figures measured when they were set in the comments.
#include <gtest/gtest.h>

#include <filesystem>

#include <algorithm>
#include <fmt/format.h>

#include "io/recording.hpp"
#include "replay/import/calibration.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

const fs::path kSyntheticRecordingsDir = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic";

struct NullSink final : ReplaySink {
  void begin_run(const Recording&, const ImportedScene&, const Scene&, const ReplayOptions&) override {}
  void add_cycle(const CycleComparison&) override { ++cycles; }
  void end_run(const ReplaySummary&) override {}
  int cycles = 0;
};

ReplaySummary replay(const std::string& name, NullSink& sink, const std::string& calibration_dir = "") {
  ReplayOptions options;
  options.seed = 1;
  options.import.calibration_dir = calibration_dir;
  return replay_recording(read_recording(kSyntheticRecordingsDir / name), options, sink);
}

std::vector<fs::path> recordings_in(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (fs::exists(entry.path() / "recording.json")) found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

TEST(SyntheticRecordings, EveryRecordingReplaysAndEveryTargetIsAccountedFor) {
  int recordings = 0;
  for (const auto& entry : fs::directory_iterator(kSyntheticRecordingsDir)) {
    if (!fs::exists(entry.path() / "recording.json")) continue;
    ++recordings;
    const std::string name = entry.path().filename().string();
    const Recording rec = read_recording(entry.path());
    NullSink sink;
    const ReplaySummary s = replay(name, sink);
    EXPECT_EQ(s.targets_recorded, static_cast<long long>(rec.targets.size())) << name;
    EXPECT_EQ(sink.cycles, rec.cycle_count() * static_cast<int>(rec.sensors.size())) << name;
    EXPECT_GT(s.targets_simulated, 0) << name;
    // Measured 0.24 m (overtaking) to 1.94 m (60-s drive, parking area).
    EXPECT_LT(s.gospa_mean_m, 2.5) << name;
    EXPECT_GT(s.targets_matched, s.targets_recorded / 3) << name;
  }
  EXPECT_EQ(recordings, 9);
}

TEST(SyntheticRecordings, TwoCarsInOneCellShowMergeArtefactsInBoth) {
  // Paper Fig. 10: measured 93 recorded, 114 simulated.
  NullSink sink;
  const ReplaySummary s = replay("two_in_one_cell", sink);
  EXPECT_GT(s.merge_artefacts_recorded, 20);
  EXPECT_GT(s.merge_artefacts_simulated, 20);
  EXPECT_GT(s.merge_artefacts_matched, 10);
}

TEST(SyntheticRecordings, NoMergeArtefactsWhereNoTwoObjectsShareACell) {
  NullSink sink;
  for (const char* name : {"front_approach", "perpendicular_crossing", "overtaking"}) {
    const ReplaySummary s = replay(name, sink);
    EXPECT_EQ(s.merge_artefacts_recorded, 0) << name;
    EXPECT_EQ(s.merge_artefacts_simulated, 0) << name;
  }
}

TEST(SyntheticRecordings, ConfirmationLatencyIsFoundInBoth) {
  // Both sides are timed from when the geometry makes the object detectable. The model reports on
  // its 4th hit (3 cycles of 40 ms) and the latency rule wants reports in 3 of 4 cycles (2 more):
  // 0.20 s where the model detects from the episode's start. The reference's own tracker also
  // needs 4 hits, but its detection starts earlier or later than eq. (1) says.
  for (const char* name : {"front_approach", "perpendicular_crossing", "close_front", "standstill_1m"}) {
    NullSink sink;
    const ReplaySummary s = replay(name, sink);
    ASSERT_GT(s.latency_pairs, 0) << name;
    EXPECT_NEAR(s.latency_simulated_s, 0.20, 1e-9) << name;
    EXPECT_GE(s.latency_recorded_s, 0.0) << name;
    EXPECT_LT(s.latency_recorded_s, 1.0) << name;
  }
}

TEST(SyntheticRecordings, OnTheCornerApproachTheModelIsLate) {
  // Paper Fig. 15: the parked car's front-left corner (ERCS 1) faces the sensors from 25 m, inside
  // eq. (1)'s 27.3 m, so it is detectable from the first cycle. The reference reports it within
  // 0.4 s; the model, whose antenna pattern at 30 deg off boresight keeps the corner's echo 3 dB
  // under the threshold, only near 2 s: about 1.7 s late.
  NullSink sink;
  const ReplaySummary s = replay("corner_approach", sink);
  ASSERT_EQ(s.latency_pairs, 2);
  for (const LatencyRow& r : s.latencies) EXPECT_LE(r.detectable_from_s, 0.1);
  EXPECT_LT(s.latency_recorded_s, 0.5);
  EXPECT_NEAR(s.latency_difference_mean_s, 1.74, 0.2);
}

// The calibration campaign (recordings_synthetic/campaign/): other situations than the nine, and a
// calibration fitted on them alone, so that the nine measure it as drives it has never seen.
TEST(SyntheticRecordings, TheCampaignCalibrationIsFittedOnNoneOfTheNineAndLowersTheirMeanError) {
  const fs::path campaign = kSyntheticRecordingsDir / "campaign";
  const auto campaign_recordings = recordings_in(campaign);
  EXPECT_EQ(campaign_recordings.size(), 13u);
  const auto calibration = load_calibration((campaign / "calibration").string());
  std::vector<std::string> campaign_checksums;
  for (const auto& dir : campaign_recordings) campaign_checksums.push_back(fmt::format("{:016x}", read_recording(dir).checksum));
  std::sort(campaign_checksums.begin(), campaign_checksums.end());
  auto fitted = calibration->fitted_on_checksums;
  std::sort(fitted.begin(), fitted.end());
  EXPECT_EQ(fitted, campaign_checksums);  // fitted on the campaign, all of it

  double before_m = 0.0, after_m = 0.0;
  const auto nine = recordings_in(kSyntheticRecordingsDir);
  ASSERT_EQ(nine.size(), 9u);
  for (const auto& dir : nine) {
    const std::string name = dir.filename().string();
    EXPECT_EQ(std::count(fitted.begin(), fitted.end(), fmt::format("{:016x}", read_recording(dir).checksum)), 0) << name;
    NullSink sink;
    before_m += replay(name, sink).gospa_mean_m;
    after_m += replay(name, sink, (campaign / "calibration").string()).gospa_mean_m;
  }
  // Measured: mean GOSPA over the nine 0.917 m with the paper's values, 0.834 m calibrated.
  EXPECT_LT(after_m, 0.95 * before_m) << before_m / 9 << " m -> " << after_m / 9 << " m";
}

}  // namespace
}  // namespace rcsim::replay
