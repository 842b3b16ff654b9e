// The streamed import (replay/import/streaming_import.hpp) on a small recording written in code:
// cycles and targets as read whole, the window's steps and what is forgotten behind it by hand,
// presence spans and gap warnings as import_recording has them, the scene evaluating bit for bit
// as the whole scene does, and refusals naming the file.
#include "replay/import/streaming_import.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "common/input_error.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::streaming_import_test {

namespace fs = std::filesystem;

constexpr double kStart_s = 100.0;  // recording time of the first cycle: scene time 0
constexpr double kCycle_s = 0.1;
constexpr int kCycles = 100;        // 0 to 9.9 s

// The cycles at which the one car is annotated: 0-9, 20-29 (gaps of 1.1 s and 3.1 s: absent in
// between), 60-69 without 65 (a hole of 0.2 s: interpolated).
bool annotated(int k) { return k < 10 || (k >= 20 && k < 30) || (k >= 60 && k < 70 && k != 65); }

// A standing ego, one srr24, one car driving along x at 2 m/s; targets in cycles 3 and 50.
Recording gappy_recording() {
  Recording r;
  r.name = "gappy";
  r.cycle_time_s = kCycle_s;
  r.sensors.push_back({"front", "srr24", 3.7, 0.0, 0.0, ListLevel::tracks});
  r.objects.push_back({"car", "passenger_car", 4.6, 1.8, nlohmann::json::object()});
  r.boxes.resize(1);
  for (int k = 0; k < kCycles; ++k) {
    const double t_s = kStart_s + kCycle_s * k;
    r.ego.push_back({t_s, 0.0, 0.0, 0.0, 0.0, 0.0});
    if (annotated(k)) r.boxes[0].push_back({t_s, 20.0 + 0.2 * k, 1.0, 0.0, 2.0, 0});
  }
  for (const int k : {3, 3, 50}) {
    RecordedTarget t;
    t.t_s = kStart_s + kCycle_s * k, t.cycle = k, t.range_m = 20.0 + k, t.azimuth_rad = 0.01, t.amplitude_db = 10.0;
    r.targets.push_back(t);
  }
  return r;
}

class StreamingImportTest : public rcsim::testing::ScratchDirTest {
 protected:
  StreamingImportTest() : ScratchDirTest("streaming_import") {}
  fs::path written(const Recording& r) {
    write_recording(dir_ / "rec", r);
    return dir_ / "rec";
  }
};

TEST_F(StreamingImportTest, CyclesTargetsAndTheSceneAreTheWholeImportsBitForBit) {
  const fs::path dir = written(gappy_recording());
  const Recording whole = read_recording(dir);
  const ImportedScene imported_whole = import_recording(whole, testing::library(), ImportOptions{});
  const Scene scene_whole = build_scene(imported_whole, testing::library(), dir.string());

  StreamingImport stream(dir, testing::library(), ImportOptions{});
  EXPECT_EQ(stream.recording().cycle_count(), kCycles);
  EXPECT_TRUE(stream.recording().targets.empty());  // the header only
  EXPECT_DOUBLE_EQ(stream.imported().time_offset_s, kStart_s);
  EXPECT_NEAR(stream.imported().duration_s, 9.9, 1e-9);  // 99 cycles of 0.1 s
  int cycle = -1, expected = 0, sensor = 0;
  double t_rec_s = 0.0;
  std::vector<RecordedTarget> targets;
  std::size_t targets_seen = 0;
  while (stream.next_cycle(cycle, t_rec_s, sensor, targets)) {
    ASSERT_EQ(cycle, expected);
    EXPECT_EQ(t_rec_s, whole.ego[static_cast<std::size_t>(cycle)].t_s);
    EXPECT_EQ(targets.size(), cycle == 3 ? 2u : cycle == 50 ? 1u : 0u) << cycle;
    targets_seen += targets.size();
    const double t_s = t_rec_s - kStart_s;
    const SceneObject& car = stream.scene().objects.at(0);
    ASSERT_EQ(car.present_at(t_s), scene_whole.objects[0].present_at(t_s)) << cycle;
    if (car.present_at(t_s)) {
      const BodyState a = car.trajectory.state_at(t_s), b = scene_whole.objects[0].trajectory.state_at(t_s);
      EXPECT_EQ(a.X_WB.x_m, b.X_WB.x_m) << cycle;
      EXPECT_EQ(a.X_WB.y_m, b.X_WB.y_m) << cycle;
      EXPECT_EQ(a.X_WB.yaw_rad, b.X_WB.yaw_rad) << cycle;
      EXPECT_EQ(a.v_WB_W, b.v_WB_W) << cycle;
    }
    ++expected;
  }
  EXPECT_EQ(expected, kCycles);
  EXPECT_EQ(targets_seen, 3u);
  EXPECT_FALSE(stream.next_cycle(cycle, t_rec_s, sensor, targets));  // and stays at the end
  // Three spans, by hand: [0 - 0.05, 0.9 + 0.05], [2.0 - 0.05, 2.9 + 0.05], [6.0 - 0.05, 6.9 + 0.05].
  const std::vector<TimeInterval>& presence = stream.scene().objects[0].presence;
  ASSERT_EQ(presence.size(), 3u);
  for (const auto& [i, from_s, until_s] : std::vector<std::tuple<std::size_t, double, double>>{{0, -0.05, 0.95}, {1, 1.95, 2.95}, {2, 5.95, 6.95}}) {
    EXPECT_NEAR(presence[i].from_s, from_s, 1e-9) << i;
    EXPECT_NEAR(presence[i].until_s, until_s, 1e-9) << i;
  }
  // The warnings as the whole import words them: lines 11 and 12 (cycles 9 and 20), 21 and 22
  // (29 and 60), 26 and 27 (64 and 66) of objects.csv.
  EXPECT_EQ(stream.imported().warnings, imported_whole.warnings);
  ASSERT_EQ(stream.imported().warnings.size(), 3u);
  EXPECT_EQ(stream.imported().warnings[0],
            (dir / "objects.csv").string() + ": lines 11 and 12: object 'car' not annotated for 1.100 s; absent from the scene in between");
  EXPECT_NE(stream.imported().warnings[2].find("lines 26 and 27: object 'car' not annotated for 0.200 s; interpolated"),
            std::string::npos)
      << stream.imported().warnings[2];
}

TEST_F(StreamingImportTest, TheWindowStepsFourSecondsAndForgetsWhatLiesASecondBehind) {
  StreamingImport stream(written(gappy_recording()), testing::library(), ImportOptions{});
  EXPECT_FALSE(stream.take_moved_window().has_value());  // nothing replayed yet
  int cycle = 0, sensor = 0;
  double t_rec_s = 0.0;
  std::vector<RecordedTarget> targets;
  ASSERT_TRUE(stream.next_cycle(cycle, t_rec_s, sensor, targets));
  const auto first = stream.take_moved_window();
  ASSERT_TRUE(first.has_value());
  EXPECT_DOUBLE_EQ(first->first, 0.0);
  EXPECT_DOUBLE_EQ(first->second, 4.0);
  EXPECT_FALSE(stream.take_moved_window().has_value());  // taken once
  // Cycles up to 4.0 s lie in it; cycle 41 (4.1 s) moves it to [4.1, 8.1].
  for (int k = 1; k <= 40; ++k) {
    ASSERT_TRUE(stream.next_cycle(cycle, t_rec_s, sensor, targets));
    EXPECT_FALSE(stream.take_moved_window().has_value()) << k;
  }
  ASSERT_TRUE(stream.next_cycle(cycle, t_rec_s, sensor, targets));
  EXPECT_EQ(cycle, 41);
  const auto second = stream.take_moved_window();
  ASSERT_TRUE(second.has_value());
  EXPECT_NEAR(second->first, 4.1, 1e-9);
  EXPECT_NEAR(second->second, 8.1, 1e-9);
  // What lies behind is forgotten once it is half the storage: not yet (the ego holds 0 to 8.2 s,
  // 31 of its 83 samples lie a second behind 4.1 s) ...
  EXPECT_EQ(stream.scene().ego.start_s(), 0.0);
  EXPECT_GE(stream.scene().ego.end_s(), 8.1);
  // ... but at the next step, cycle 82 (8.2 s > 8.1 s): 72 of the 100 samples lie before 7.2 s,
  // the ego keeps the last at or before it (7.1 or 7.2 s, as the written times round).
  std::optional<std::pair<double, double>> third;
  while (!third && stream.next_cycle(cycle, t_rec_s, sensor, targets)) third = stream.take_moved_window();
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(cycle, 82);
  EXPECT_NEAR(third->second, 12.2, 1e-9);
  EXPECT_GE(stream.scene().ego.start_s(), 7.1 - 1e-9);
  EXPECT_LE(stream.scene().ego.start_s(), 7.2 + 1e-9);
  EXPECT_NEAR(stream.scene().ego.end_s(), 9.9, 1e-9);  // the last ego row
}

TEST_F(StreamingImportTest, AnEgoLogWithoutRowsAndTargetsBeyondItAreRefusedNamingTheFile) {
  const fs::path dir = written(gappy_recording());
  {
    // Line 5, after the three targets: a row of cycle 100, one beyond the ego log.
    std::ofstream(dir / "targets.csv", std::ios::app) << "110.000000,100,front,30.0000,0.010000,0.0000,10.000\n";
    StreamingImport stream(dir, testing::library(), ImportOptions{});
    int cycle = 0, sensor = 0;
    double t_rec_s = 0.0;
    std::vector<RecordedTarget> targets;
    try {
      while (stream.next_cycle(cycle, t_rec_s, sensor, targets)) {
      }
      ADD_FAILURE() << "a target beyond the ego log was streamed";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), (dir / "targets.csv").string() +
                                           ": line 5, column 'cycle': cycle 100 is outside the ego log's cycles 0..99");
    }
  }
  std::ofstream(dir / "ego.csv") << "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
  try {
    StreamingImport stream(dir, testing::library(), ImportOptions{});
    ADD_FAILURE() << "an ego log without rows was streamed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "ego.csv").string() + ": line 1: the ego log has no rows");
  }
}

}  // namespace rcsim::replay::streaming_import_test
