// `rcsim import --from mcap` (replay/import/mcap_importer.hpp) on logs written by the format's own
// writer (@mcap/core) with ROS 2's CDR (@foxglove/cdr): tests/tools/mcap/write_ros2_log.js turns a
// recording into radar_msgs/RadarScan, nav_msgs/Odometry and foxglove.SceneUpdate messages, and
// the import must give the recording back: the same targets (float32, as the messages carry them),
// boxes within 1 mm, the times exact; uncompressed, zstd and lz4 chunks alike. Damaged logs and
// mappings are refused naming what is wrong. Skips, saying so, without Node.js and the tool.
#include "replay/import/mcap_importer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "common/limits.hpp"
#include "fuzz/mcap_targets.hpp"
#include "io/mcap_writer.hpp"
#include "io/recording.hpp"
#include "peak_memory.hpp"
#include "refusal.hpp"
#include "replay/import/dataset_importer.hpp"
#include "replay/profile/sensor_clocks.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::mcap_importer_test {
namespace {

namespace fs = std::filesystem;
using testing::refusal_of;

const fs::path kTool = fs::path(RCSIM_SOURCE_DIR) / "tests" / "tools" / "mcap";

bool tool_installed() {
  return std::system("command -v node > /dev/null 2>&1") == 0 && fs::exists(kTool / "node_modules" / "@mcap" / "core") &&
         fs::exists(kTool / "node_modules" / "@foxglove" / "rosmsg2-serialization");
}

class McapImport : public testing::ScratchDirTest {
 protected:
  McapImport() : ScratchDirTest("mcap_import") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    if (!tool_installed()) GTEST_SKIP() << "the MCAP test tool is not installed (scripts/test-tools.sh: Node.js and npm ci in tests/tools/mcap)";
  }
  // The recording in `dir` as a ROS 2 log (and its mapping file), written by the test tool.
  fs::path log_of(const fs::path& dir, const std::string& compression, const std::string& name,
                  const std::string& detections = "radarscan", const std::string& ego = "odometry",
                  const std::string& boxes = "scene", const std::string& extra = "") {
    const fs::path log = dir_ / (name + ".mcap");
    mapping_ = dir_ / (name + ".mapping.json");
    const auto written = rcsim::testing::run_shell_command("node " + (kTool / "write_ros2_log.js").string() + " " + dir.string() +
                                                           " " + log.string() + " --compression " + compression +
                                                           " --mapping " + mapping_.string() + " --chunk-bytes 16384" +
                                                           " --detections " + detections + " --ego " + ego +
                                                           " --boxes " + boxes + " " + extra);
    EXPECT_EQ(written.exit_code, 0) << written.output;
    return log;
  }
  Recording imported(const fs::path& log) {
    DatasetImportOptions options;
    options.mapping = mapping_;
    write_recording(dir_ / "back", import_mcap(log, options).recording);
    return read_recording(dir_ / "back");
  }
  fs::path mapping_;
};

// Per (sensor, time in µs): the targets as (range, azimuth, range rate, amplitude, elevation).
using Target = std::tuple<double, double, double, double, double>;
std::map<std::pair<int, long long>, std::vector<Target>> cycles_of(const Recording& r) {
  std::map<std::pair<int, long long>, std::vector<Target>> out;
  for (int k = 0; k < r.cycle_count(); ++k) {
    const int only = r.cycle_sensor(k);
    for (int s = 0; s < static_cast<int>(r.sensors.size()); ++s) {
      if (only < 0 || only == s) out[{s, std::llround(r.cycle_t_s(k) * 1e6)}];
    }
  }
  for (const RecordedTarget& t : r.targets) {
    const double el = std::isnan(t.elevation_rad) ? 0.0 : t.elevation_rad;
    out[{t.sensor, std::llround(t.t_s * 1e6)}].emplace_back(t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db, el);
  }
  return out;
}

// The imported recording holds the original's drive: every sensor cycle at its time with its
// targets (to float32 and the files' decimals), the ego rows, the boxes within 1 mm.
void expect_same_drive(const Recording& original, const Recording& back, double speed_tolerance_mps = 1e-4) {
  EXPECT_EQ(back.clock, Clock::per_sensor);
  ASSERT_EQ(back.sensors.size(), original.sensors.size());
  for (std::size_t s = 0; s < back.sensors.size(); ++s) {
    EXPECT_EQ(back.sensors[s].id, original.sensors[s].id);
    EXPECT_EQ(back.sensors[s].type, original.sensors[s].type);
    EXPECT_NEAR(back.sensors[s].x_m, original.sensors[s].x_m, 1e-9);
    EXPECT_NEAR(back.sensors[s].y_m, original.sensors[s].y_m, 1e-9);
    EXPECT_NEAR(back.sensors[s].yaw_rad, original.sensors[s].yaw_rad, 1e-9);
  }
  const auto a = cycles_of(original), b = cycles_of(back);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, targets] : a) {
    const auto it = b.find(key);
    ASSERT_NE(it, b.end()) << "sensor " << key.first << " at " << key.second << " us";
    ASSERT_EQ(it->second.size(), targets.size()) << key.second;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const auto& [r0, az0, rr0, a0, el0] = targets[i];
      const auto& [r1, az1, rr1, a1, el1] = it->second[i];
      EXPECT_NEAR(r1, r0, 1e-4 + 1e-7 * r0);  // float32 slant range, over the cosine
      EXPECT_NEAR(az1, az0, 1e-6);
      EXPECT_NEAR(rr1, rr0, 1e-4);
      EXPECT_NEAR(a1, a0, 1e-3);
      EXPECT_NEAR(el1, el0, 1e-6);
    }
  }
  ASSERT_EQ(back.ego.size(), original.ego.size());
  for (std::size_t i = 0; i < back.ego.size(); ++i) {
    EXPECT_NEAR(back.ego[i].t_s, original.ego[i].t_s, 1e-9);
    EXPECT_NEAR(back.ego[i].x_m, original.ego[i].x_m, 1e-4);
    EXPECT_NEAR(back.ego[i].yaw_rad, original.ego[i].yaw_rad, 1e-6);
    EXPECT_NEAR(back.ego[i].y_m, original.ego[i].y_m, 1e-4);
    EXPECT_NEAR(back.ego[i].speed_mps, original.ego[i].speed_mps, speed_tolerance_mps);
    EXPECT_NEAR(back.ego[i].yaw_rate_radps, original.ego[i].yaw_rate_radps, speed_tolerance_mps);
  }
  ASSERT_EQ(back.objects.size(), original.objects.size());
  for (std::size_t o = 0; o < back.objects.size(); ++o) {
    const auto found = std::find_if(original.objects.begin(), original.objects.end(),
                                    [&](const RecordingObject& x) { return x.id == back.objects[o].id; });
    ASSERT_NE(found, original.objects.end()) << back.objects[o].id;
    const auto& boxes = original.boxes[static_cast<std::size_t>(found - original.objects.begin())];
    EXPECT_EQ(back.objects[o].object_class, found->object_class);
    EXPECT_NEAR(back.objects[o].length_m, found->length_m, 1e-3);
    ASSERT_EQ(back.boxes[o].size(), boxes.size()) << found->id;
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      EXPECT_NEAR(back.boxes[o][k].t_s, boxes[k].t_s, 1e-9);
      EXPECT_NEAR(back.boxes[o][k].x_m, boxes[k].x_m, 1e-3);
      EXPECT_NEAR(back.boxes[o][k].y_m, boxes[k].y_m, 1e-3);
      EXPECT_NEAR(back.boxes[o][k].yaw_rad, boxes[k].yaw_rad, 1e-6);
      EXPECT_NEAR(back.boxes[o][k].speed_mps, boxes[k].speed_mps, 1e-4);
    }
  }
}

TEST_F(McapImport, ASyntheticDriveComesBackFromAZstdLog) {
  const fs::path dir = testing::kBundledRecordings / "two_in_one_cell";
  const Recording original = read_recording(dir);
  const Recording back = imported(log_of(dir, "zstd", "synthetic"));
  expect_same_drive(original, back);
  EXPECT_NEAR(back.sensors[0].cycle_time_s, 0.04, 1e-9);  // the scans' median step
  EXPECT_NEAR(back.cycle_time_s, 0.04, 1e-9);              // the boxes'
}

TEST_F(McapImport, UncompressedAndLz4ChunksReadAlike) {
  const fs::path dir = testing::kBundledRecordings / "front_approach";
  const Recording original = read_recording(dir);
  expect_same_drive(original, imported(log_of(dir, "none", "plain")));
  expect_same_drive(original, imported(log_of(dir, "lz4", "lz4")));
}

// The detections as foxglove.PointCloud (JSON, float32 x y z in each radar's frame) instead of
// RadarScan: the same drive back.
TEST_F(McapImport, PointCloudDetectionsGiveTheSameDrive) {
  const fs::path dir = testing::kBundledRecordings / "two_in_one_cell";
  expect_same_drive(read_recording(dir), imported(log_of(dir, "lz4", "clouds", "pointcloud")));
}

// The ego as a chain of /tf transforms (odom -> base_footprint moving, base_footprint -> base_link
// static) and the radars' mountings from /tf_static, as a robot's bag has them: the same drive.
// Speed and yaw rate come from the poses by central differences: exact for the drive's constant
// deceleration but for the 4 decimals of the positions (1e-4 m / 0.08 s) and the one-sided ends
// (1.25 m/s^2 x 0.02 s).
TEST_F(McapImport, TheEgoFromATfChainAndTheMountingsFromTfStatic) {
  const fs::path dir = testing::kBundledRecordings / "front_approach";
  const Recording original = read_recording(dir);
  const Recording back = imported(log_of(dir, "zstd", "tf", "radarscan", "tf"));
  expect_same_drive(original, back, 0.03);
  for (std::size_t i = 1; i + 1 < back.ego.size(); ++i) EXPECT_NEAR(back.ego[i].speed_mps, original.ego[i].speed_mps, 2e-3) << i;
  // Without /tf_static the mounting cannot be had: the refusal names the frame and the frames there are.
  std::string mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("\"vehicle_frame\": \"base_link\""), 28, "\"vehicle_frame\": \"base_lnk\"");
  DatasetImportOptions options;
  options.mapping = write_file("typo.json", mapping);
  const std::string m = refusal_of([&] { import_mcap(dir_ / "tf.mcap", options); });
  EXPECT_NE(m.find("no transform names frame 'base_lnk' (the frames: base_footprint, base_link, front_left, front_right, odom)"),
            std::string::npos) << m;
}

// The boxes from an ASAM OpenLABEL file beside the log, each cuboid in the vehicle's frame at its
// time: moved into the world by the odometry's pose, or by the /tf chain, the same boxes come back.
TEST_F(McapImport, BoxesFromAnOpenLabelFileInTheVehiclesFrame) {
  const fs::path dir = testing::kBundledRecordings / "overtaking";
  const Recording original = read_recording(dir);
  ASSERT_FALSE(original.objects.empty());
  expect_same_drive(original, imported(log_of(dir, "zstd", "openlabel", "radarscan", "odometry", "openlabel")));
  const Recording tf = imported(log_of(dir, "zstd", "openlabel_tf", "radarscan", "tf", "openlabel"));
  ASSERT_EQ(tf.boxes.size(), original.boxes.size());
  for (std::size_t o = 0; o < tf.boxes.size(); ++o) {
    ASSERT_EQ(tf.boxes[o].size(), original.boxes[o].size());
    for (std::size_t k = 0; k < tf.boxes[o].size(); ++k) {
      EXPECT_NEAR(tf.boxes[o][k].x_m, original.boxes[o][k].x_m, 1e-3);
      EXPECT_NEAR(tf.boxes[o][k].y_m, original.boxes[o][k].y_m, 1e-3);
      EXPECT_NEAR(tf.boxes[o][k].yaw_rad, original.boxes[o][k].yaw_rad, 1e-6);
    }
  }
  // A cuboid in a frame the odometry does not know is refused naming the file, the object and the frame.
  std::string labels = testing::file_bytes(dir_ / "openlabel.mcap.openlabel.json");
  for (std::size_t at = labels.find("\"base_link\""); at != std::string::npos; at = labels.find("\"base_link\"", at)) {
    labels.replace(at, 11, "\"radar_fl\"");
  }
  write_file("openlabel.mcap.openlabel.json", labels);
  DatasetImportOptions options;
  options.mapping = dir_ / "openlabel.mapping.json";
  const std::string m = refusal_of([&] { import_mcap(dir_ / "openlabel.mcap", options); });
  EXPECT_NE(m.find("openlabel.mcap.openlabel.json"), std::string::npos) << m;
  EXPECT_NE(m.find("is in frame 'radar_fl': neither the odometry's world frame 'odom' nor its vehicle frame "
                   "'base_link'"), std::string::npos) << m;
}

// Streamed straight to disk (as `rcsim import` does, in bounded memory) the files are those of the
// import in memory, byte for byte; scans logged up to 0.5 s late (their log time, not their stamp)
// are put back in order, and scans 3 s late, beyond the 2 s window, are refused by name.
TEST_F(McapImport, StreamedToDiskTheSameFilesAndLateScansPutInOrder) {
  const fs::path dir = testing::kBundledRecordings / "two_in_one_cell";
  DatasetImportOptions options;
  const fs::path log = log_of(dir, "zstd", "on_time");
  options.mapping = mapping_;
  write_recording(dir_ / "in_memory", import_mcap(log, options).recording);
  const ImportSummary summary = import_mcap_to(log, options, dir_ / "streamed");
  for (const char* file : {"recording.json", "ego.csv", "objects.csv", "targets.csv", "cycles.csv"}) {
    EXPECT_EQ(testing::file_bytes(dir_ / "streamed" / file), testing::file_bytes(dir_ / "in_memory" / file)) << file;
  }
  const Recording original = read_recording(dir);
  EXPECT_EQ(summary.targets, original.targets.size());
  EXPECT_EQ(summary.cycles, 2 * original.ego.size());  // two radars, a scan each per ego row
  const fs::path late = log_of(dir, "zstd", "late", "radarscan", "odometry", "scene", "--scan-delay-ms 500");
  options.mapping = mapping_;
  import_mcap_to(late, options, dir_ / "late");
  for (const char* file : {"ego.csv", "objects.csv", "targets.csv", "cycles.csv"}) {
    EXPECT_EQ(testing::file_bytes(dir_ / "late" / file), testing::file_bytes(dir_ / "in_memory" / file)) << file;
  }
  const fs::path later = log_of(dir, "zstd", "later", "radarscan", "odometry", "scene", "--scan-delay-ms 3000");
  options.mapping = mapping_;
  const std::string m = refusal_of([&] { import_mcap_to(later, options, dir_ / "later"); });
  EXPECT_NE(m.find("the import puts the radars' scans in order within 2 s"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(dir_ / "later"));  // nothing half-written
}

// The aiMotive drive as a ROS 2 log gives the recording `import --from aimotive` gives, and the
// radars on their own (estimated) clocks keep them.
TEST_F(McapImport, TheAimotiveDriveAsARos2LogGivesTheSameRecording) {
  if (!fs::exists(testing::kAimotiveRaw)) {
    std::cout << "skipped: no real data at " << testing::kAimotiveRaw << '\n';
    GTEST_SKIP();
  }
  const Recording keyframed = find_dataset_importer("aimotive").import(testing::kAimotiveRaw, {}).recording;
  write_recording(dir_ / "aimotive", keyframed);
  expect_same_drive(read_recording(dir_ / "aimotive"), imported(log_of(dir_ / "aimotive", "lz4", "aimotive")));
  const Recording own = profile::on_estimated_clocks(keyframed, profile::estimate_sensor_clocks(keyframed));
  write_recording(dir_ / "aimotive_own", own);
  const Recording back = imported(log_of(dir_ / "aimotive_own", "zstd", "aimotive_own"));
  expect_same_drive(read_recording(dir_ / "aimotive_own"), back);
  EXPECT_NEAR(back.sensors[0].cycle_time_s, own.sensors[0].cycle_time_s, 0.06);  // one or two periods a step
}

TEST_F(McapImport, WhatIsNotThereOrNotAsMappedIsRefusedByName) {
  const fs::path dir = testing::kBundledRecordings / "standstill_1m";
  const fs::path log = log_of(dir, "zstd", "log");
  DatasetImportOptions options;
  // No mapping.
  EXPECT_NE(refusal_of([&] { import_mcap(log, options); }).find("--mapping"), std::string::npos);
  // A topic the log does not have, the others listed.
  std::string mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("/radar/front_left/scan"), 22, "/radar/front_lft/scan");
  const fs::path wrong = write_file("wrong.json", mapping);
  options.mapping = wrong;
  std::string m = refusal_of([&] { import_mcap(log, options); });
  EXPECT_NE(m.find("/radar/front_lft/scan"), std::string::npos) << m;
  EXPECT_NE(m.find("the log's topics: "), std::string::npos) << m;
  // The ego topic mapped as a radar's: its schema named.
  mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("/radar/front_left/scan"), 22, "/odom");
  mapping.replace(mapping.find("\"topic\": \"/odom\"", mapping.find("\"ego\"")), 16, "\"topic\": \"/annotations\"");
  options.mapping = write_file("swapped.json", mapping);
  m = refusal_of([&] { import_mcap(log, options); });
  EXPECT_NE(m.find("schema 'nav_msgs/msg/Odometry' in 'cdr': the mapping takes radar_msgs/msg/RadarScan"), std::string::npos) << m;
  // A boxes topic the log does not have: refused, not an import without objects.
  mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("/annotations"), 12, "/annotation");
  options.mapping = write_file("no_boxes.json", mapping);
  m = refusal_of([&] { import_mcap(log, options); });
  EXPECT_NE(m.find("/annotation: no messages on the objects topic"), std::string::npos) << m;
  // A mapping of another format.
  options.mapping = write_file("bad.json", R"({"format": "rcsim-recording", "version": 1})");
  EXPECT_NE(refusal_of([&] { import_mcap(log, options); }).find("bad.json"), std::string::npos);
}

TEST_F(McapImport, DamagedLogsAreRefusedNamingTheRecordAndOffset) {
  const fs::path dir = testing::kBundledRecordings / "standstill_1m";
  const fs::path log = log_of(dir, "none", "log");
  DatasetImportOptions options;
  options.mapping = mapping_;
  const std::string bytes = testing::file_bytes(log);
  // Cut in the middle, as a recorder that crashed leaves it: no footer, read up to its last whole
  // record (a chunk), said in a warning; the cycles are a prefix of the whole log's.
  const fs::path cut = write_file("cut.mcap", bytes.substr(0, bytes.size() / 2));
  const DatasetRecording whole = import_mcap(log, options), prefix = import_mcap(cut, options);
  ASSERT_EQ(prefix.warnings.size(), 1u);
  EXPECT_NE(prefix.warnings[0].find("cut.mcap: no footer (the recorder stopped before closing the log): read up to its last whole record"),
            std::string::npos) << prefix.warnings[0];
  EXPECT_GT(prefix.recording.cycles.size(), 0u);
  EXPECT_LT(prefix.recording.cycles.size(), whole.recording.cycles.size());
  for (std::size_t k = 0; k < prefix.recording.cycles.size(); ++k) EXPECT_EQ(prefix.recording.cycles[k].t_s, whole.recording.cycles[k].t_s);
  std::string m;
  // A byte flipped inside the first chunk's records: its CRC no longer holds.
  std::string flipped = bytes;
  const std::size_t chunk = flipped.find('\x06', 8 + 9);  // the first chunk's opcode after the header
  ASSERT_NE(chunk, std::string::npos);
  flipped[chunk + 200] = static_cast<char>(flipped[chunk + 200] ^ 0x5a);
  m = refusal_of([&] { import_mcap(write_file("flipped.mcap", flipped), options); });
  EXPECT_NE(m.find("flipped.mcap"), std::string::npos) << m;
  EXPECT_NE(m.find("Chunk at byte "), std::string::npos) << m;
  EXPECT_NE(m.find("CRC-32"), std::string::npos) << m;
}

// Issue 50: a radar driver's sensor_msgs/msg/PointCloud2 (fields x y z radial_speed rcs, named in
// the mapping) gives the same drive; so does the awkward layout: big-endian, float64 coordinates,
// a field not asked for between, two rows with padding, NaN points of a cloud that is not dense
// (left out, counted), and the points in the vehicle's frame, moved through /tf into the radar's.
TEST_F(McapImport, PointCloud2DetectionsInAnyLayoutAndFrameGiveTheSameDrive) {
  const fs::path dir = testing::kBundledRecordings / "two_in_one_cell";
  const Recording original = read_recording(dir);
  expect_same_drive(original, imported(log_of(dir, "zstd", "cloud2", "pointcloud2")));
  const fs::path mixed = log_of(dir, "none", "cloud2_mixed", "pointcloud2", "tf", "scene", "--cloud-layout mixed --scan-frame vehicle");
  DatasetImportOptions options;
  options.mapping = mapping_;
  const DatasetRecording back = import_mcap(mixed, options);
  write_recording(dir_ / "mixed", back.recording);
  expect_same_drive(original, read_recording(dir_ / "mixed"), 0.03);
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_NE(back.warnings[0].find("invalid points (not finite) of clouds that are not dense left out"), std::string::npos) << back.warnings[0];
  // A field the mapping names that the cloud lacks: the cloud's fields listed.
  std::string mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("\"radial_speed\""), 14, "\"velocity\"");
  options.mapping = write_file("velocity.json", mapping);
  const std::string m = refusal_of([&] { import_mcap(mixed, options); });
  EXPECT_NE(m.find("no field 'velocity' (the cloud's fields: x, y, z, flags, radial_speed, rcs); name the radial speed's and the "
                   "amplitude's in the mapping's sensors[0].fields"), std::string::npos) << m;
}

// Issue 50: a ROS 2 bag as Humble records it (SQLite storage, metadata.yaml), split in two files
// with /tf_static only in the first, and the same bag in MCAP storage: the same drive, through
// --from mcap and --from rosbag2 alike.
TEST_F(McapImport, Rosbag2BagsSplitInTwoGiveTheSameDrive) {
  const fs::path dir = testing::kBundledRecordings / "overtaking";
  const Recording original = read_recording(dir);
  for (const std::string storage : {"sqlite3", "mcap"}) {
    const fs::path bag = dir_ / ("bag_" + storage);
    mapping_ = dir_ / ("bag_" + storage + ".mapping.json");
    const auto written = testing::run_shell_command("node " + (kTool / "write_ros2_log.js").string() + " " + dir.string() + " " +
                                                    bag.string() + " --mapping " + mapping_.string() +
                                                    " --ego tf --boxes openlabel --storage " + storage + " --split 2");
    ASSERT_EQ(written.exit_code, 0) << written.output;
    ASSERT_TRUE(fs::exists(bag / ("bag_" + storage + "_1." + (storage == "sqlite3" ? "db3" : "mcap"))));
    const Recording back = imported(bag);
    expect_same_drive(original, back, 0.03);
    EXPECT_EQ(back.name, original.name);
    const auto via_rosbag2 = testing::run_rcsim("import --from rosbag2 " + bag.string() + " --mapping " + mapping_.string() + " -o " +
                                                (dir_ / ("cli_" + storage)).string());
    EXPECT_EQ(via_rosbag2.exit_code, 0) << via_rosbag2.output;
    EXPECT_EQ(testing::file_bytes(dir_ / ("cli_" + storage) / "targets.csv"), testing::file_bytes(dir_ / "back" / "targets.csv"));
  }
  // A damaged bag: a storage file that is not SQLite, a metadata.yaml that leads out of the bag.
  const fs::path bag = dir_ / "bag_sqlite3";
  DatasetImportOptions options;
  options.mapping = dir_ / "bag_sqlite3.mapping.json";
  write_file("bag_sqlite3/bag_sqlite3_1.db3", "not a database");
  std::string m = refusal_of([&] { import_mcap(bag, options); });
  EXPECT_NE(m.find("bag_sqlite3_1.db3: table topics: not a rosbag2 SQLite storage file"), std::string::npos) << m;
  std::string yaml = testing::file_bytes(bag / "metadata.yaml");
  yaml.replace(yaml.find("- bag_sqlite3_1.db3"), 19, "- ../../etc/passwd");
  write_file("bag_sqlite3/metadata.yaml", yaml);
  m = refusal_of([&] { import_mcap(bag, options); });
  EXPECT_NE(m.find("metadata.yaml: rosbag2_bagfile_information.relative_file_paths[1]: '../../etc/passwd' leads out of the bag"),
            std::string::npos) << m;
}

// Issue 50, item 4: foxglove.SceneUpdate entities in the vehicle's frame ("base_link") are moved
// into the world, by the odometry or by /tf; a frame neither knows is refused by name.
TEST_F(McapImport, SceneEntitiesInTheVehiclesFrameAreMovedIntoTheWorld) {
  const fs::path dir = testing::kBundledRecordings / "overtaking";
  const Recording original = read_recording(dir);
  expect_same_drive(original, imported(log_of(dir, "zstd", "boxes_v", "radarscan", "odometry", "scene", "--box-frame vehicle")));
  expect_same_drive(original, imported(log_of(dir, "zstd", "boxes_tf", "radarscan", "tf", "scene", "--box-frame vehicle")), 0.03);
  std::string mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("\"base_link\""), 11, "\"base_lnk\"");
  DatasetImportOptions options;
  options.mapping = write_file("typo_frame.json", mapping);
  const std::string m = refusal_of([&] { import_mcap(dir_ / "boxes_tf.mcap", options); });
  EXPECT_NE(m.find("base_lnk"), std::string::npos) << m;
}

// Issue 50, items 3 and 6: a radar with one scan, given its cycle time as the refusal says,
// imports (it crashed); a mistyped topic lists the log's topics; the header's profile and library
// reach recording.json; a driver that leaves header.stamp at 0 is refused until the mapping takes
// the log's times.
TEST_F(McapImport, OneScanRadarsTopicListsAndUnstampedScans) {
  const fs::path dir = testing::kBundledRecordings / "standstill_1m";
  const fs::path log = log_of(dir, "zstd", "log");
  DatasetImportOptions options;
  std::string mapping = testing::file_bytes(mapping_);
  mapping.replace(mapping.find("/radar/front_left/scan"), 22, "/radar/front_lft/scan");
  options.mapping = write_file("wrong.json", mapping);
  const std::string m = refusal_of([&] { import_mcap(log, options); });
  EXPECT_NE(m.find("the log's topics: /annotations, /odom, /radar/front_left/scan, /radar/front_right/scan)"),
            std::string::npos) << m;
  options.mapping = mapping_;
  const DatasetRecording back = import_mcap(log, options);
  EXPECT_EQ(back.recording.source.value("profile", ""), "ros2");
  EXPECT_EQ(back.recording.source.value("library", ""), "rcsim tests/tools/mcap/write_ros2_log.js");
}

// Issue 50, item 7: an attachment the import skips is never read into memory (a 300 MiB one made
// a 20-s log's import peak at 932 MB).
TEST_F(McapImport, AnAttachmentIsSkippedUnread) {
  const fs::path dir = testing::kBundledRecordings / "standstill_1m";
  const fs::path log = log_of(dir, "zstd", "attached", "radarscan", "odometry", "scene", "--attachment-mib 96");
  ASSERT_GT(fs::file_size(log), 96u << 20);
  DatasetImportOptions options;
  options.mapping = mapping_;
  const auto added = testing::peak_memory_added_by([&] { import_mcap_to(log, options, dir_ / "out"); });
  if (added) {
    EXPECT_LT(*added, 32 << 20) << "peak memory added by the import";
  }
  EXPECT_EQ(read_recording(dir_ / "out").targets.size(), read_recording(dir).targets.size());
}

// Logs that break the rules in one message each, written with rcsim's MCAP writer and the fuzz
// seeds' hand-laid CDR: each refused naming what is wrong, no recording written.
TEST(McapImportRules, OneBadMessageIsRefusedByName) {
  const fs::path dir = rcsim::fuzz::fresh_dir("mcap_rules");
  rcsim::fuzz::write_file(dir / "mapping.json", rcsim::fuzz::kMcapMapping);
  DatasetImportOptions options;
  options.mapping = dir / "mapping.json";
  // 10 scans at 20 Hz, the ego and a box at 10 Hz; `bad` rewrites scan k's bytes.
  const auto log = [&](const std::string& name, const std::function<std::string(int, std::string)>& bad) {
    std::ostringstream out;
    mcap::Writer writer(out, "ros2");
    const auto scan = writer.add_channel("/radar/front/scan", "cdr", writer.add_schema("radar_msgs/msg/RadarScan", "ros2msg", ""));
    const auto odom = writer.add_channel("/odom", "cdr", writer.add_schema("nav_msgs/msg/Odometry", "ros2msg", ""));
    const auto scene = writer.add_channel("/annotations", "json", writer.add_schema("foxglove.SceneUpdate", "jsonschema", "{}"));
    const std::int64_t t0_ns = 1'700'000'000'000'000'000;
    for (int k = 0; k < 10; ++k) {
      const std::int64_t t_ns = t0_ns + k * 50'000'000;
      if (k % 2 == 0) {
        writer.write_message(odom, static_cast<std::uint64_t>(t_ns), rcsim::fuzz::mcap_seed::odometry(t_ns, 0.05 * k));
        writer.write_message(scene, static_cast<std::uint64_t>(t_ns), rcsim::fuzz::mcap_seed::scene_update(t_ns));
      }
      // An empty rewrite: no scan k.
      if (const std::string b = bad(k, rcsim::fuzz::mcap_seed::radar_scan(t_ns, 0.05 * k)); !b.empty()) {
        writer.write_message(scan, static_cast<std::uint64_t>(t_ns), b);
      }
    }
    writer.finish();
    rcsim::fuzz::write_file(dir / name, out.str());
    return dir / name;
  };
  const auto refusal = [&](const fs::path& path) { return refusal_of([&] { import_mcap_to(path, options, dir / "out"); }); };
  EXPECT_NO_THROW(import_mcap_to(log("good.mcap", [](int, std::string b) { return b; }), options, dir / "out"));
  const std::string good = testing::file_bytes(dir / "out" / "targets.csv");
  // Scan 4 stamped as scan 3: two scans of the radar at one time.
  const std::string twice = refusal(log("twice.mcap", [](int k, std::string b) {
    return k == 4 ? rcsim::fuzz::mcap_seed::radar_scan(1'700'000'000'000'000'000 + 3 * 50'000'000, 0.0) : b;
  }));
  EXPECT_NE(twice.find("two scans stamped 0.150000000 s after the log's start"), std::string::npos) << twice;
  // A radial speed that is NaN: the first return's doppler_velocity, at byte 40 (the encapsulation
  // 4, the stamp 8, the frame "front" 4 + 6 + 2 of padding, the returns' count 4, then 12 into it).
  const std::string nan = refusal(log("nan.mcap", [](int k, std::string b) {
    if (k == 2) {
      const float v = std::nanf("");
      std::memcpy(b.data() + 4 + 8 + 4 + 6 + 2 + 4 + 12, &v, sizeof v);
    }
    return b;
  }));
  EXPECT_NE(nan.find("beyond the limits of schemas/limits.md"), std::string::npos) << nan;
  EXPECT_NE(nan.find("doppler_velocity nan"), std::string::npos) << nan;
  EXPECT_EQ(testing::file_bytes(dir / "out" / "targets.csv"), good) << "the earlier recording stays as it was";
  // Issue 50, item 9: a real log's edges, a radar that starts 1 s before the odometry and a scan
  // stamped twice: refused, saying --skip-edges; with it, left out and counted.
  const fs::path edges = log("edges.mcap", [](int k, std::string b) {
    const std::int64_t t0 = 1'700'000'000'000'000'000;
    if (k == 0) return rcsim::fuzz::mcap_seed::radar_scan(t0 - 1'000'000'000, 0.0);
    if (k == 4) return rcsim::fuzz::mcap_seed::radar_scan(t0 + 3 * 50'000'000, 0.0);
    return b;
  });
  const std::string edge = refusal(edges);
  EXPECT_NE(edge.find("two scans stamped 1.150000000 s after the log's start (--skip-edges leaves the second out)"), std::string::npos) << edge;
  DatasetImportOptions skipping = options;
  skipping.skip_edges = true;
  const DatasetRecording trimmed = import_mcap(edges, skipping);
  EXPECT_EQ(trimmed.recording.cycles.size(), 8u);
  ASSERT_EQ(trimmed.warnings.size(), 1u);
  EXPECT_EQ(trimmed.warnings[0], "--skip-edges left out 1 scan(s) beyond the ego log, 1 scan(s) and 0 ego pose(s) stamped as the one before");
  // Issue 51 (MEDIUM, LOW): a scan stamped near 1970 among 2023's, an odometry with a zero
  // quaternion, a sensor id with DEL: each refused at import, exit 2, not later by replay or the
  // writer.
  const std::string epoch = refusal(log("epoch.mcap", [](int k, std::string b) {
    return k == 5 ? rcsim::fuzz::mcap_seed::radar_scan(1'000'000'000, 0.0) : b;
  }));
  EXPECT_NE(epoch.find("s a recording's times hold (schemas/limits.md; a stamp near 1970 or 2038?)"), std::string::npos) << epoch;
  std::string del_mapping = rcsim::fuzz::kMcapMapping;
  del_mapping.replace(del_mapping.find("\"id\": \"front\""), 13, "\"id\": \"fr\u007fnt\"");
  rcsim::fuzz::write_file(dir / "del.json", del_mapping);
  DatasetImportOptions del;
  del.mapping = dir / "del.json";
  const std::string del_refusal = refusal_of([&] { import_mcap(dir / "good.mcap", del); });
  EXPECT_NE(del_refusal.find("sensors[0].id: holds"), std::string::npos) << del_refusal;
  EXPECT_EQ(del_refusal.find('\x7f'), std::string::npos) << "not echoed";
  // Issue 50, item 3: scans that a driver leaves at stamp 0 are refused, saying how to take the
  // log's times; so taken, they import at the log's times.
  const auto unstamped = [](int k, std::string b) { return k >= 0 ? rcsim::fuzz::mcap_seed::radar_scan(0, 0.05 * k) : b; };
  const std::string zero = refusal(log("unstamped.mcap", unstamped));
  EXPECT_NE(zero.find("header.stamp is 0: the driver does not stamp its scans; map sensors[0].stamp: \"log\""), std::string::npos) << zero;
  std::string mapping = rcsim::fuzz::kMcapMapping;
  mapping.replace(mapping.find("\"yaw_rad\": 0.0}"), 15, "\"yaw_rad\": 0.0, \"stamp\": \"log\"}");
  rcsim::fuzz::write_file(dir / "log_times.json", mapping);
  DatasetImportOptions log_times;
  log_times.mapping = dir / "log_times.json";
  EXPECT_EQ(import_mcap(dir / "unstamped.mcap", log_times).recording.cycles.size(), 10u);
  // A radar with one scan (the rest another radar's topic): refused without a cycle time; with the
  // mapping's cycle_time_s, as the refusal says, imported (it crashed).
  const fs::path one = log("one_scan.mcap", [](int k, std::string b) { return k == 0 ? b : std::string(); });
  const std::string no_step = refusal(one);
  EXPECT_NE(no_step.find("sensor 'front' has one scan: no step shows its cycle time (give the mapping's sensors[0].cycle_time_s)"),
            std::string::npos) << no_step;
  mapping = rcsim::fuzz::kMcapMapping;
  mapping.replace(mapping.find("\"yaw_rad\": 0.0}"), 15, "\"yaw_rad\": 0.0, \"cycle_time_s\": 0.05}");
  rcsim::fuzz::write_file(dir / "cycle.json", mapping);
  DatasetImportOptions cycle;
  cycle.mapping = dir / "cycle.json";
  const Recording single = import_mcap(one, cycle).recording;
  EXPECT_EQ(single.cycles.size(), 1u);
  EXPECT_EQ(single.sensors[0].cycle_time_s, 0.05);
}

// Issue 51, HIGH 4: 111 KB of zstd chunks holding scans of 6.7 M zero returns wrote a 1.4 GB
// recording. A scan holds at most limits::kMaxReturnsPerScan returns, and a log's scans at most
// one return per byte of the log (at least one scan's worth): each scan's count is checked, before
// its returns are allocated or a row written, naming the file, the topic and the message.
TEST(McapImportRules, ScansOfZeroReturnsBeyondTheBoundsAreRefusedAtTheirCount) {
  const fs::path dir = rcsim::fuzz::fresh_dir("mcap_returns_bound");
  rcsim::fuzz::write_file(dir / "mapping.json", rcsim::fuzz::kMcapMapping);
  DatasetImportOptions options;
  options.mapping = dir / "mapping.json";
  // 10 scans at 20 Hz of `returns(k)` returns of zeros each, the ego and a box at 10 Hz, zstd.
  const auto log = [&](const std::string& name, const std::function<std::uint32_t(int)>& returns) {
    std::ostringstream out;
    mcap::Writer writer(out, "ros2", mcap::Compression::zstd);
    const auto scan = writer.add_channel("/radar/front/scan", "cdr", writer.add_schema("radar_msgs/msg/RadarScan", "ros2msg", ""));
    const auto odom = writer.add_channel("/odom", "cdr", writer.add_schema("nav_msgs/msg/Odometry", "ros2msg", ""));
    const auto scene = writer.add_channel("/annotations", "json", writer.add_schema("foxglove.SceneUpdate", "jsonschema", "{}"));
    const std::int64_t t0_ns = 1'700'000'000'000'000'000;
    for (int k = 0; k < 10; ++k) {
      const std::int64_t t_ns = t0_ns + k * 50'000'000;
      if (k % 2 == 0) {
        writer.write_message(odom, static_cast<std::uint64_t>(t_ns), rcsim::fuzz::mcap_seed::odometry(t_ns, 0.05 * k));
        writer.write_message(scene, static_cast<std::uint64_t>(t_ns), rcsim::fuzz::mcap_seed::scene_update(t_ns));
      }
      std::string zeros = rcsim::fuzz::mcap_seed::header(t_ns, "front");
      rcsim::fuzz::mcap_seed::put(zeros, returns(k));
      zeros.append(std::size_t{20} * returns(k), '\0');
      writer.write_message(scan, static_cast<std::uint64_t>(t_ns), zeros);
    }
    writer.finish();
    rcsim::fuzz::write_file(dir / name, out.str());
    return dir / name;
  };
  const auto refusal = [&](const fs::path& path) { return refusal_of([&] { import_mcap_to(path, options, dir / "out"); }); };
  // One scan of kMaxReturnsPerScan + 1 zeros (5 MiB of CDR, a few kB of zstd).
  const fs::path one = log("one.mcap", [](int k) { return k == 3 ? limits::kMaxReturnsPerScan + 1 : 1u; });
  EXPECT_LT(fs::file_size(one), 64u * 1024u);
  const std::string too_many = refusal(one);
  EXPECT_NE(too_many.find("one.mcap: topic '/radar/front/scan', the message at log time 1700000000150000000 ns: returns: 262145 in one scan "
                          "exceed the limit of 262144 (schemas/limits.md)"),
            std::string::npos)
      << too_many;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing written";
  // Scans of 100,000 zeros each: the third passes the log's bound (262,144 returns: the log is far
  // smaller than that many bytes).
  const fs::path bomb = log("bomb.mcap", [](int) { return 100'000u; });
  const std::string bombed = refusal(bomb);
  EXPECT_NE(bombed.find("bomb.mcap: topic '/radar/front/scan', the message at log time 1700000000100000000 ns: returns: 100000 exceed the "
                        "62144 the log has left: its scans held 200000 returns before this one, and a log holds at most 262144 (one per "
                        "byte of its " + std::to_string(fs::file_size(bomb)) + " bytes"),
            std::string::npos)
      << bombed;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing written";
  // Within both: imported.
  EXPECT_NO_THROW(import_mcap_to(log("fine.mcap", [](int) { return 20'000u; }), options, dir / "out"));
}

}  // namespace
}  // namespace rcsim::replay::mcap_importer_test
