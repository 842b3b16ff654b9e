#pragma once
// The aiMotive Multimodal Dataset (Matuszka et al. 2022, arXiv:2211.09445) as an rcsim recording
// (`rcsim import --from aimotive RAW_DIR -o RECORDING_DIR`, docs/importers.md). A sequence holds
//   dynamic/box/3d_body/frame_N.json   annotated boxes per keyframe (body frame), Timestamp in ns
//   sensor/radar/LABEL/LABEL_N.json    each radar's detections of keyframe N
//   sensor/calibration/calibration.json  RT_body_from_sensor of every sensor
// One keyframe is one cycle. The ego log (sensor/gnssins) is not in the public sample: the ego's
// speed and yaw rate are estimated from the Doppler of the stationary world
// (replay/import/doppler_ego_motion.hpp) and recording.json says so, with the residuals.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/pose2.hpp"
#include "replay/import/dataset_importer.hpp"

namespace rcsim::replay {

namespace aimotive {

struct RadarMount {
  std::string label;            // F_LRR_C, B_LRR_C, ...
  Eigen::Matrix4d T_body_sensor;  // RT_body_from_sensor: p_B = R p_S + t
  Pose2 X_VS;                   // its planar part: position and yaw in the vehicle (body) frame
};

struct RadarDetection {
  double range_m = 0.0, azimuth_rad = 0.0, elevation_rad = 0.0;
  double speed_mps = 0.0;  // radial, negative approaching, not ego-compensated
  double rcs_m2 = 0.0, power_db = 0.0, noise_db = 0.0;
};

struct Keyframe {
  std::string number;  // "0033643"
  std::int64_t timestamp_ns = 0;
  std::filesystem::path box_file;
};

// The sequence directory under raw_dir (raw_dir itself, or the one sequence below it).
std::filesystem::path find_sequence(const std::filesystem::path& raw_dir);
// Every radar under sensor/radar/ with its mounting from the calibration file.
std::vector<RadarMount> read_radar_mounts(const std::filesystem::path& sequence);
// The keyframes in time order.
std::vector<Keyframe> list_keyframes(const std::filesystem::path& sequence);
std::vector<RadarDetection> read_radar_file(const std::filesystem::path& path);

// A detection as the planar sensor at mount.X_VS reports it: the 3-D point through the full
// mounting matrix, projected onto the road plane: horizontal range and azimuth from the sensor's
// planar pose; the measured radial speed; SNR (power - noise) as the amplitude.
RecordedTarget planar_target(const RadarDetection& detection, const RadarMount& mount);

}  // namespace aimotive

// The sequence under raw_dir. The public sample has no ego log (sensor/gnssins/egomotion*.json,
// whose layout is not published): the ego motion is estimated from the radars' Doppler unless
// options.ego_log gives one, which is then used and the estimate only reported beside it.
DatasetRecording import_aimotive(const std::filesystem::path& raw_dir, const DatasetImportOptions& options = {});

}  // namespace rcsim::replay
