#pragma once
// The Astyx HiRes2019 dataset (Meyer and Kuschk, EuRAD 2019; CC BY-NC-SA 4.0, Astyx GmbH) as an
// rcsim recording (`rcsim import --from astyx RAW_DIR -o RECORDING_DIR [--frames LIST]`,
// docs/importers.md). RAW_DIR is one dataset directory:
//   dataset.json (dataset_info.json)   the frames: `data` keys, each with its files
//   radar_6455/NNNNNN.txt (radar_hires1/)  the imaging radar's point cloud: X Y Z V_r Mag
//   groundtruth_obj3d/NNNNNN.json      3-D boxes in the radar frame, no velocities
//   calibration/NNNNNN.json            T_to_ref_COS of every sensor (the radar's: the identity)
//   canbus/NNNNNN.json                 the demo frames only: vehicle_speed (km/h), YAW_RATE (deg/s)
// The frames are single snapshots, not a drive: the recording's timeline is `snapshots`, one
// frame one cycle, t_s = k only orders them. Frames without CAN have no ego motion
// (ego_motion_known false).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/pose2.hpp"
#include "replay/import/dataset_importer.hpp"

namespace rcsim::replay {

namespace astyx {

// The radar's Doppler (README of the data; Meyer and Kuschk 2019): V_r in 128 levels of
// 0.0812 m/s from -5.1156 to +5.1968 m/s; faster radial speeds wrap around. A level stands for
// the half step either side, so the unambiguous V_r interval is [-5.1156 - 0.0406,
// 5.1968 + 0.0406) = [-5.1562, 5.2374), 128 x 0.0812 = 10.3936 m/s wide.
inline constexpr int kDopplerLevels = 128;
inline constexpr double kDopplerStep_mps = 0.0812;
inline constexpr double kLowestVr_mps = -5.1156, kHighestVr_mps = 5.1968;  // (H - L) / step = 127
// V_r is positive for a target that comes closer (measured on the demo frames, whose CAN speeds
// are known: the stationary world ahead reads V_r = +v cos(angle), docs/importers.md), the
// opposite of rcsim's range rate: range_rate_mps = -V_r, wrapped into [-5.2374, 5.1562).
inline constexpr RangeRateInterval kRangeRateInterval_mps{-(kHighestVr_mps + 0.5 * kDopplerStep_mps),
                                                          -(kLowestVr_mps - 0.5 * kDopplerStep_mps)};

inline constexpr const char* kSensorProfile = "astyx_hires";  // src/sensor/sensors/astyx_hires.json

// One row of a radar file, as the file gives it.
struct RadarPoint {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;  // radar frame: x forward, y left, z up
  double v_r_mps = 0.0;                    // radial speed, positive approaching, aliased
  double mag = 0.0;                        // the radar's own dB-like level
  int line = 0;                            // in the file, for messages
};

// One frame of the dataset and its files (absolute paths); canbus empty where there is none.
struct Frame {
  int number = 0;  // the `data` key
  std::filesystem::path radar, groundtruth, calibration, canbus;
};

struct Dataset {
  std::filesystem::path dir;
  std::filesystem::path listing;  // dataset.json or dataset_info.json
  std::string radar;              // the radar's key and sensor uid: radar_6455, radar_hires1
  std::vector<Frame> frames;      // by number
};

// The dataset in raw_dir: raw_dir itself; a directory holding datasets is refused naming them.
Dataset find_dataset(const std::filesystem::path& raw_dir);
// The frames a --frames list chooses (all where it is empty), in ascending order.
std::vector<Frame> choose_frames(const Dataset& dataset, const std::string& frames);
// A radar file's rows; InputError naming the file and line.
std::vector<RadarPoint> read_radar_file(const std::filesystem::path& path);
// The point as the planar radar at X_VS (mounting T_VS) reports it: horizontal range and azimuth,
// elevation, range rate -V_r, amplitude Mag.
RecordedTarget planar_target(const RadarPoint& point, const Eigen::Matrix4d& T_VS, const Pose2& X_VS);
// The heading of a box whose orientation is the unit quaternion (w, x, y, z): its yaw about z.
double yaw_of_quaternion_rad(double w, double x, double y, double z);

}  // namespace astyx

DatasetRecording import_astyx(const std::filesystem::path& raw_dir, const DatasetImportOptions& options = {});

}  // namespace rcsim::replay
