// The View-of-Delft importer (replay/import/vod_importer.hpp) on fixture files written here from
// the dataset's published layout (its devkit's readers: radar points float32 x 7, KITTI labels
// and calibrations, pose files of JSON lines); the real frames are held out and never committed.
// A box moved through both calibrations by hand, the ego's velocity and yaw rate, a box's speed
// from its points, --frames, and refusals of damaged files naming file and place.
#include "replay/import/vod_importer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace vod_importer_test {

namespace fs = std::filesystem;
using testing::run_rcsim;

constexpr double kPi = std::numbers::pi;

// The LiDAR's and the radar's axes (x forward, y left, z up) in the camera's (x right, y down,
// z forward), as in KITTI; the translations are the fixture's own.
Eigen::Matrix4d camera_from(const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  T.topRightCorner<3, 1>() = t;
  return T;
}
const Eigen::Matrix4d kT_camera_lidar = camera_from({0.1, -1.0, -0.3});
const Eigen::Matrix4d kT_camera_radar = camera_from({0.0, 0.5, -2.0});

std::string kitti_calib(const Eigen::Matrix4d& T) {
  std::string text;
  for (const char* p : {"P0", "P1", "P2", "P3"}) text += fmt::format("{}: 1000 0 960 0 0 1000 600 0 0 0 1 0\n", p);
  text += "R0_rect: 1 0 0 0 1 0 0 0 1\nTr_velo_to_cam:";
  for (int k = 0; k < 12; ++k) text += fmt::format(" {:.17g}", T(k / 4, k % 4));
  return text + "\nTr_imu_to_velo: 1 0 0 0 0 1 0 0 0 0 1 0\n";
}

struct Point {
  double x, y, z, rcs, v_r, v_comp, time;
};

std::string radar_bytes(const std::vector<Point>& points) {
  std::string bytes;
  for (const Point& p : points) {
    for (const double v : {p.x, p.y, p.z, p.rcs, p.v_r, p.v_comp, p.time}) {
      const float f = static_cast<float>(v);
      char b[4];
      std::memcpy(b, &f, 4);  // the machine is little-endian, as the dataset's files
      bytes.append(b, 4);
    }
  }
  return bytes;
}

// The radar's velocity over the ground in the fixture's frames: 8 m/s forward, 0.3 m/s to the left.
const Eigen::Vector3d kV_S_S(8.0, 0.3, 0.0);
constexpr double kCarSpeed_mps = 5.0;

// A stationary point at p: v_r_compensated 0, v_r = -v_S . u.
Point stationary(double x, double y, double z, double rcs = 0.0) {
  const Eigen::Vector3d u = Eigen::Vector3d(x, y, z).normalized();
  return {x, y, z, rcs, -kV_S_S.dot(u), 0.0, 0.0};
}

// A point of the car ahead (centre (20, 1) in the radar frame, heading along x) moving at kCarSpeed_mps.
Point on_car(double x, double y, double z) {
  const Eigen::Vector3d u = Eigen::Vector3d(x, y, z).normalized();
  const double v_comp = kCarSpeed_mps * u.x();
  return {x, y, z, 10.0, v_comp - kV_S_S.dot(u), v_comp, 0.0};
}

// The camera position of a radar-frame point p (labels are in the camera frame).
Eigen::Vector3d in_camera(const Eigen::Vector3d& p_R) { return (kT_camera_radar * p_R.homogeneous()).head<3>(); }

// A pose file for the radar at (x, y) heading yaw in the odometry frame.
std::string pose_json(double x_m, double y_m, double yaw_rad) {
  Eigen::Matrix4d T_odom_radar = Eigen::Matrix4d::Identity();
  T_odom_radar.topLeftCorner<2, 2>() << std::cos(yaw_rad), -std::sin(yaw_rad), std::sin(yaw_rad), std::cos(yaw_rad);
  T_odom_radar(0, 3) = x_m;
  T_odom_radar(1, 3) = y_m;
  const Eigen::Matrix4d T_odom_camera = T_odom_radar * kT_camera_radar.inverse();
  std::string numbers;
  for (int k = 0; k < 16; ++k) numbers += fmt::format("{}{:.17g}", k ? ", " : "", T_odom_camera(k / 4, k % 4));
  return fmt::format("{{\"odomToCamera\": [{0}]}}\n{{\"mapToCamera\": [{0}]}}\n{{\"UTMToCamera\": [{0}]}}\n", numbers);
}

class VodImporter : public testing::ScratchDirTest {
 protected:
  VodImporter() : ScratchDirTest("vod") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    root_ = dir_ / "view_of_delft";
    for (const char* sub : {"radar/training/velodyne", "radar/training/calib", "lidar/training/calib", "lidar/training/label_2",
                            "lidar/training/pose"}) {
      fs::create_directories(root_ / sub);
    }
    // Frames 10 and 11 follow each other on an arc of curvature 0.01 rad/m (1 m apart); frame 20 stands alone.
    write_frame(10, pose_json(0.0, 0.0, 0.0));
    write_frame(11, pose_json(std::sin(0.01) / 0.01, (1.0 - std::cos(0.01)) / 0.01, 0.01));
    write_frame(20, pose_json(50.0, 3.0, 0.4));
  }

  void write_frame(int number, const std::string& pose) {
    const std::string name = fmt::format("{:05}", number);
    std::vector<Point> points;
    for (int i = 0; i < 12; ++i) {
      const double az = -1.0 + 2.0 * i / 11.0, r = 5.0 + 3.0 * i;
      points.push_back(stationary(r * std::cos(az), r * std::sin(az), -1.0 + 0.25 * i));
    }
    points.push_back(on_car(18.0, 1.2, 0.0));
    points.push_back(on_car(18.2, 0.4, 0.3));
    points.push_back(on_car(19.0, 1.8, -0.2));
    points.push_back({30.0, 0.0, 0.0, 3.0, -8.0, 0.0, -1.0});  // an earlier scan's: left out
    put("radar/training/velodyne/" + name + ".bin", radar_bytes(points));
    put("radar/training/calib/" + name + ".txt", kitti_calib(kT_camera_radar));
    put("lidar/training/calib/" + name + ".txt", kitti_calib(kT_camera_lidar));
    put("lidar/training/pose/" + name + ".json", pose);
    // The car: bottom centre 0.75 m below its centre (20, 1, 0), heading along the radar's x:
    // rotation -pi/2 (yaw = -(rotation + pi/2) = 0 in the LiDAR, whose axes are the radar's).
    const Eigen::Vector3d car_C = in_camera({20.0, 1.0, -0.75});
    put("lidar/training/label_2/" + name + ".txt",
        fmt::format("Car 0 1 0 100 200 300 400 1.5 1.8 4.0 {:.9f} {:.9f} {:.9f} {:.9f} 1\n"
                    "Pedestrian 0 0 0 10 20 30 40 1.7 0.6 0.5 1.0 1.5 8.0 0.0 1\n"
                    // A cyclist boxed three times (VoD boxes its rider and its bicycle again, 0.1 m
                    // from its centre), and a bicycle alone 7.2 m from it.
                    "Cyclist 0 0 0 10 20 30 40 1.8 0.6 1.8 -2.0 1.5 12.0 0.0 1\n"
                    "rider 0 0 0 10 20 30 40 1.7 0.6 0.6 -2.0 1.5 12.1 0.0 1\n"
                    "bicycle 0 0 0 10 20 30 40 1.1 0.6 1.8 -2.0 1.5 11.9 0.0 1\n"
                    "bicycle 0 0 0 10 20 30 40 1.1 0.6 1.8 4.0 1.5 6.0 0.0 1\n"
                    "DontCare -1 -1 -10 1 2 3 4 -1 -1 -1 -1000 -1000 -1000 -10 1\n",
                    car_C.x(), car_C.y(), car_C.z(), -kPi / 2));
  }

  void put(const std::string& relative, const std::string& bytes) const {
    std::ofstream(root_ / relative, std::ios::binary | std::ios::trunc) << bytes;
  }

  fs::path root_;
};

TEST(VodBox, MovedThroughBothCalibrationsByHand) {
  // Camera (2, 1.2, 10): minus the LiDAR's translation (1.9, 2.2, 10.3), turned into the LiDAR's
  // axes (z, -x, -y) = (10.3, -1.9, -2.2): the bottom centre; the centre 0.75 m up: z = -1.45.
  // Into the radar: + R^T (t_lidar - t_radar) = R^T (0.1, -1.5, 1.7) = (1.7, -0.1, 1.5), so
  // (12.0, -2.0, 0.05). Rotation 0: yaw -(0 + pi/2) = -pi/2 in the LiDAR and (same axes) the radar.
  vod::Label label;
  label.height_m = 1.5;
  label.width_m = 1.8;
  label.length_m = 4.0;
  label.p_bottom_C = {2.0, 1.2, 10.0};
  label.rotation_rad = 0.0;
  const vod::RadarBox box = vod::box_in_radar_frame(label, kT_camera_radar, kT_camera_lidar);
  EXPECT_NEAR(box.p_RO_R.x(), 12.0, 1e-12);
  EXPECT_NEAR(box.p_RO_R.y(), -2.0, 1e-12);
  EXPECT_NEAR(box.p_RO_R.z(), 0.05, 1e-12);
  EXPECT_NEAR(box.yaw_rad, -kPi / 2, 1e-12);
  // A radar turned 90 deg to the left of the LiDAR: the box (12, -2) seen from it lies at
  // Rz(-90 deg) (12, -2) = (-2, -12), and a box heading along the LiDAR's x heads to its right.
  Eigen::Matrix4d T_camera_turned = kT_camera_radar;
  T_camera_turned.topLeftCorner<3, 3>() =
      kT_camera_radar.topLeftCorner<3, 3>() * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  label.rotation_rad = -kPi / 2;  // yaw -(rotation + pi/2) = 0: along the LiDAR's x
  const vod::RadarBox turned = vod::box_in_radar_frame(label, T_camera_turned, kT_camera_lidar);
  EXPECT_NEAR(turned.p_RO_R.x(), -2.0, 1e-12);
  EXPECT_NEAR(turned.p_RO_R.y(), -12.0, 1e-12);
  EXPECT_NEAR(turned.yaw_rad, -kPi / 2, 1e-12);
}

TEST(VodVelocity, TheRadarsVelocityFromCompensatedMinusMeasured) {
  std::vector<vod::RadarPoint> points;
  const Eigen::Vector3d v_S(6.0, -0.5, 0.1);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d p(10.0 + i, -8.0 + 0.9 * i, -2.0 + 0.8 * (i % 5));  // not on one line: u spans 3-D
    const double v_comp = (i % 3 == 0) ? 2.0 : 0.0;  // moving points count as well: only the difference matters
    points.push_back({p.x(), p.y(), p.z(), 0.0, v_comp - v_S.dot(p.normalized()), v_comp, 0.0, 0});
  }
  const vod::RadarVelocity fit = vod::radar_velocity(points);
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.v_S_S.x(), 6.0, 1e-9);
  EXPECT_NEAR(fit.v_S_S.y(), -0.5, 1e-9);
  EXPECT_NEAR(fit.v_S_S.z(), 0.1, 1e-9);
  EXPECT_LT(fit.residual_rms_mps, 1e-9);
  // Two points show no velocity; points along one line of sight none either.
  EXPECT_FALSE(vod::radar_velocity({points[0], points[1]}).valid);
  std::vector<vod::RadarPoint> one_line(5, points[0]);
  EXPECT_FALSE(vod::radar_velocity(one_line).valid);
}

TEST_F(VodImporter, ImportsTheFramesAsSnapshots) {
  const DatasetRecording out = import_vod(root_);
  const Recording& rec = out.recording;
  ASSERT_EQ(rec.cycle_count(), 3);
  EXPECT_EQ(rec.timeline, Timeline::snapshots);
  EXPECT_TRUE(rec.ego_motion_known);
  EXPECT_EQ(rec.source["frames"], nlohmann::json::array({10, 11, 20}));
  ASSERT_EQ(rec.sensors.size(), 1u);
  EXPECT_EQ(rec.sensors[0].reports, ListLevel::detections);
  EXPECT_EQ(rec.sensors[0].amplitude_unit, AmplitudeUnit::relative_db);
  EXPECT_FALSE(rec.sensors[0].range_rate_interval_mps.has_value());
  ASSERT_TRUE(out.extra_files.count(rec.sensors[0].type));
  EXPECT_EQ(out.extra_files.at(rec.sensors[0].type).find("unambiguous_range_rate_mps"), std::string::npos);

  // 15 points of the frame's own scan each; the earlier scan's left out, and said so.
  ASSERT_EQ(rec.targets.size(), 45u);
  const RecordedTarget& first = rec.targets[0];  // stationary at azimuth -1 rad, 5 m, z -1
  EXPECT_NEAR(first.range_m, 5.0, 1e-5);
  EXPECT_NEAR(first.azimuth_rad, -1.0, 1e-6);
  EXPECT_NEAR(first.elevation_rad, std::atan2(-1.0, 5.0), 1e-6);
  EXPECT_NEAR(first.range_rate_mps, -kV_S_S.dot(Eigen::Vector3d(5 * std::cos(-1.0), 5 * std::sin(-1.0), -1.0).normalized()), 1e-5);
  EXPECT_EQ(first.amplitude_db, 0.0);
  EXPECT_EQ(rec.targets[12].rcs_dbsm, 10.0);

  // The ego: 8 m/s from the Doppler; yaw rate 0.01 rad/m x 8 m/s where the poses beside show the arc.
  for (const EgoSample& e : rec.ego) EXPECT_NEAR(e.speed_mps, 8.0, 1e-4);
  EXPECT_NEAR(rec.ego[0].yaw_rate_radps, 0.08, 1e-4);
  EXPECT_NEAR(rec.ego[1].yaw_rate_radps, 0.08, 1e-4);
  EXPECT_EQ(rec.ego[2].yaw_rate_radps, 0.0);  // frame 20 has no neighbour
  EXPECT_EQ(rec.source["ego_motion"]["frames_without_yaw_rate"], 1);
  EXPECT_NEAR(rec.source["ego_motion"]["lateral_speed_max_abs_mps"].get<double>(), 0.3, 1e-4);

  // A car, a pedestrian, a cyclist and a bicycle a frame, in the radar frame, the car with its speed
  // from its points; the cyclist's rider and bicycle boxed again left out as its parts, the
  // others left out, said why.
  ASSERT_EQ(rec.objects.size(), 12u);
  std::map<std::string, int> models;
  for (const RecordingObject& o : rec.objects) ++models[o.object_class];
  EXPECT_EQ(models, (std::map<std::string, int>{{"bicycle", 3}, {"cyclist", 3}, {"passenger_car", 3}, {"pedestrian", 3}}));
  EXPECT_EQ(rec.objects[1].object_class, "pedestrian");
  EXPECT_EQ(rec.objects[1].attributes["dataset_class"], "Pedestrian");
  EXPECT_EQ(rec.objects[0].id, "f00010_00");
  EXPECT_EQ(rec.objects[0].object_class, "passenger_car");
  EXPECT_EQ(rec.objects[0].length_m, 4.0);
  EXPECT_EQ(rec.objects[0].attributes["dataset_class"], "Car");
  const AnnotatedBox& car = rec.boxes[0][0];
  EXPECT_NEAR(car.x_m, 20.0, 1e-6);
  EXPECT_NEAR(car.y_m, 1.0, 1e-6);
  EXPECT_NEAR(car.yaw_rad, 0.0, 1e-6);
  EXPECT_NEAR(car.speed_mps, kCarSpeed_mps, 1e-4);
  EXPECT_NEAR(rec.objects[0].attributes["z_m"].get<double>(), 0.0, 1e-6);
  std::string warnings;
  for (const std::string& w : out.warnings) warnings += w + "\n";
  EXPECT_EQ(warnings.find("class Pedestrian"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("3 boxes of class rider left out: parts of a Cyclist box"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("3 boxes of class bicycle left out: parts of a Cyclist box"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("3 boxes of class DontCare left out"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("3 points of earlier scans"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("placeholder"), std::string::npos) << warnings;
}

DatasetImportOptions with_frames(const std::string& frames) {
  DatasetImportOptions options;
  options.frames = frames;
  return options;
}

TEST_F(VodImporter, FramesChooseByNumberAndRefuseWhatIsNotThere) {
  EXPECT_EQ(import_vod(root_, with_frames("11,20")).recording.source["frames"], nlohmann::json::array({11, 20}));
  EXPECT_EQ(import_vod(root_, with_frames("0-15")).recording.cycle_count(), 2);
  const auto refused = [&](const std::string& frames) {
    try {
      (void)import_vod(root_, with_frames(frames));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused("12").find("--frames: no frame 12"), std::string::npos) << refused("12");
  EXPECT_NE(refused("10-11,11").find("chosen twice"), std::string::npos);
  EXPECT_NE(refused("30-40").find("no frame in 30-40"), std::string::npos);
}

TEST_F(VodImporter, DamagedFilesAreRefusedNamingFileAndPlace) {
  const auto message = [&] {
    try {
      (void)import_vod(root_);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string bin = (root_ / "radar/training/velodyne/00011.bin").string();
  const std::string bytes = testing::file_bytes(bin);
  put("radar/training/velodyne/00011.bin", bytes.substr(0, bytes.size() - 5));
  EXPECT_NE(message().find(bin + ": " + std::to_string(bytes.size() - 5) + " bytes is no whole number of points"), std::string::npos)
      << message();
  put("radar/training/velodyne/00011.bin", radar_bytes({{1.0, 2.0, std::nan(""), 0, 0, 0, 0}}));
  EXPECT_NE(message().find(bin + ": point 0, z: not finite"), std::string::npos) << message();
  put("radar/training/velodyne/00011.bin", radar_bytes({{1.0, 2.0, 0.0, 0, 0, 0, 0.5}}));
  EXPECT_NE(message().find("point 0, time: 0.5 is no scan id"), std::string::npos) << message();
  put("radar/training/velodyne/00011.bin", bytes);

  const std::string labels = (root_ / "lidar/training/label_2/00020.txt").string();
  put("lidar/training/label_2/00020.txt", "Car 0 1 0 1 2 3 4 1.5 1.8\n");
  EXPECT_NE(message().find(labels + ": line 1: 10 fields, expected 15 or 16"), std::string::npos) << message();
  put("lidar/training/label_2/00020.txt", "Car 0 1 0 1 2 3 4 1.5 0 4 1 1 1 0\n");
  EXPECT_NE(message().find(labels + ": line 1, w: 0 m"), std::string::npos) << message();
  put("lidar/training/label_2/00020.txt", "Car 0 1 0 1 2 3 4 1.5 1.8 4 1 1 x1 0\n");
  EXPECT_NE(message().find(labels + ": line 1, field 14: 'x1' is not a number"), std::string::npos) << message();
  fs::remove(labels);
  EXPECT_NE(message().find(labels), std::string::npos) << message();
  put("lidar/training/label_2/00020.txt", "");

  const std::string calib = (root_ / "lidar/training/calib/00010.txt").string();
  put("lidar/training/calib/00010.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(message().find(calib + ": no line 'Tr_velo_to_cam:'"), std::string::npos) << message();
  put("lidar/training/calib/00010.txt", "Tr_velo_to_cam: 2 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(message().find(calib + ": line 1, Tr_velo_to_cam: is no rigid transform"), std::string::npos) << message();
  put("lidar/training/calib/00010.txt", kitti_calib(kT_camera_lidar));

  const std::string pose = (root_ / "lidar/training/pose/00011.json").string();
  put("lidar/training/pose/00011.json", "{\"odomToCamera\": [1, 2]}\n");
  EXPECT_NE(message().find(pose + ": line 1, odomToCamera: must hold 16 numbers"), std::string::npos) << message();
}

TEST_F(VodImporter, AFolderOfTheDatasetNamesItsRoot) {
  try {
    (void)import_vod(root_ / "radar" / "training");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a folder of the View-of-Delft dataset " + fs::absolute(root_).lexically_normal().string() +
                                         ": give its root"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)import_vod(dir_), InputError);
}

TEST_F(VodImporter, FromTheCommandLineToAReplay) {
  const fs::path rec = dir_ / "rec", db = dir_ / "report.sqlite";
  const auto imported = run_rcsim(fmt::format("import --from vod '{}' -o '{}'", root_.string(), rec.string()));
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  EXPECT_TRUE(fs::is_regular_file(rec / "sensor_zf_frgen21.json"));
  const auto replayed = run_rcsim(fmt::format("replay '{}' --db '{}'", rec.string(), db.string()));
  EXPECT_EQ(replayed.exit_code, 0) << replayed.output;
  const auto mistyped = run_rcsim(fmt::format("import --from vdo '{}' -o '{}'", root_.string(), (dir_ / "x").string()));
  EXPECT_EQ(mistyped.exit_code, 2);
  EXPECT_TRUE(testing::output_has(mistyped, "vod")) << mistyped.output;
}

}  // namespace vod_importer_test
}  // namespace rcsim::replay
