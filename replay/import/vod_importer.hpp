#pragma once
// The View-of-Delft dataset (Palffy et al., "Multi-class Road User Detection with 3+1D Radar in
// the View-of-Delft Dataset", IEEE RA-L 2022; TU Delft, non-commercial licence) as an rcsim
// recording (`rcsim import --from vod RAW_DIR -o RECORDING_DIR [--frames LIST]`,
// docs/importers.md). RAW_DIR is the dataset's root, in its KITTI-style layout:
//   radar/training/velodyne/NNNNN.bin  the ZF FRGen21 3+1D radar's points: float32 x 7 each,
//                                      x y z RCS v_r v_r_compensated time (radar frame)
//   radar/training/calib/NNNNN.txt     KITTI calibration: Tr_velo_to_cam = T_camera_radar
//   lidar/training/calib/NNNNN.txt     KITTI calibration: Tr_velo_to_cam = T_camera_lidar
//   lidar/training/label_2/NNNNN.txt   KITTI labels, camera frame (radar/training/label_2 where
//                                      the lidar folder has none)
//   lidar/training/pose/NNNNN.json     odometry: JSON lines odomToCamera, mapToCamera,
//                                      UTMToCamera (radar/training/pose where the lidar has none)
// The frames are snapshots (one frame one cycle, `timeline: "snapshots"`); the ego's velocity
// comes from each frame's own points (v_r_compensated - v_r), its yaw rate from the poses of the
// frames beside it where the dataset has them.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "replay/import/dataset_importer.hpp"

namespace rcsim::replay {

namespace vod {

// One point of a radar file, as the file gives it (radar frame: x forward, y left, z up).
struct RadarPoint {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double rcs_dbsm = 0.0;
  double v_r_mps = 0.0;              // relative radial speed, positive receding (as measured)
  double v_r_compensated_mps = 0.0;  // the same over the ground (ego motion removed)
  double time = 0.0;                 // which scan: 0 the frame's own, -1, -2 ... earlier ones
  std::size_t index = 0;             // in the file, for messages
};

// A radar file's points; an InputError naming the file (and the point) otherwise.
std::vector<RadarPoint> read_radar_file(const std::filesystem::path& path);

// A KITTI calibration file's Tr_velo_to_cam (the point-cloud sensor in the camera frame) as a
// 4 x 4 rigid transform; an InputError naming the file and line otherwise.
Eigen::Matrix4d read_kitti_extrinsic(const std::filesystem::path& path);

// One KITTI label line: class, truncated, occluded, alpha, 2-D box (4), h w l, x y z (the box's
// bottom centre in the camera frame), rotation (about the LiDAR's -z, VoD's devkit), [score].
struct Label {
  std::string label_class;
  int occluded = 0;
  double height_m = 0.0, width_m = 0.0, length_m = 0.0;
  Eigen::Vector3d p_bottom_C = Eigen::Vector3d::Zero();
  double rotation_rad = 0.0;
  int line = 0;
};
std::vector<Label> read_labels(const std::filesystem::path& path);

// A label's box in the radar frame R, as VoD's devkit draws it: the bottom centre into the LiDAR
// frame L (T_camera_lidar^-1), the yaw there -(rotation + pi/2), then into R through
// T_radar_lidar = T_camera_radar^-1 T_camera_lidar; the centre lifted by half the height.
struct RadarBox {
  Eigen::Vector3d p_RO_R = Eigen::Vector3d::Zero();  // the box's centre
  double yaw_rad = 0.0;                              // its length axis, about R's z
};
RadarBox box_in_radar_frame(const Label& label, const Eigen::Matrix4d& T_camera_radar, const Eigen::Matrix4d& T_camera_lidar);

// VoD boxes a cyclist three times: the Cyclist box and, inside it, its rider and its bicycle. A
// rider or bicycle box whose centre lies within this reach of a Cyclist box's centre is a part of
// it (left out); one alone is a road user of its own (a rider: cyclist, a bicycle: bicycle).
inline constexpr double kCyclistPartReach_m = 1.0;
bool part_of_a_cyclist(const RadarBox& box, const std::vector<RadarBox>& cyclists);

// The radar's own velocity over the ground in its frame, from one frame's points: a point's
// v_r_compensated - v_r is the radar's velocity along its line of sight u (v_r = (v_T - v_S).u,
// v_r_compensated = v_T.u), least squares over all points; vz left out (0) where the points
// hardly spread in elevation.
struct RadarVelocity {
  Eigen::Vector3d v_S_S = Eigen::Vector3d::Zero();
  double residual_rms_mps = 0.0;
  std::size_t points = 0;
  bool valid = false;  // at least 3 points spread in azimuth
};
RadarVelocity radar_velocity(const std::vector<RadarPoint>& points);

// A pose file's odomToCamera (T_odom_camera); an InputError naming the file and line otherwise.
Eigen::Matrix4d read_odom_pose(const std::filesystem::path& path);

// The files of one frame (absolute paths); pose empty where the dataset has none for it.
struct Frame {
  int number = 0;
  std::filesystem::path radar, radar_calib, lidar_calib, labels, pose;
};

struct Dataset {
  std::filesystem::path dir;
  std::vector<Frame> frames;  // by number
};

// The dataset in raw_dir; every radar frame with its calibrations and labels.
Dataset find_dataset(const std::filesystem::path& raw_dir);
// The frames a --frames list chooses (all where it is empty), ascending.
std::vector<Frame> choose_frames(const Dataset& dataset, const std::string& frames);

}  // namespace vod

DatasetRecording import_vod(const std::filesystem::path& raw_dir, const DatasetImportOptions& options = {});

}  // namespace rcsim::replay
