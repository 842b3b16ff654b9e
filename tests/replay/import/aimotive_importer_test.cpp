// The aiMotive importer (replay/import/aimotive_importer.hpp) on the real sample in
// ../shared/realdata (never part of the project; skipped, saying so, where it is absent): counts,
// mounting and frames (the detections land on the annotated boxes, and would not with the
// azimuth's sign flipped), the ego estimate (both radars agree), and refusals of damaged files.
#include "replay/import/aimotive_importer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "metrics/sensor_view.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

using rcsim::testing::kAimotiveRaw;

class AimotiveImporter : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (fs::is_directory(kAimotiveRaw)) imported_ = new DatasetRecording(import_aimotive(kAimotiveRaw));
  }
  static void TearDownTestSuite() {
    delete imported_;
    imported_ = nullptr;
  }
  void SetUp() override {
    if (imported_ == nullptr) GTEST_SKIP() << "real data absent (" << kAimotiveRaw.string() << "): aiMotive importer tests skipped";
  }
  static const Recording& rec() { return imported_->recording; }

  struct OnBoxes {
    int moving = 0, on_boxes = 0;
  };
  // The moving targets (radial speed 1 m/s or more from what the stationary world would give)
  // and how many of them lie within gate_m of an annotated box of their cycle.
  static OnBoxes moving_targets_on_boxes(const Recording& r, double gate_m, double azimuth_sign) {
    OnBoxes count;
    int& on = count.on_boxes;
    for (const RecordedTarget& t : r.targets) {
      const EgoSample& e = r.ego[static_cast<std::size_t>(t.cycle)];
      const RecordingSensor& s = r.sensors[static_cast<std::size_t>(t.sensor)];
      if (std::abs(t.range_rate_mps + e.speed_mps * std::cos(s.yaw_rad + t.azimuth_rad)) < 1.0) continue;
      ++count.moving;
      const Pose2 X_WS = compose(Pose2{e.x_m, e.y_m, e.yaw_rad}, Pose2{s.x_m, s.y_m, s.yaw_rad});
      BodyState ego;
      ego.X_WB = {e.x_m, e.y_m, e.yaw_rad};
      const double az = azimuth_sign * t.azimuth_rad;
      const Vec2 p_ST_S(t.range_m * std::cos(az), t.range_m * std::sin(az));
      for (std::size_t o = 0; o < r.objects.size(); ++o) {
        for (const AnnotatedBox& b : r.boxes[o]) {
          if (std::abs(b.t_s - t.t_s) > 1e-6) continue;
          BodyState object;
          object.X_WB = {b.x_m, b.y_m, b.yaw_rad};
          const auto box = metrics::box_in_sensor(0, X_WS, ego, object, r.objects[o].length_m, r.objects[o].width_m);
          if (metrics::distance_to_box_m(box, p_ST_S) <= gate_m) {
            ++on;
            goto next_target;
          }
        }
      }
    next_target:;
    }
    return count;
  }

  static DatasetRecording* imported_;
};
DatasetRecording* AimotiveImporter::imported_ = nullptr;

TEST_F(AimotiveImporter, CountsAndMountingAsTheSampleHasThem) {
  EXPECT_EQ(rec().cycle_count(), 50);
  EXPECT_NEAR(rec().cycle_time_s, 1.0 / 15.0, 2e-3);
  ASSERT_EQ(rec().sensors.size(), 2u);
  EXPECT_EQ(rec().sensors[0].id, "B_LRR_C");
  EXPECT_NEAR(rec().sensors[0].yaw_rad, 3.1346, 1e-3);  // looking backwards
  EXPECT_NEAR(rec().sensors[1].x_m, 3.8126, 1e-3);
  EXPECT_NEAR(rec().sensors[1].yaw_rad, -0.0122, 1e-3);
  EXPECT_EQ(rec().objects.size(), 8u);
  EXPECT_EQ(rec().targets.size(), 3909u);
  for (const auto& o : rec().objects) {
    EXPECT_EQ(o.object_class, o.id.rfind("truck", 0) == 0 ? "truck_trailer" : "passenger_car") << o.id;
  }
  // The radars get the built-in profile derived from them; no configuration file beside it.
  for (const auto& sensor : rec().sensors) EXPECT_EQ(sensor.type, "aimotive_lrr") << sensor.id;
  EXPECT_TRUE(imported_->extra_files.empty());
  EXPECT_TRUE(rec().all_sensors_report(ListLevel::detections));
  // RCS (dBsm), SNR and elevation kept as the optional columns.
  for (const RecordedTarget& t : rec().targets) {
    EXPECT_DOUBLE_EQ(t.snr_db, t.amplitude_db);
    EXPECT_GT(t.rcs_dbsm, -20.0);  // the sample's RCS: 0.087 to 11811 m^2
    EXPECT_LT(std::abs(t.elevation_rad), 0.2);
  }  // raw detections: replay compares without the tracker
}

TEST_F(AimotiveImporter, MovingDetectionsLandOnTheBoxesAndWouldNotWithTheAzimuthFlipped) {
  // Measured: 442 of the 705 moving targets within 1 m of a box; 58 with the azimuth's sign
  // flipped. (Of all 3909 targets, about 450 lie on boxes: the rest are guard rails, signs, road.)
  const OnBoxes right = moving_targets_on_boxes(rec(), 1.0, 1.0), flipped = moving_targets_on_boxes(rec(), 1.0, -1.0);
  EXPECT_GT(right.moving, 600);
  EXPECT_GT(right.on_boxes, right.moving / 2);
  EXPECT_LT(flipped.on_boxes, right.moving / 6);
}

TEST_F(AimotiveImporter, BothRadarsAgreeOnTheEgoSpeed) {
  const auto& ego = rec().source.at("ego_motion");
  EXPECT_EQ(ego.at("cycles_fitted").get<int>(), 50);
  EXPECT_LT(std::abs(ego.at("speed_difference_mps").at("mean").get<double>()), 0.05);
  EXPECT_LT(ego.at("speed_difference_mps").at("std").get<double>(), 0.05);
  EXPECT_LT(ego.at("residual_rms_mps").get<double>(), 0.1);
  for (const EgoSample& e : rec().ego) EXPECT_NEAR(e.speed_mps, 30.0, 0.5);
}

// --ego-log: the given log is used (here the Doppler estimate written out with 1 m/s added), the
// estimate is reported beside it as a check; a log that does not cover the keyframes is refused.
class AimotiveEgoLog : public rcsim::testing::ScratchDirTest {
 protected:
  AimotiveEgoLog() : ScratchDirTest("aimotive_ego") {}
  void SetUp() override {
    if (!fs::is_directory(kAimotiveRaw)) GTEST_SKIP() << "real data absent (" << kAimotiveRaw.string() << "): aiMotive ego-log tests skipped";
    ScratchDirTest::SetUp();
  }
  fs::path write_log(const std::vector<EgoSample>& ego, double add_mps, std::size_t rows) {
    const fs::path path = dir_ / "ego_log.csv";
    std::ofstream out(path);
    out << "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
    for (std::size_t k = 0; k < std::min(rows, ego.size()); ++k) {
      const EgoSample& e = ego[k];
      out << fmt::format("{:.9f},{},{},{},{},{}\n", e.t_s, e.x_m, e.y_m, e.yaw_rad, e.speed_mps + add_mps, e.yaw_rate_radps);
    }
    return path;
  }
};

TEST_F(AimotiveEgoLog, AGivenLogIsUsedAndTheDopplerEstimateReportedBesideIt) {
  const DatasetRecording estimated = import_aimotive(kAimotiveRaw);
  const fs::path log = write_log(estimated.recording.ego, 1.0, estimated.recording.ego.size());
  const DatasetRecording logged = import_aimotive(kAimotiveRaw, {log});
  ASSERT_EQ(logged.recording.ego.size(), estimated.recording.ego.size());
  for (std::size_t k = 0; k < logged.recording.ego.size(); ++k) {
    EXPECT_NEAR(logged.recording.ego[k].speed_mps, estimated.recording.ego[k].speed_mps + 1.0, 1e-6);
  }
  const auto& report = logged.recording.source.at("ego_motion");
  EXPECT_NE(report.at("method").get<std::string>().find("--ego-log"), std::string::npos);
  EXPECT_NEAR(report.at("doppler_check").at("speed_difference_mean_mps").get<double>(), -1.0, 1e-6);
  EXPECT_EQ(report.at("doppler_estimate").at("cycles_fitted").get<int>(), 50);
  // Through the command line, and a log that ends before the last keyframe is refused.
  const auto ok = rcsim::testing::run_rcsim("import --from aimotive " + kAimotiveRaw.string() + " --ego-log " + log.string() +
                                           " -o " + (dir_ / "rec").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  const fs::path short_log = write_log(estimated.recording.ego, 0.0, 40);
  const auto r = rcsim::testing::run_rcsim("import --from aimotive " + kAimotiveRaw.string() + " --ego-log " +
                                           short_log.string() + " -o " + (dir_ / "rec2").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("ego_log.csv"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "rec2"));
}

class AimotiveRefusals : public rcsim::testing::ScratchDirTest {
 protected:
  AimotiveRefusals() : ScratchDirTest("aimotive") {}
  void SetUp() override {
    if (!fs::is_directory(kAimotiveRaw)) GTEST_SKIP() << "real data absent (" << kAimotiveRaw.string() << "): aiMotive refusal tests skipped";
    ScratchDirTest::SetUp();
    fs::copy(kAimotiveRaw, dir_ / "raw", fs::copy_options::recursive);
    sequence_ = aimotive::find_sequence(dir_ / "raw");
  }
  std::string import_error() {
    try {
      import_aimotive(dir_ / "raw");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path sequence_;
};

TEST_F(AimotiveRefusals, ATruncatedRadarFileIsRefusedNamingIt) {
  const fs::path file = sequence_ / "sensor/radar/F_LRR_C/F_LRR_C_0033660.json";
  const std::string text = rcsim::testing::read_file(file);
  std::ofstream(file, std::ios::trunc) << text.substr(0, text.size() / 2);
  const std::string error = import_error();
  EXPECT_NE(error.find("F_LRR_C_0033660.json"), std::string::npos) << error;
  // And through the command line: exit 2, nothing written.
  const auto r = rcsim::testing::run_rcsim("import --from aimotive " + (dir_ / "raw").string() + " -o " + (dir_ / "rec").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "rec"));
}

TEST_F(AimotiveRefusals, AMissingFieldIsRefusedNamingFileAndField) {
  const fs::path file = sequence_ / "dynamic/box/3d_body/frame_0033650.json";
  std::string text = rcsim::testing::read_file(file);
  const auto at = text.find("\"BoundingBox3D Extent X\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 24, "\"Extent\"");
  std::ofstream(file, std::ios::trunc) << text;
  const std::string error = import_error();
  EXPECT_NE(error.find("frame_0033650.json"), std::string::npos) << error;
  EXPECT_NE(error.find("BoundingBox3D Extent X"), std::string::npos) << error;
}

// Found by the aimotive fuzzer: a noise of 2408 dB made an amplitude (power - noise) of -2338 dB,
// which the importer wrote and the recording's reader then refused (schemas/limits.md).
TEST_F(AimotiveRefusals, ALevelBeyondTheLimitIsRefusedAtImportNamingFileAndField) {
  const fs::path file = sequence_ / "sensor/radar/F_LRR_C/F_LRR_C_0033660.json";
  const std::string text = rcsim::testing::read_file(file);
  const std::string damaged = std::regex_replace(text, std::regex(R"("noise": [-0-9.e]+)"), R"("noise": 2408.0)",
                                                 std::regex_constants::format_first_only);
  ASSERT_NE(damaged, text);
  std::ofstream(file, std::ios::trunc) << damaged;
  const std::string error = import_error();
  EXPECT_NE(error.find("F_LRR_C_0033660.json"), std::string::npos) << error;
  EXPECT_NE(error.find("noise"), std::string::npos) << error;
  EXPECT_NE(error.find("1000 dB"), std::string::npos) << error;
}

// An RCS of 0 m^2 or below has no level in dBsm: it was written as -100 dBsm without a word.
TEST_F(AimotiveRefusals, ARadarCrossSectionOfZeroOrBelowIsRefusedNamingFileAndField) {
  const fs::path file = sequence_ / "sensor/radar/F_LRR_C/F_LRR_C_0033660.json";
  const std::string text = rcsim::testing::read_file(file);
  for (const char* rcs : {R"("rcs": 0.0)", R"("rcs": -3.5)"}) {
    const std::string damaged =
        std::regex_replace(text, std::regex(R"("rcs": [-0-9.e]+)"), rcs, std::regex_constants::format_first_only);
    ASSERT_NE(damaged, text);
    std::ofstream(file, std::ios::trunc) << damaged;
    const std::string error = import_error();
    EXPECT_NE(error.find("F_LRR_C_0033660.json"), std::string::npos) << error;
    EXPECT_NE(error.find("rcs: must be positive"), std::string::npos) << error;
  }
}

// A name with a newline was imported, and the written objects.csv then refused by `rcsim replay`:
// an importer writes only what rcsim reads back.
TEST_F(AimotiveRefusals, AnActorNameWithALineBreakIsRefusedNamingFileAndField) {
  const fs::path file = sequence_ / "dynamic/box/3d_body/frame_0033650.json";
  const std::string text = rcsim::testing::read_file(file);
  const std::string damaged = std::regex_replace(text, std::regex(R"re("ActorName": "([^"]*)")re"), R"re("ActorName": "$1\nX")re");
  ASSERT_NE(damaged, text);
  std::ofstream(file, std::ios::trunc) << damaged;
  const std::string error = import_error();
  EXPECT_NE(error.find("frame_0033650.json"), std::string::npos) << error;
  EXPECT_NE(error.find("ActorName: the name holds a newline (U+000A)"), std::string::npos) << error;
}

TEST_F(AimotiveRefusals, ABoxBeyondTheLimitsIsRefusedNamingFileAndField) {
  const fs::path file = sequence_ / "dynamic/box/3d_body/frame_0033650.json";
  const std::string text = rcsim::testing::read_file(file);
  const std::string damaged = std::regex_replace(text, std::regex(R"("BoundingBox3D Extent X": [-0-9.e]+)"),
                                                 R"("BoundingBox3D Extent X": 5000.0)", std::regex_constants::format_first_only);
  ASSERT_NE(damaged, text);
  std::ofstream(file, std::ios::trunc) << damaged;
  const std::string error = import_error();
  EXPECT_NE(error.find("frame_0033650.json"), std::string::npos) << error;
  EXPECT_NE(error.find("BoundingBox3D Extent X: |5000| exceeds the limit of 100 m"), std::string::npos) << error;
}

// A dropped keyframe was imported, and the recording then refused by `rcsim replay` (ego.csv: one
// row per cycle). The import refuses it, naming the keyframe after the gap.
TEST_F(AimotiveRefusals, AMissingKeyframeIsRefusedAtImportNamingTheNextOne) {
  fs::remove(sequence_ / "dynamic/box/3d_body/frame_0033650.json");
  const std::string error = import_error();
  EXPECT_NE(error.find("frame_0033651.json"), std::string::npos) << error;
  EXPECT_NE(error.find("a keyframe is missing"), std::string::npos) << error;
}

TEST_F(AimotiveRefusals, AMissingRadarFileAndAnUnknownDatasetAreRefused) {
  fs::remove(sequence_ / "sensor/radar/B_LRR_C/B_LRR_C_0033670.json");
  EXPECT_NE(import_error().find("B_LRR_C_0033670.json"), std::string::npos);
  const auto r = rcsim::testing::run_rcsim("import --from nuscenes " + (dir_ / "raw").string() + " -o " + (dir_ / "rec").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("known: aimotive"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rcsim::replay
