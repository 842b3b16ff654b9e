// Recording format version 4 (schemas/recording.md): sensors on their own clocks. Each sensor's
// cycles are listed in cycles.csv, the ego log runs at a rate of its own and is interpolated to
// them; a round trip keeps all of it, older recordings are untouched, every refusal names the
// file and the line or field.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "io/recording_stream.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::recording_v4_test {
namespace {

namespace fs = std::filesystem;
using testing::refusal_of;

class RecordingV4 : public testing::ScratchDirTest {
 protected:
  RecordingV4() : ScratchDirTest("rec_v4") {}
  // Two radars: "front" at 20 Hz from t = 0, "rear" at 15 Hz from t = 0.013 s; the ego log at
  // 10 Hz, driving along x at 10 m/s.
  void SetUp() override {
    ScratchDirTest::SetUp();
    rec_.name = "two_clocks";
    rec_.cycle_time_s = 0.1;  // the annotation's step
    rec_.clock = Clock::per_sensor;
    rec_.sensors = {{"front", "srr24", 3.6, 0.0, 0.0}, {"rear", "srr24", -1.0, 0.0, 3.14159}};
    rec_.sensors[0].cycle_time_s = 0.05;
    rec_.sensors[1].cycle_time_s = 1.0 / 15.0;
    rec_.objects = {{"car", "passenger_car", 4.5, 1.8}};
    rec_.boxes = {{}};
    for (int k = 0; k <= 10; ++k) {
      const double t_s = 0.1 * k;
      rec_.ego.push_back({t_s, 10.0 * t_s, 0.0, 0.0, 10.0, 0.0});
      rec_.boxes[0].push_back({t_s, 30.0 + 10.0 * t_s, 0.0, 0.0, 0.0, 0});
    }
    std::vector<SensorCycle> front, rear;
    for (int k = 0; k * 0.05 <= 1.0 + 1e-9; ++k) front.push_back({0.05 * k, 0});
    for (int k = 0; 0.013 + k / 15.0 <= 1.0; ++k) rear.push_back({0.013 + k / 15.0, 1});
    std::merge(front.begin(), front.end(), rear.begin(), rear.end(), std::back_inserter(rec_.cycles),
               [](const SensorCycle& a, const SensorCycle& b) { return a.t_s < b.t_s; });
    for (std::size_t k = 0; k < rec_.cycles.size(); ++k) {
      const SensorCycle& c = rec_.cycles[k];
      rec_.targets.push_back({std::round(c.t_s * 1e6) / 1e6, static_cast<int>(k), c.sensor, -1, 25.0, 0.0, 0.0, 40.0});
    }
  }
  fs::path written() const {
    write_recording(dir_ / "r", rec_);
    return dir_ / "r";
  }
  Recording rec_;
};

TEST_F(RecordingV4, RoundTripKeepsEachSensorsClockAndWritesVersion4) {
  const fs::path dir = written();
  const std::string header = testing::file_bytes(dir / "recording.json");
  EXPECT_NE(header.find("\"version\": 4"), std::string::npos) << header;
  EXPECT_NE(header.find("\"clock\": \"per_sensor\""), std::string::npos) << header;
  EXPECT_EQ(testing::file_bytes(dir / "cycles.csv").substr(0, 30), "t_s,sensor\n0.000000,front\n0.01");
  const Recording back = read_recording(dir);
  EXPECT_EQ(back.clock, Clock::per_sensor);
  ASSERT_EQ(back.cycle_count(), static_cast<int>(rec_.cycles.size()));
  EXPECT_EQ(back.cycle_count(), 21 + 15);  // 20 Hz over [0, 1] s, 15 Hz over [0.013, 1] s
  EXPECT_EQ(back.sensor_cycle_count(), 36);
  EXPECT_DOUBLE_EQ(back.sensor_cycle_time_s(0), 0.05);
  EXPECT_NEAR(back.sensor_cycle_time_s(1), 1.0 / 15.0, 1e-12);
  EXPECT_EQ(back.cycle_sensor(1), 1);  // the rear's first cycle at 0.013 s comes second
  EXPECT_NEAR(back.cycle_t_s(1), 0.013, 1e-9);
  EXPECT_EQ(back.ego.size(), 11u);
  ASSERT_EQ(back.targets.size(), rec_.targets.size());
  EXPECT_EQ(back.targets[1].sensor, 1);
  EXPECT_EQ(back.targets[1].cycle, 1);
  // The streamed header counts the cycles listed, not the ego rows.
  RecordingStream stream(dir);
  EXPECT_EQ(stream.header().cycle_count(), 36);
}

TEST_F(RecordingV4, TheChecksumCoversCyclesCsv) {
  const fs::path dir = written();
  const std::uint64_t before = recording_checksum(dir);
  EXPECT_EQ(before, read_recording(dir).checksum);
  std::string cycles = testing::file_bytes(dir / "cycles.csv");
  cycles.replace(cycles.find("0.000000,front"), 14, "0.000001,front");
  std::ofstream(dir / "cycles.csv", std::ios::trunc) << cycles;
  EXPECT_NE(recording_checksum(dir), before);
}

// Linear between the rows, the yaw along the shorter arc across ±π: hand-computed.
TEST_F(RecordingV4, TheEgoIsInterpolatedToEachSensorsCycle) {
  Recording r = rec_;
  r.ego = {{0.0, 0.0, 0.0, 3.1, 10.0, 0.0}, {0.1, 3.0, 1.0, -3.1, 14.0, 0.2}};
  r.cycles = {{0.0, 0}, {0.025, 1}, {0.1, 0}};
  const EgoSample e = r.ego_at_cycle(1);
  EXPECT_DOUBLE_EQ(e.t_s, 0.025);
  EXPECT_NEAR(e.x_m, 0.75, 1e-12);
  EXPECT_NEAR(e.y_m, 0.25, 1e-12);
  EXPECT_NEAR(e.yaw_rad, 3.1 + 0.25 * (2.0 * M_PI - 6.2), 1e-12);  // 0.0208 on through π, not back across 0
  EXPECT_NEAR(e.speed_mps, 11.0, 1e-12);
  EXPECT_NEAR(e.yaw_rate_radps, 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(r.ego_at_cycle(2).x_m, 3.0);
}

TEST_F(RecordingV4, ASharedClockRecordingStaysVersion1To3ByteForByte) {
  Recording shared = rec_;
  shared.clock = Clock::shared;
  shared.cycles.clear();
  shared.sensors = {rec_.sensors[0]};
  shared.sensors[0].cycle_time_s = 0.0;
  shared.targets.clear();
  write_recording(dir_ / "s", shared);
  EXPECT_NE(testing::file_bytes(dir_ / "s" / "recording.json").find("\"version\": 1"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "s" / "cycles.csv"));
}

TEST_F(RecordingV4, CyclesOfAnotherSensorsClockOrOutOfOrderAreRefusedNamingTheLine) {
  const fs::path dir = written();
  const auto with = [&](const std::string& file, const std::string& from, const std::string& to) {
    const fs::path copy = dir_ / "copy";
    fs::remove_all(copy);
    fs::copy(dir, copy);
    std::string text = testing::file_bytes(copy / file);
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(copy / file, std::ios::trunc) << text;
    return refusal_of([&] { read_recording(copy); });
  };
  // A target in the rear's cycle said to be the front's.
  std::string m = with("targets.csv", "0.013000,1,rear", "0.013000,1,front");
  EXPECT_NE(m.find("targets.csv: line 3, column 'sensor'"), std::string::npos) << m;
  EXPECT_NE(m.find("which cycles.csv gives to sensor 'rear'"), std::string::npos) << m;
  // A target's time not its cycle's.
  m = with("targets.csv", "0.013000,1,rear", "0.014000,1,rear");
  EXPECT_NE(m.find("cycle 1's time 0.013 s in cycles.csv"), std::string::npos) << m;
  // Rows out of time order.
  m = with("cycles.csv", "0.013000,rear\n", "0.013000,rear\n0.013000,rear\n");
  EXPECT_NE(m.find("cycles.csv: line 4"), std::string::npos) << m;
  EXPECT_NE(m.find("strictly increase"), std::string::npos) << m;
  m = with("cycles.csv", "0.050000,front", "0.010000,front");
  EXPECT_NE(m.find("rows must be in time order"), std::string::npos) << m;
  // An unknown sensor.
  m = with("cycles.csv", "0.013000,rear", "0.013000,side");
  EXPECT_NE(m.find("sensor 'side' is not listed"), std::string::npos) << m;
  // A cycle beyond the ego log's end by more than the margin (0.1 s), one within it.
  m = with("cycles.csv", "1.000000,front\n", "1.000000,front\n1.099000,rear\n");
  EXPECT_EQ(m, "accepted");
  m = with("cycles.csv", "1.000000,front\n", "1.000000,front\n1.101000,rear\n");
  EXPECT_NE(m.find("cycles.csv: line 38"), std::string::npos) << m;
  EXPECT_NE(m.find("beyond the ego log's 0 to 1 s by more than 0.1 s"), std::string::npos) << m;
  // The ego log with a hole longer than a second.
  m = with("ego.csv", "0.500000,", "1.500000,");
  EXPECT_NE(m.find("ego.csv"), std::string::npos) << m;
  // Without cycles.csv.
  fs::remove(dir / "cycles.csv");
  m = refusal_of([&] { read_recording(dir); });
  EXPECT_NE(m.find("cycles.csv"), std::string::npos) << m;
}

TEST_F(RecordingV4, TheClockFieldsAreRefusedWhereTheyDoNotBelong) {
  const fs::path dir = written();
  const std::string header = testing::file_bytes(dir / "recording.json");
  const auto with_header = [&](const std::string& from, const std::string& to) {
    std::string text = header;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(dir / "recording.json", std::ios::trunc) << text;
    return refusal_of([&] { read_recording(dir); });
  };
  std::string m = with_header("\"version\": 4", "\"version\": 3");
  EXPECT_NE(m.find("clock: is a version 4 field, but the recording says version 3"), std::string::npos) << m;
  m = with_header("\"per_sensor\"", "\"shared\"");
  EXPECT_NE(m.find("sensors[0].cycle_time_s"), std::string::npos) << m;
  EXPECT_NE(m.find("needs the recording's \"clock\": \"per_sensor\""), std::string::npos) << m;
  m = with_header("\"per_sensor\"", "\"own\"");
  EXPECT_NE(m.find("clock"), std::string::npos) << m;
  EXPECT_NE(m.find("\"shared\" or \"per_sensor\""), std::string::npos) << m;
  m = with_header("\"cycle_time_s\": 0.05", "\"cycle_time_s\": 0");
  EXPECT_NE(m.find("sensors[0].cycle_time_s"), std::string::npos) << m;
  m = with_header(",\n      \"cycle_time_s\": 0.05", "");
  EXPECT_NE(m.find("sensors[0].cycle_time_s: a sensor on its own clock"), std::string::npos) << m;
}

TEST_F(RecordingV4, ASensorWithoutCyclesIsRefused) {
  Recording r = rec_;
  std::erase_if(r.targets, [](const RecordedTarget& t) { return t.sensor == 1; });
  std::erase_if(r.cycles, [](const SensorCycle& c) { return c.sensor == 1; });
  for (std::size_t k = 0; k < r.targets.size(); ++k) r.targets[k].cycle = static_cast<int>(k);
  write_recording(dir_ / "r", r);
  const std::string m = refusal_of([&] { read_recording(dir_ / "r"); });
  EXPECT_NE(m.find("cycles.csv: sensor 'rear' of recording.json has no cycles"), std::string::npos) << m;
}

}  // namespace
}  // namespace rcsim::recording_v4_test
