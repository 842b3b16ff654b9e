// Bounded inputs of a recording (issue 19): a file that never ends (a device, a pipe) or a line
// beyond the stated limit is refused with a message naming the file and line, never read until
// memory runs out; objects.csv out of time order (replay streams it) is refused by line; and a
// long drive replays within a fixed memory limit.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "io/recording.hpp"
#include "sanitizers.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;

class BoundedInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_scratch_dir("bounded_input") / "rec";
    Recording rec;
    rec.name = "bounded";
    rec.cycle_time_s = 0.04;
    rec.sensors = {{"front", "srr24", 3.7, 0.0, 0.0}};
    rec.objects = {{"car1", "passenger_car", 4.5, 1.8}, {"car2", "passenger_car", 4.5, 1.8}};
    rec.boxes.resize(2);
    for (int k = 0; k < 50; ++k) {
      const double t = 0.04 * k;
      rec.ego.push_back({t, 0.0, 0.0, 0.0, 0.0, 0.0});
      rec.boxes[0].push_back({t, 20.0, 1.0, 3.14159, 0.0, 0});
      rec.boxes[1].push_back({t, 25.0, -1.0, 3.14159, 0.0, 0});
      rec.targets.push_back({t, k, 0, 3, 15.0, 0.1, -2.0, 12.5});
    }
    write_recording(dir_, rec);
  }

  std::string refusal() {
    try {
      read_recording(dir_);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  }

  fs::path dir_;
};

TEST_F(BoundedInput, ADeviceThatNeverEndsIsRefusedNotRead) {
  fs::remove(dir_ / "targets.csv");
  fs::create_symlink("/dev/zero", dir_ / "targets.csv");
  const std::string message = refusal();
  EXPECT_NE(message.find("targets.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
  // As a user meets it: rcsim replay says so and fails at once.
  const auto result = testing::run_rcsim(fmt::format("replay {} --db {}", dir_.string(), (dir_ / "r.sqlite").string()));
  EXPECT_EQ(result.exit_code, 2);  // bad input
  EXPECT_NE(result.output.find("targets.csv: not a regular file"), std::string::npos) << result.output;
}

TEST_F(BoundedInput, APipeIsRefusedWithoutWaitingForItsWriter) {
  fs::remove(dir_ / "objects.csv");
  ASSERT_EQ(::mkfifo((dir_ / "objects.csv").c_str(), 0600), 0);
  const std::string message = refusal();
  EXPECT_NE(message.find("objects.csv: not a regular file"), std::string::npos) << message;
}

TEST_F(BoundedInput, ALineBeyondTheLimitIsRefusedByNumber) {
  std::ofstream(dir_ / "targets.csv", std::ios::app) << std::string(kMaxLineBytes + 10, '7') << "\n";
  const std::string message = refusal();
  EXPECT_NE(message.find("targets.csv: line 52: line longer than the limit of 65536 bytes"), std::string::npos)
      << message;
  // A line at the limit is a line (here a malformed row, said as such).
  std::ofstream(dir_ / "targets.csv", std::ios::trunc)
      << "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n"
      << std::string(kMaxLineBytes - 1, '1') << "\n";
  const std::string at_limit = refusal();
  EXPECT_NE(at_limit.find("line 2: 1 fields where the header has 8"), std::string::npos) << at_limit;
}

TEST_F(BoundedInput, AJsonDocumentBeyondItsLimitOrFromADeviceIsRefused) {
  EXPECT_THROW(read_text_file("/dev/urandom"), InputError);
  std::ofstream(dir_ / "big.json") << std::string(2000, ' ');
  try {
    read_text_file(dir_ / "big.json", 1000);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2000 bytes exceed the limit of 1000 bytes"), std::string::npos) << e.what();
  }
}

TEST_F(BoundedInput, AnnotationsOutOfTimeOrderAreRefusedByLine) {
  std::ofstream(dir_ / "objects.csv", std::ios::trunc) << "t_s,object,x_m,y_m,yaw_rad,speed_mps\n"
                                                       << "0.08,car1,20,1,0,0\n"
                                                       << "0.04,car2,25,-1,0,0\n";
  const std::string message = refusal();
  EXPECT_NE(message.find("objects.csv: line 3, column 't_s': time 0.04 s precedes line 2's 0.08 s"), std::string::npos)
      << message;
}

#if RCSIM_UNDER_SANITIZER
TEST(StreamingMemory, ALongDriveReplaysWithinAFixedMemoryLimit) {
  GTEST_SKIP() << "the sanitizers reserve terabytes of address space: no address-space limit applies";
}
#else
// Half an hour, 40 annotated objects every cycle (1.8 million annotation rows, 95 MB of CSV):
// read whole, the annotations alone take about 400 MB in memory; streamed, the replay runs in
// an address space of 150 MB (the binary and its libraries included).
TEST(StreamingMemory, ALongDriveReplaysWithinAFixedMemoryLimit) {
  const fs::path dir = testing::fresh_scratch_dir("streaming_memory") / "long";
  fs::create_directories(dir);
  constexpr int kCycles = 45'000, kObjects = 40;
  {
    std::ofstream header(dir / "recording.json");
    header << R"({"format": "rcsim-recording", "version": 1, "name": "long", "cycle_time_s": 0.04,
      "sensors": [{"id": "front", "type": "srr24", "x_m": 3.7, "y_m": 0.0, "yaw_rad": 0.0}], "objects": [)";
    for (int o = 0; o < kObjects; ++o) {
      header << (o ? "," : "") << fmt::format(R"({{"id": "car{}", "class": "passenger_car", "length_m": 4.5, "width_m": 1.8}})", o);
    }
    header << "]}\n";
    std::ofstream ego(dir / "ego.csv"), objects(dir / "objects.csv"), targets(dir / "targets.csv");
    ego << "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
    objects << "t_s,object,x_m,y_m,yaw_rad,speed_mps\n";
    targets << "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n";
    for (int k = 0; k < kCycles; ++k) {
      const double t = 0.04 * k;
      ego << fmt::format("{:.6f},0.0000,0.0000,0.000000,0.0000,0.000000\n", t);
      // Far beyond the sensor's 40 m: the replay's cost is the reading and the annotations.
      for (int o = 0; o < kObjects; ++o) {
        objects << fmt::format("{:.6f},car{},{:.4f},{:.4f},0.000000,1.0000\n", t, o, 500.0 + 10.0 * o + 0.04 * k, 3.0 * o);
      }
      if (k % 10 == 0) targets << fmt::format("{:.6f},{},front,1,15.0000,0.100000,-2.0000,12.500\n", t, k);
    }
  }
  ASSERT_GT(fs::file_size(dir / "objects.csv"), 80'000'000u);
  const std::string command = fmt::format("ulimit -v 150000 && {} replay {} --db {} 2>&1", RCSIM_BINARY, dir.string(),
                                          (dir.parent_path() / "report.sqlite").string());
  FILE* pipe = popen(("bash -c '" + command + "'").c_str(), "r");
  std::string output(1 << 16, '\0');
  output.resize(fread(output.data(), 1, output.size(), pipe));
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(output.find("45000 cycles, 1 sensor,"), std::string::npos) << output;
  EXPECT_NE(output.find("all targets: 4500 recorded"), std::string::npos) << output;
}
#endif

}  // namespace
}  // namespace rcsim
