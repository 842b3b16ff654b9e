#include "io/recording.hpp"

#include "common/angles.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "io/recording_stream.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;

class RecordingFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rcsim_rec_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    rec_.name = "tiny";
    rec_.cycle_time_s = 0.04;
    rec_.sensors = {{"front_left", "srr24", 3.7, 0.7, 0.5}};
    rec_.objects = {{"car1", "passenger_car", 4.5, 1.8}};
    rec_.source = {{"generator", "test"}};
    rec_.boxes.resize(1);
    for (int k = 0; k < 3; ++k) {
      const double t = 0.04 * k;
      rec_.ego.push_back({t, 1.0 * k, 0.0, 0.0, 25.0, 0.0});
      rec_.boxes[0].push_back({t, 20.0, 1.0, 3.14159, 0.0, 0});
      rec_.targets.push_back({t, k, 0, 3, 15.0 + k, 0.1, -2.0, 12.5});
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes the recording, then replaces one file's text and expects the error to mention `expected`.
  void expect_refused(const std::string& file, const std::string& text, const std::string& expected) {
    const fs::path dir = dir_ / "bad";
    write_recording(dir, rec_);
    std::ofstream(dir / file, std::ios::trunc) << text;
    try {
      read_recording(dir);
      FAIL() << "accepted " << file << ":\n" << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  }

  fs::path dir_;
  Recording rec_;
};

// A mistyped recording directory is named with the nearest recording beside it; one nothing
// resembles, or beside no recording, only as what it is not.
TEST(RecordingDirectory, AMistypedDirectoryIsNamedWithTheNearestRecordingBesideIt) {
  const std::string bundled = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/";
  const auto message = [](const std::string& dir) {
    try {
      read_recording_header(dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(bundled + "two_in_one_cel"),
            bundled + "two_in_one_cel: not a recording directory; did you mean '" + bundled + "two_in_one_cell'?");
  EXPECT_EQ(message(bundled + "zzzzzzzzzz"), bundled + "zzzzzzzzzz: not a recording directory");
  EXPECT_EQ(message(bundled + "no_such/two_in_one_cel"), bundled + "no_such/two_in_one_cel: not a recording directory");
}

TEST_F(RecordingFiles, RoundTripKeepsEveryRowAndIsByteStable) {
  write_recording(dir_ / "a", rec_);
  const Recording back = read_recording(dir_ / "a");
  EXPECT_EQ(back.name, "tiny");
  EXPECT_EQ(back.cycle_count(), 3);
  ASSERT_EQ(back.targets.size(), 3u);
  EXPECT_EQ(back.targets[2].cycle, 2);
  EXPECT_EQ(back.targets[2].id, 3);
  EXPECT_DOUBLE_EQ(back.targets[2].range_m, 17.0);
  EXPECT_EQ(back.boxes[0].size(), 3u);
  EXPECT_EQ(back.source["generator"], "test");
  write_recording(dir_ / "b", back);
  EXPECT_EQ(read_recording(dir_ / "b").checksum, back.checksum);
}

// Version 2: a sensor that reports raw detections, without track ids; version 1 stays as it was.
TEST_F(RecordingFiles, VersionTwoDeclaresRawDetectionsAndVersionOneStaysReadable) {
  write_recording(dir_ / "v1", rec_);
  EXPECT_NE(testing::read_file(dir_ / "v1" / "recording.json").find("\"version\": 1"), std::string::npos);
  EXPECT_TRUE(read_recording(dir_ / "v1").all_sensors_report(ListLevel::tracks));
  Recording raw = rec_;
  raw.sensors[0].reports = ListLevel::detections;
  for (auto& t : raw.targets) t.id = -1;
  write_recording(dir_ / "v2", raw);
  const std::string header = testing::read_file(dir_ / "v2" / "recording.json");
  EXPECT_NE(header.find("\"version\": 2"), std::string::npos);
  EXPECT_NE(header.find("\"reports\": \"detections\""), std::string::npos);
  EXPECT_EQ(testing::read_file(dir_ / "v2" / "targets.csv").rfind("t_s,cycle,sensor,range_m,", 0), 0u);  // no id column
  const Recording back = read_recording(dir_ / "v2");
  EXPECT_TRUE(back.all_sensors_report(ListLevel::detections));
  EXPECT_EQ(back.targets[1].id, -1);
  // Version 1 has no "reports"; an unknown level and an unknown version are refused.
  std::string v1_with_reports = header;
  v1_with_reports.replace(v1_with_reports.find("\"version\": 2"), 12, "\"version\": 1");
  expect_refused("recording.json", v1_with_reports, "reports");
  std::string bad_level = header;
  bad_level.replace(bad_level.find("\"detections\""), 12, "\"plots\"");
  expect_refused("recording.json", bad_level, "plots");
  std::string v6 = header;
  v6.replace(v6.find("\"version\": 2"), 12, "\"version\": 6");
  expect_refused("recording.json", v6, "versions 1 to 5");
}

// Version 5: a sensor's height and pitch (a radar that measures elevation reads them), written
// only where one is set, read back; a version 4 file that names them is refused.
TEST_F(RecordingFiles, VersionFiveHoldsTheMountingsHeightAndPitch) {
  write_recording(dir_ / "level", rec_);
  EXPECT_EQ(testing::read_file(dir_ / "level" / "recording.json").find("pitch_rad"), std::string::npos);
  Recording raised = rec_;
  raised.sensors[0].z_m = 0.8;
  raised.sensors[0].pitch_rad = 0.02;
  write_recording(dir_ / "raised", raised);
  const std::string header = testing::read_file(dir_ / "raised" / "recording.json");
  EXPECT_NE(header.find("\"version\": 5"), std::string::npos);
  const Recording back = read_recording(dir_ / "raised");
  EXPECT_DOUBLE_EQ(back.sensors[0].z_m, 0.8);
  EXPECT_DOUBLE_EQ(back.sensors[0].pitch_rad, 0.02);
  std::string v4 = header;
  v4.replace(v4.find("\"version\": 5"), 12, "\"version\": 4");
  expect_refused("recording.json", v4, "z_m");
  std::string steep = header;
  steep.replace(steep.find("\"pitch_rad\": 0.02"), 18, "\"pitch_rad\": 1.2");
  expect_refused("recording.json", steep, "pitch_rad");
}

// Optional per-target columns: RCS, SNR and elevation, written only where given, read back.
TEST_F(RecordingFiles, OptionalTargetColumnsRoundTrip) {
  Recording extra = rec_;
  for (auto& t : extra.targets) t.rcs_dbsm = 4.25, t.snr_db = 31.5, t.elevation_rad = -0.02;
  write_recording(dir_ / "x", extra);
  EXPECT_NE(testing::read_file(dir_ / "x" / "targets.csv").find("amplitude_db,rcs_dbsm,snr_db,elevation_rad\n"),
            std::string::npos);
  const Recording back = read_recording(dir_ / "x");
  EXPECT_DOUBLE_EQ(back.targets[1].rcs_dbsm, 4.25);
  EXPECT_DOUBLE_EQ(back.targets[1].snr_db, 31.5);
  EXPECT_DOUBLE_EQ(back.targets[1].elevation_rad, -0.02);
  EXPECT_TRUE(std::isnan(read_recording((write_recording(dir_ / "y", rec_), dir_ / "y")).targets[0].rcs_dbsm));
  extra.targets[2].snr_db = RecordedTarget::kNoValue;  // given for some targets only: no such file is written
  EXPECT_THROW(write_recording(dir_ / "z", extra), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "z"));
  const std::string header = "t_s,cycle,sensor,range_m,azimuth_rad,range_rate_mps,amplitude_db,elevation_rad\n";
  expect_refused("targets.csv", header + "0.000000,0,front_left,10,0,0,10,5.0\n", "degrees");
}

TEST_F(RecordingFiles, RewritingReplacesAnEarlierRecordingWhole) {
  write_recording(dir_ / "a", rec_);
  rec_.targets.pop_back();
  write_recording(dir_ / "a", rec_);
  EXPECT_EQ(read_recording(dir_ / "a").targets.size(), 2u);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
  }
}

TEST_F(RecordingFiles, ReplacesOnlyARecordingOrAnEmptyDirectoryAndNeverALink) {
  const auto refusal = [&](const std::filesystem::path& to) {
    try {
      write_recording(to, rec_);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("written");
  };
  std::filesystem::create_directories(dir_ / "photos");
  std::ofstream(dir_ / "photos" / "holiday.jpg") << "not a recording";
  EXPECT_NE(refusal(dir_ / "photos").find("photos: is a directory without a recording.json"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir_ / "photos" / "holiday.jpg"));
  std::ofstream(dir_ / "file") << "x";
  EXPECT_NE(refusal(dir_ / "file").find("exists and is not a directory"), std::string::npos);
  std::filesystem::create_directories(dir_ / "empty");
  EXPECT_EQ(refusal(dir_ / "empty"), "written");
  std::filesystem::create_directory_symlink(dir_ / "empty", dir_ / "link");
  EXPECT_NE(refusal(dir_ / "link").find("is a symbolic link"), std::string::npos);
  EXPECT_EQ(refusal(dir_ / "empty"), "written");  // a recording it wrote is replaced
  // An id that would break its CSV row is not written.
  Recording bad = rec_;
  bad.objects.front().id = "car\n1";
  EXPECT_THROW(write_recording(dir_ / "bad", bad), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad"));
}

TEST_F(RecordingFiles, RefusesBadEgoLogs) {
  expect_refused("ego.csv", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,0,0,0\n0.04,0,0,0,0,0\n0.02,0,0,0,0,0\n",
                 "line 4, column 't_s'");
  expect_refused("ego.csv", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,0,0,0\n0.5,0,0,0,0,0\n", "gap");
  expect_refused("ego.csv", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,nan,0,0,0\n", "column 'y_m'");
  expect_refused("ego.csv", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,0,0,0\n0.04,0,0,0\n", "line 3");
  expect_refused("ego.csv", "t_s,x_m,yaw_rad,speed_mps,yaw_rate_radps\n", "'y_m'");
  expect_refused("ego.csv", "", "empty file");
  // Issue 21: a yaw in degrees. Heading 90 (east) in the first row; or a turn at 0.25 rad/s whose
  // yaw grows 0.573 per 40 ms cycle (degrees), 57 times what the yaw rate says.
  expect_refused("ego.csv", "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,90,10,0\n", "degrees");
  std::string turning = "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
  for (int k = 0; k < 8; ++k) turning += fmt::format("{:.2f},0,0,{:.4f},10,0.25\n", 0.04 * k, 0.573 * k);
  expect_refused("ego.csv", turning, "column 'yaw_rad'");
  expect_refused("ego.csv", turning, "degrees");
}

TEST_F(RecordingFiles, AYawInRadiansThatWrapsOrTurnsIsAccepted) {
  // The same turn in radians (0.01 rad per cycle), and a yaw that wraps from +pi to -pi.
  std::string text = "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
  for (int k = 0; k < 8; ++k) text += fmt::format("{:.2f},{},0,{:.6f},10,0.25\n", 0.04 * k, 0.4 * k, 3.10 + 0.01 * k);
  const fs::path dir = dir_ / "ok";
  rec_.ego.clear();
  for (int k = 0; k < 8; ++k) rec_.ego.push_back({0.04 * k, 0.4 * k, 0.0, wrap_angle_rad(3.10 + 0.01 * k), 10.0, 0.25});
  rec_.targets.clear();
  write_recording(dir, rec_);
  EXPECT_EQ(read_recording(dir).ego.size(), 8u);
  std::ofstream(dir / "ego.csv", std::ios::trunc) << text;
  EXPECT_EQ(read_recording(dir).ego.size(), 8u);
}

TEST_F(RecordingFiles, RefusesBadTargetsAndObjects) {
  const std::string header = "t_s,cycle,sensor,range_m,azimuth_rad,range_rate_mps,amplitude_db\n";
  expect_refused("targets.csv", header + "0.000000,0,rear,10,0,0,10\n", "sensor 'rear'");
  expect_refused("targets.csv", header + "0.040000,0,front_left,10,0,0,10\n", "differs from cycle 0");
  expect_refused("targets.csv", header + "0.000000,7,front_left,10,0,0,10\n", "outside");
  expect_refused("targets.csv", header + "0.000000,0,front_left,10,20.0,0,10\n", "degrees");
  expect_refused("targets.csv", header + "0.000000,0,front_left,10m,0,0,10\n", "not a number");
  // Issue 21: numbers beyond the stated limits are refused, naming the column.
  expect_refused("targets.csv", header + "0.000000,0,front_left,1e308,0,0,10\n", "column 'range_m'");
  expect_refused("targets.csv", header + "0.000000,0,front_left,10,0,-5000,10\n", "column 'range_rate_mps'");
  expect_refused("targets.csv", header + "0.000000,0,front_left,10,0,0,1e9\n", "limit of 1000 dB");
  expect_refused("objects.csv", "t_s,object,x_m,y_m,yaw_rad,speed_mps\n0,truck9,1,1,0,0\n", "'truck9'");
  expect_refused("objects.csv", "t_s,object,x_m,y_m,yaw_rad,speed_mps\n", "has no rows");
  expect_refused("recording.json", R"({"format": "rcsim-recording", "version": 9})", "version");
  expect_refused("recording.json",
                 R"({"format": "rcsim-recording", "version": 1, "name": "x", "cycle_time_s": 0.04,
                     "sensors": [{"id": "a", "type": "srr24", "x_m": 0, "y_m": 0, "yaw_deg": 0}], "objects": []})",
                 "yaw_deg");
}

TEST_F(RecordingFiles, MissingDirectoryIsNamed) {
  try {
    read_recording(dir_ / "nowhere");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere"), std::string::npos);
  }
}

}  // namespace
}  // namespace rcsim
