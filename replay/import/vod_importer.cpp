#include "replay/import/vod_importer.hpp"
#include "replay/import/ground_plane.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <nlohmann/json.hpp>

#include "common/angles.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/safe_text.hpp"
#include "common/text_file.hpp"
#include "model/model_library.hpp"
#include "replay/import/rigid_transform.hpp"

namespace rcsim::replay {

namespace fs = std::filesystem;

namespace vod {

namespace {

constexpr std::size_t kRadarFields = 7;  // x y z RCS v_r v_r_compensated time
constexpr std::size_t kRadarPointBytes = kRadarFields * sizeof(float);
// A radar file of more bytes is no single frame (a frame holds hundreds of points): 2.4 M points
// (schemas/limits.md).
constexpr std::uintmax_t kMaxRadarFileBytes = 64ull << 20;
// The earliest scan a point may come from (radar_5_scans holds 0 to -4).
constexpr double kEarliestScan = -1000.0;
// The largest frame number (the dataset's file names have five digits).
constexpr long long kMaxFrameNumber = 99'999'999;
// Box points: a point belongs to a box within this margin (the labels are drawn on the LiDAR).
constexpr double kBoxMargin_m = 0.3;

double field_number(std::string_view text, const std::string& file, int line, std::string_view name) {
  return finite_number_field(text, file, fmt::format("line {}, {}", line, name));
}

float little_endian_float(const unsigned char* bytes) {
  std::uint32_t bits = 0;
  for (int b = 3; b >= 0; --b) bits = (bits << 8) | bytes[b];
  return std::bit_cast<float>(bits);
}

}  // namespace

std::vector<RadarPoint> read_radar_file(const fs::path& path) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path);  // refuses what is missing or no regular file, by name
  std::error_code error;
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (error) throw InputError(file, "", "cannot tell its size: " + error.message());
  if (bytes > kMaxRadarFileBytes) {
    throw InputError(file, "", fmt::format("{} bytes, beyond the limit of {} bytes for one frame's points", bytes, kMaxRadarFileBytes));
  }
  if (bytes % kRadarPointBytes != 0) {
    throw InputError(file, "", fmt::format("{} bytes is no whole number of points of 7 float32 (x y z RCS v_r "
                                           "v_r_compensated time, {} bytes each): truncated?",
                                           bytes, kRadarPointBytes));
  }
  std::vector<unsigned char> data(static_cast<std::size_t>(bytes));
  if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(bytes))) {
    throw InputError(file, "", "could not be read whole");
  }
  std::vector<RadarPoint> points(data.size() / kRadarPointBytes);
  static constexpr const char* kNames[kRadarFields] = {"x", "y", "z", "RCS", "v_r", "v_r_compensated", "time"};
  for (std::size_t i = 0; i < points.size(); ++i) {
    double v[kRadarFields];
    for (std::size_t f = 0; f < kRadarFields; ++f) {
      v[f] = little_endian_float(data.data() + i * kRadarPointBytes + f * sizeof(float));
      if (!std::isfinite(v[f])) throw InputError(file, fmt::format("point {}, {}", i, kNames[f]), "not finite");
    }
    const auto fail = [&](std::size_t f, const std::string& message) {
      throw InputError(file, fmt::format("point {}, {}", i, kNames[f]), message);
    };
    for (std::size_t f = 0; f < 3; ++f) {
      if (std::abs(v[f]) > limits::kMaxRange_m) fail(f, fmt::format("|{}| exceeds the limit of {} m", v[f], limits::kMaxRange_m));
    }
    if (std::abs(v[3]) > limits::kMaxLevel_dB) fail(3, fmt::format("|{}| exceeds the limit of {} dB", v[3], limits::kMaxLevel_dB));
    for (std::size_t f = 4; f < 6; ++f) {
      if (std::abs(v[f]) > limits::kMaxSpeed_mps) fail(f, fmt::format("|{}| exceeds the limit of {} m/s", v[f], limits::kMaxSpeed_mps));
    }
    if (v[6] > 0.0 || v[6] < kEarliestScan || v[6] != std::floor(v[6])) {
      fail(6, fmt::format("{} is no scan id (0 for the frame's own scan, -1, -2, ... for earlier ones)", v[6]));
    }
    points[i] = {v[0], v[1], v[2], v[3], v[4], v[5], v[6], i};
  }
  return points;
}

Eigen::Matrix4d read_kitti_extrinsic(const fs::path& path) {
  const std::string file = path.string();
  LineReader lines(path);
  std::string_view line;
  while (lines.next(line)) {
    const std::vector<std::string_view> fields = whitespace_fields(line);
    if (fields.empty() || fields[0] != "Tr_velo_to_cam:") continue;
    const int n = lines.line_number();
    if (fields.size() != 13) {
      throw InputError(file, fmt::format("line {}", n),
                       fmt::format("Tr_velo_to_cam holds {} numbers, expected 12 (a 3 x 4 matrix, row by row)", fields.size() - 1));
    }
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (int k = 0; k < 12; ++k) {
      T(k / 4, k % 4) = field_number(fields[static_cast<std::size_t>(k) + 1], file, n, fmt::format("Tr_velo_to_cam element {}", k));
    }
    if (const auto flaw = rigid_transform_flaw(T)) throw InputError(file, fmt::format("line {}, Tr_velo_to_cam", n), *flaw);
    if (T.topRightCorner<3, 1>().cwiseAbs().maxCoeff() > limits::kMaxMountOffset_m) {
      throw InputError(file, fmt::format("line {}, Tr_velo_to_cam", n),
                       fmt::format("a translation beyond {} m: is it in millimetres?", limits::kMaxMountOffset_m));
    }
    return T;
  }
  throw InputError(file, "", "no line 'Tr_velo_to_cam:' (a KITTI calibration file: P0-P3, R0_rect, Tr_velo_to_cam, ...)");
}

std::vector<Label> read_labels(const fs::path& path) {
  const std::string file = path.string();
  LineReader lines(path);
  std::string_view line;
  std::vector<Label> labels;
  while (lines.next(line)) {
    const std::vector<std::string_view> f = whitespace_fields(line);
    if (f.empty()) continue;
    const int n = lines.line_number();
    if (f.size() != 15 && f.size() != 16) {
      throw InputError(file, fmt::format("line {}", n),
                       fmt::format("{} fields, expected 15 or 16 (KITTI: class truncated occluded alpha, the 2-D box, h w "
                                   "l, x y z, rotation, [score])",
                                   f.size()));
    }
    Label label;
    label.label_class = std::string(f[0]);
    if (const auto bad = find_control_character(label.label_class)) throw InputError(file, fmt::format("line {}, class", n), "holds " + *bad);
    if (label.label_class.size() > 64) throw InputError(file, fmt::format("line {}, class", n), "longer than 64 bytes: not a class name");
    label.line = n;
    std::vector<double> v;
    for (std::size_t k = 1; k < f.size(); ++k) v.push_back(field_number(f[k], file, n, fmt::format("field {}", k + 1)));
    if (label.label_class == "DontCare") {  // a region left unlabelled: KITTI writes -1 and -1000 there
      labels.push_back(std::move(label));
      continue;
    }
    label.occluded = static_cast<int>(v[1]);
    label.height_m = v[7];
    label.width_m = v[8];
    label.length_m = v[9];
    label.p_bottom_C = {v[10], v[11], v[12]};
    label.rotation_rad = v[13];
    const auto where = [&](const char* name) { return fmt::format("line {}, {}", n, name); };
    for (const auto& [name, size] : {std::pair{"h", label.height_m}, std::pair{"w", label.width_m}, std::pair{"l", label.length_m}}) {
      if (!(size > 0.0 && size <= limits::kMaxSize_m)) {
        throw InputError(file, where(name), fmt::format("{} m: a box's height, width and length lie in (0, {}] m", size, limits::kMaxSize_m));
      }
    }
    if (label.p_bottom_C.cwiseAbs().maxCoeff() > limits::kMaxRange_m) {
      throw InputError(file, where("x y z"), fmt::format("beyond the limit of {} m", limits::kMaxRange_m));
    }
    if (std::abs(label.rotation_rad) > limits::kMaxYaw_rad) {
      throw InputError(file, where("rotation"), fmt::format("{}: beyond ±2π (degrees?)", label.rotation_rad));
    }
    labels.push_back(std::move(label));
  }
  return labels;
}

bool part_of_a_cyclist(const RadarBox& box, const std::vector<RadarBox>& cyclists) {
  return std::any_of(cyclists.begin(), cyclists.end(), [&](const RadarBox& c) {
    return (c.p_RO_R.head<2>() - box.p_RO_R.head<2>()).norm() <= kCyclistPartReach_m;
  });
}

RadarBox box_in_radar_frame(const Label& label, const Eigen::Matrix4d& T_camera_radar, const Eigen::Matrix4d& T_camera_lidar) {
  const Eigen::Matrix4d T_lidar_camera = T_camera_lidar.inverse();
  const Eigen::Matrix4d T_radar_lidar = T_camera_radar.inverse() * T_camera_lidar;
  // VoD's devkit: the label's rotation is about the LiDAR's -z, a quarter turn off its x axis.
  const double yaw_L_rad = -(label.rotation_rad + 0.5 * kPi);
  const Eigen::Vector4d p_bottom_L = T_lidar_camera * label.p_bottom_C.homogeneous();
  const Eigen::Vector4d p_centre_L = p_bottom_L + Eigen::Vector4d(0.0, 0.0, 0.5 * label.height_m, 0.0);
  const Eigen::Vector3d axis_R = T_radar_lidar.topLeftCorner<3, 3>() * Eigen::Vector3d(std::cos(yaw_L_rad), std::sin(yaw_L_rad), 0.0);
  RadarBox box;
  box.p_RO_R = (T_radar_lidar * p_centre_L).head<3>();
  box.yaw_rad = std::atan2(axis_R.y(), axis_R.x());
  return box;
}

RadarVelocity radar_velocity(const std::vector<RadarPoint>& points) {
  RadarVelocity fit;
  std::vector<Eigen::Vector3d> u;
  std::vector<double> d;
  for (const RadarPoint& p : points) {
    const Eigen::Vector3d p_ST_S(p.x_m, p.y_m, p.z_m);
    if (p_ST_S.norm() < 1e-3) continue;  // no line of sight
    u.push_back(p_ST_S.normalized());
    d.push_back(p.v_r_compensated_mps - p.v_r_mps);  // = v_S . u
  }
  fit.points = u.size();
  if (u.size() < 3) return fit;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(u.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(u.size()));
  for (std::size_t i = 0; i < u.size(); ++i) {
    A.row(static_cast<Eigen::Index>(i)) = u[i].transpose();
    b(static_cast<Eigen::Index>(i)) = d[i];
  }
  // The normal matrix's spread: a frame whose points lie in one plane of elevation (or one line of
  // sight) cannot show vz (or vy); those stay 0.
  const Eigen::Matrix3d N = A.transpose() * A / static_cast<double>(u.size());
  const bool with_vz = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(N, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() > 1e-8;
  const Eigen::Matrix2d N2 = N.topLeftCorner<2, 2>();
  if (N2.determinant() < 1e-4) return fit;  // all points along one line of sight
  if (with_vz) {
    fit.v_S_S = A.colPivHouseholderQr().solve(b);
  } else {
    fit.v_S_S.head<2>() = A.leftCols<2>().colPivHouseholderQr().solve(b);
    fit.v_S_S.z() = 0.0;
  }
  fit.residual_rms_mps = std::sqrt((A * fit.v_S_S - b).squaredNorm() / static_cast<double>(u.size()));
  fit.valid = fit.v_S_S.allFinite();
  return fit;
}

Eigen::Matrix4d read_odom_pose(const fs::path& path) {
  const std::string file = path.string();
  LineReader lines(path);
  std::string_view line;
  while (lines.next(line)) {
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    const std::string where = fmt::format("line {}", lines.line_number());
    const nlohmann::json json = parse_json_text(line, file + ": " + where);
    if (!json.is_object() || !json.contains("odomToCamera")) continue;
    const nlohmann::json& m = json.at("odomToCamera");
    if (!m.is_array() || m.size() != 16) throw InputError(file, where + ", odomToCamera", "must hold 16 numbers (a 4 x 4 matrix, row by row)");
    Eigen::Matrix4d T;
    for (int k = 0; k < 16; ++k) {
      const nlohmann::json& v = m[static_cast<std::size_t>(k)];
      if (!v.is_number() || !std::isfinite(v.get<double>())) {
        throw InputError(file, where + ", odomToCamera", fmt::format("element {} is not a finite number", k));
      }
      T(k / 4, k % 4) = v.get<double>();
    }
    if (const auto flaw = rigid_transform_flaw(T)) throw InputError(file, where + ", odomToCamera", *flaw);
    if (T.topRightCorner<3, 1>().cwiseAbs().maxCoeff() > limits::kMaxCoordinate_m) {
      throw InputError(file, where + ", odomToCamera", fmt::format("a translation beyond {} m", limits::kMaxCoordinate_m));
    }
    return T;
  }
  throw InputError(file, "", "no line with odomToCamera (VoD's pose files: one JSON object a line)");
}

namespace {

bool is_frame_name(const fs::path& file, std::string_view extension, long long& number) {
  if (file.extension() != extension) return false;
  const std::string stem = file.stem().string();
  const auto [end, error] = std::from_chars(stem.data(), stem.data() + stem.size(), number);
  return !stem.empty() && stem.size() <= 8 && error == std::errc() && end == stem.data() + stem.size() && number >= 0 &&
         number <= kMaxFrameNumber;
}

fs::path first_existing(const std::vector<fs::path>& candidates) {
  for (const fs::path& p : candidates) {
    if (fs::exists(p)) return p;
  }
  return {};
}

}  // namespace

Dataset find_dataset(const fs::path& raw_dir) {
  if (!fs::exists(raw_dir)) throw InputError(raw_dir.string(), "", "no such directory");
  if (!fs::is_directory(raw_dir)) throw InputError(raw_dir.string(), "", "not a directory");
  const fs::path radar_dir = raw_dir / "radar" / "training" / "velodyne";
  if (!fs::is_directory(radar_dir)) {
    fs::path absolute = fs::absolute(raw_dir).lexically_normal();
    if (absolute.filename().empty()) absolute = absolute.parent_path();
    for (fs::path up = absolute; !up.empty() && up != up.root_path(); up = up.parent_path()) {
      if (fs::is_directory(up / "radar" / "training" / "velodyne")) {
        throw InputError(raw_dir.string(), "", fmt::format("a folder of the View-of-Delft dataset {}: give its root", up.string()));
      }
    }
    throw InputError(raw_dir.string(), "",
                     "no View-of-Delft dataset here (its root holds radar/training/velodyne/NNNNN.bin, radar/training/calib/, "
                     "lidar/training/calib/ and lidar/training/label_2/)");
  }
  Dataset dataset;
  dataset.dir = raw_dir;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(radar_dir, fs::directory_options::skip_permission_denied, ignored)) {
    long long number = -1;
    if (!is_frame_name(entry.path().filename(), ".bin", number)) continue;
    const std::string name = entry.path().stem().string();
    Frame frame;
    frame.number = static_cast<int>(number);
    frame.radar = entry.path();
    frame.radar_calib = raw_dir / "radar" / "training" / "calib" / (name + ".txt");
    frame.lidar_calib = raw_dir / "lidar" / "training" / "calib" / (name + ".txt");
    frame.labels = first_existing({raw_dir / "lidar" / "training" / "label_2" / (name + ".txt"),
                                   raw_dir / "radar" / "training" / "label_2" / (name + ".txt")});
    if (frame.labels.empty()) frame.labels = raw_dir / "lidar" / "training" / "label_2" / (name + ".txt");
    frame.pose = first_existing({raw_dir / "lidar" / "training" / "pose" / (name + ".json"),
                                 raw_dir / "radar" / "training" / "pose" / (name + ".json")});
    dataset.frames.push_back(std::move(frame));
  }
  std::sort(dataset.frames.begin(), dataset.frames.end(), [](const Frame& a, const Frame& b) { return a.number < b.number; });
  for (std::size_t i = 1; i < dataset.frames.size(); ++i) {
    if (dataset.frames[i].number == dataset.frames[i - 1].number) {
      throw InputError(dataset.frames[i].radar.string(), "",
                       fmt::format("frame {} again (as {}): one file a frame", dataset.frames[i].number, dataset.frames[i - 1].radar.string()));
    }
  }
  if (dataset.frames.empty()) throw InputError(radar_dir.string(), "", "no radar frame (NNNNN.bin) in it");
  return dataset;
}

std::vector<Frame> choose_frames(const Dataset& dataset, const std::string& frames) {
  if (frames.empty()) return dataset.frames;
  const std::vector<FrameRange> ranges = parse_frame_list(frames);
  // Each item must name a frame of the dataset; the frames are walked, never the ranges.
  std::vector<bool> chosen(dataset.frames.size(), false);
  for (const FrameRange& range : ranges) {
    bool any = false;
    for (std::size_t i = 0; i < dataset.frames.size(); ++i) {
      if (dataset.frames[i].number < range.first || dataset.frames[i].number > range.last) continue;
      if (chosen[i]) {
        throw InputError("--frames", "", fmt::format("frame {} is chosen twice in '{}'", dataset.frames[i].number, frames));
      }
      chosen[i] = any = true;
    }
    if (!any) {
      throw InputError("--frames", "",
                       range.first == range.last
                           ? fmt::format("no frame {} in {} (its frames: {} to {})", range.first, dataset.dir.string(),
                                         dataset.frames.front().number, dataset.frames.back().number)
                           : fmt::format("no frame in {}-{} in {} (its frames: {} to {})", range.first, range.last,
                                         dataset.dir.string(), dataset.frames.front().number, dataset.frames.back().number));
    }
  }
  std::vector<Frame> out;
  for (std::size_t i = 0; i < dataset.frames.size(); ++i) {
    if (chosen[i]) out.push_back(dataset.frames[i]);
  }
  return out;
}

}  // namespace vod

namespace vod {
namespace {

constexpr const char* kSensorFile = "sensor_zf_frgen21.json";
constexpr const char* kLicence =
    "View-of-Delft dataset, TU Delft (non-commercial research use, see the dataset's licence; Palffy et al., IEEE RA-L 2022)";

// The dataset's classes: an object model, or why it is left out.
struct ClassMapping {
  const char* model;  // empty: left out
  const char* why;
};

const std::map<std::string, ClassMapping, std::less<>>& class_mappings() {
  static const std::map<std::string, ClassMapping, std::less<>> mappings{
      {"Car", {"passenger_car", ""}},
      {"truck", {"truck_trailer", ""}},
      {"vehicle_other", {"passenger_car", ""}},
      {"Pedestrian", {"pedestrian", ""}},
      {"Cyclist", {"cyclist", ""}},
      // Parts of a Cyclist box are boxed again (its rider, its bicycle): those are left out as
      // parts (part_of_a_cyclist); a rider or a bicycle alone is one of its own.
      {"rider", {"cyclist", ""}},
      {"bicycle", {"bicycle", ""}},
      {"moped_scooter", {"", "a moped or scooter: the object library has no model of two-wheelers yet"}},
      {"motor", {"", "a motorcycle: the object library has no model of two-wheelers yet"}},
      {"ride_other", {"", "another ridden vehicle: no object model for it"}},
      {"ride_uncertain", {"", "a ridden vehicle of uncertain kind: no object model for it"}},
      {"bicycle_rack", {"", "street furniture: part of the stationary background"}},
      {"human_depiction", {"", "a picture or statue of a person, not a road user"}},
      {"DontCare", {"", "a region the annotators left unlabelled"}},
  };
  return mappings;
}

// The points of one frame's own scan (time 0), counting those of earlier scans left out.
std::vector<RadarPoint> own_scan(std::vector<RadarPoint> points, std::size_t& earlier) {
  const auto from_earlier = std::stable_partition(points.begin(), points.end(), [](const RadarPoint& p) { return p.time == 0.0; });
  earlier += static_cast<std::size_t>(points.end() - from_earlier);
  points.erase(from_earlier, points.end());
  return points;
}

// The radar's pose in the odometry frame (x, y, heading of its x axis).
struct PlanarPose {
  Eigen::Vector2d p_OR_O = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
};

PlanarPose radar_in_odom(const Eigen::Matrix4d& T_odom_camera, const Eigen::Matrix4d& T_camera_radar) {
  const Eigen::Matrix4d T_odom_radar = T_odom_camera * T_camera_radar;
  const Eigen::Vector3d axis_O = T_odom_radar.topLeftCorner<3, 3>() * Eigen::Vector3d::UnitX();
  return {T_odom_radar.topRightCorner<2, 1>(), std::atan2(axis_O.y(), axis_O.x())};
}

// What the poses of the frames beside one say: the path's curvature (rad/m) and whether the
// radar moved forward, where it moved at least kMinPath_m.
struct PathShape {
  bool known = false;
  double curvature_radpm = 0.0;
  double forward_m = 0.0;  // the displacement along the radar's x axis
  double path_m = 0.0;
};
constexpr double kMinPath_m = 0.2;

PathShape path_shape(const Dataset& dataset, const Frame& frame, const Eigen::Matrix4d& T_camera_radar) {
  const auto pose_of = [&](int number) -> std::optional<PlanarPose> {
    const auto it = std::lower_bound(dataset.frames.begin(), dataset.frames.end(), number,
                                     [](const Frame& f, int n) { return f.number < n; });
    if (it == dataset.frames.end() || it->number != number || it->pose.empty()) return std::nullopt;
    return radar_in_odom(read_odom_pose(it->pose), T_camera_radar);
  };
  std::optional<PlanarPose> before = pose_of(frame.number - 1), after = pose_of(frame.number + 1);
  const std::optional<PlanarPose> here = pose_of(frame.number);
  if (!before) before = here;
  if (!after) after = here;
  PathShape shape;
  if (!before || !after || !here) return shape;
  const Eigen::Vector2d step_O = after->p_OR_O - before->p_OR_O;
  shape.path_m = step_O.norm();
  if (shape.path_m < kMinPath_m) return shape;
  shape.known = true;
  shape.curvature_radpm = angle_difference_rad(after->yaw_rad, before->yaw_rad) / shape.path_m;
  shape.forward_m = step_O.dot(Eigen::Vector2d(std::cos(here->yaw_rad), std::sin(here->yaw_rad)));
  return shape;
}

RecordedTarget target_of(const RadarPoint& p, int k) {
  RecordedTarget t;
  t.t_s = static_cast<double>(k);
  t.cycle = k;
  t.sensor = 0;
  t.range_m = std::hypot(p.x_m, p.y_m);  // horizontal: the model is planar
  t.azimuth_rad = std::atan2(p.y_m, p.x_m);
  t.elevation_rad = std::atan2(p.z_m, t.range_m);
  t.range_rate_mps = p.v_r_mps;
  t.amplitude_db = p.rcs_dbsm;
  t.rcs_dbsm = p.rcs_dbsm;
  return t;
}

// A box's speed along its length axis from the compensated radial speeds of the points in it:
// v_r_compensated = s (cos yaw, sin yaw) . u, least squares over the points; none where the
// points' lines of sight are all (nearly) across the box's axis.
std::optional<double> box_speed_mps(const RadarBox& box, const Label& label, const std::vector<RadarPoint>& points) {
  const Eigen::Vector2d axis(std::cos(box.yaw_rad), std::sin(box.yaw_rad));
  double sum_cc = 0.0, sum_cv = 0.0;
  for (const RadarPoint& p : points) {
    const Eigen::Vector3d p_R(p.x_m, p.y_m, p.z_m);
    const Eigen::Vector3d d = p_R - box.p_RO_R;
    const double along = d.head<2>().dot(axis), across = d.x() * -axis.y() + d.y() * axis.x();
    if (std::abs(along) > 0.5 * label.length_m + kBoxMargin_m || std::abs(across) > 0.5 * label.width_m + kBoxMargin_m ||
        std::abs(d.z()) > 0.5 * label.height_m + kBoxMargin_m || p_R.norm() < 1e-3) {
      continue;
    }
    const Eigen::Vector3d u = p_R.normalized();
    const double c = axis.x() * u.x() + axis.y() * u.y();
    sum_cc += c * c;
    sum_cv += c * p.v_r_compensated_mps;
  }
  if (sum_cc < 0.25) return std::nullopt;  // less than one point seeing the axis within 60 deg
  return sum_cv / sum_cc;
}

struct Tally {
  std::map<std::string, int> kept, left_out;  // by model, by class
  std::map<std::string, int> parts_of_cyclists;  // rider and bicycle boxes inside a Cyclist box, by class
  std::size_t earlier_scan_points = 0, boxes_without_speed = 0, frames_without_velocity = 0, frames_without_path = 0;
  std::size_t backwards_frames = 0;
  double max_lateral_mps = 0.0, max_residual_mps = 0.0;
  std::vector<double> lateral_mps;
};

nlohmann::json ego_motion_source(const Tally& tally, std::size_t frames) {
  std::vector<double> lateral = tally.lateral_mps;
  std::sort(lateral.begin(), lateral.end());
  return {{"method", "speed: per frame the radar's velocity over the ground from its own points, v_r_compensated - "
                     "v_r = v_S . u (least squares over the frame's points; v_r_compensated is the dataset's, from "
                     "its odometry); yaw rate: the path's curvature from the odometry poses of the frames beside it "
                     "(odomToCamera through Tr_velo_to_cam), times that speed; the frames carry no clock, so the "
                     "poses give the path's shape but not its speed"},
          {"vehicle_frame", "the radar's own frame (x forward, y left): the sensor at the origin"},
          {"frames", frames},
          {"frames_without_velocity", tally.frames_without_velocity},
          {"frames_without_yaw_rate", tally.frames_without_path},
          {"frames_moving_backwards_by_the_poses", tally.backwards_frames},
          {"residual_rms_max_mps", tally.max_residual_mps},
          {"lateral_speed_median_abs_mps", lateral.empty() ? 0.0 : lateral[lateral.size() / 2]},
          {"lateral_speed_max_abs_mps", tally.max_lateral_mps},
          {"lateral_speed", "the radar's speed across its x axis is not modelled (an ego at the radar has none): a "
                            "stationary point's simulated radial speed is off by v_y sin(azimuth)"}};
}

std::string sensor_placeholder() {
  for (const EmbeddedFile& file : embedded_sensor_configs()) {
    if (file.name != "astyx_hires" && file.name != "astyx_hires.json") continue;
    nlohmann::ordered_json profile = nlohmann::ordered_json::parse(file.text);
    profile["name"] = "zf_frgen21_placeholder";
    profile["description"] =
        "A placeholder for the ZF FRGen21 3+1D radar of View-of-Delft, written by rcsim import --from vod: every value "
        "is the Astyx 6455 HiRes's (astyx_hires), an imaging radar of another maker, except that it has no Doppler "
        "interval (the FRGen21's radial speeds do not wrap at +-5.2 m/s) and no fitted stationary background. Nothing "
        "here is this radar's: derive its profile from your frames (rcsim profile derive REC --base astyx_hires).";
    profile["resolution"].erase("unambiguous_range_rate_mps");
    profile.erase("background");
    return profile.dump(2) + "\n";
  }
  throw std::logic_error("the built-in sensor astyx_hires is missing");
}

}  // namespace
}  // namespace vod

DatasetRecording import_vod(const fs::path& raw_dir, const DatasetImportOptions& options) {
  if (!options.mapping.empty()) throw InputError("--mapping", "", "maps the topics of an MCAP log (--from mcap)");
  if (!options.ego_log.empty()) {
    throw InputError("--ego-log", "",
                     "View-of-Delft frames are snapshots without a clock: no ego log can cover them (the speed comes from "
                     "each frame's v_r_compensated - v_r, the yaw rate from the poses)");
  }
  const vod::Dataset dataset = vod::find_dataset(raw_dir);
  const std::vector<vod::Frame> frames = vod::choose_frames(dataset, options.frames);

  DatasetRecording out;
  Recording& rec = out.recording;
  fs::path root = fs::absolute(raw_dir).lexically_normal();
  if (root.filename().empty()) root = root.parent_path();
  rec.name = root.filename().string() + (options.frames.empty() ? "" : " frames " + options.frames);
  rec.cycle_time_s = 1.0;
  rec.timeline = Timeline::snapshots;

  vod::Tally tally;
  std::vector<int> numbers;
  std::optional<Eigen::Matrix4d> T_camera_radar_first;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const vod::Frame& frame = frames[k];
    const int cycle = static_cast<int>(k);
    const double t_s = static_cast<double>(k);
    const Eigen::Matrix4d T_camera_radar = vod::read_kitti_extrinsic(frame.radar_calib);
    const Eigen::Matrix4d T_camera_lidar = vod::read_kitti_extrinsic(frame.lidar_calib);
    if (!T_camera_radar_first) T_camera_radar_first = T_camera_radar;
    const std::vector<vod::RadarPoint> points = vod::own_scan(vod::read_radar_file(frame.radar), tally.earlier_scan_points);

    // ego: the radar's velocity from its own points, the yaw rate from the path's curvature
    const vod::RadarVelocity velocity = vod::radar_velocity(points);
    EgoSample ego{t_s, 0.0, 0.0, 0.0, 0.0, 0.0};
    if (velocity.valid) {
      ego.speed_mps = velocity.v_S_S.x();
      tally.max_residual_mps = std::max(tally.max_residual_mps, velocity.residual_rms_mps);
      tally.lateral_mps.push_back(std::abs(velocity.v_S_S.y()));
      tally.max_lateral_mps = std::max(tally.max_lateral_mps, std::abs(velocity.v_S_S.y()));
    } else {
      ++tally.frames_without_velocity;
    }
    const vod::PathShape path = vod::path_shape(dataset, frame, T_camera_radar);
    if (path.known) {
      ego.yaw_rate_radps = path.curvature_radpm * ego.speed_mps;
      if (velocity.valid && std::abs(ego.speed_mps) > 0.5 && (path.forward_m > 0.0) != (ego.speed_mps > 0.0)) ++tally.backwards_frames;
    } else {
      ++tally.frames_without_path;
    }
    if (!(std::abs(ego.speed_mps) <= limits::kMaxSpeed_mps) || !(std::abs(ego.yaw_rate_radps) <= limits::kMaxYawRate_radps)) {
      throw InputError(frame.radar.string(), "", fmt::format("the ego motion read off its points ({} m/s, {} rad/s) exceeds the limits",
                                                             ego.speed_mps, ego.yaw_rate_radps));
    }
    rec.ego.push_back(ego);
    for (const vod::RadarPoint& p : points) rec.targets.push_back(vod::target_of(p, cycle));

    // boxes: each label of the frame an object of its own, in the radar (vehicle) frame
    const std::vector<vod::Label> labels = vod::read_labels(frame.labels);
    std::vector<vod::RadarBox> cyclists;
    for (const vod::Label& label : labels) {
      if (label.label_class == "Cyclist") cyclists.push_back(vod::box_in_radar_frame(label, T_camera_radar, T_camera_lidar));
    }
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const vod::Label& label = labels[i];
      const auto mapping = vod::class_mappings().find(label.label_class);
      if (mapping == vod::class_mappings().end() || std::string_view(mapping->second.model).empty()) {
        ++tally.left_out[label.label_class];
        continue;
      }
      const vod::RadarBox box = vod::box_in_radar_frame(label, T_camera_radar, T_camera_lidar);
      if ((label.label_class == "rider" || label.label_class == "bicycle") && vod::part_of_a_cyclist(box, cyclists)) {
        ++tally.parts_of_cyclists[label.label_class];
        continue;
      }
      if (box.p_RO_R.head<2>().cwiseAbs().maxCoeff() > limits::kMaxRange_m) {
        throw InputError(frame.labels.string(), fmt::format("line {}", label.line), "the box lies beyond the limit of 10 km from the radar");
      }
      const std::optional<double> speed = vod::box_speed_mps(box, label, points);
      if (!speed) ++tally.boxes_without_speed;
      ++tally.kept[mapping->second.model];
      RecordingObject object{fmt::format("f{:05}_{:02}", frame.number, i), mapping->second.model, label.length_m, label.width_m};
      object.attributes = {{"dataset_class", label.label_class}, {"occluded", label.occluded}, {"height_m", label.height_m},
                           {"z_m", box.p_RO_R.z()},              {"frame", frame.number},     {"speed_source", speed ? "points" : "none"}};
      rec.objects.push_back(std::move(object));
      rec.boxes.push_back({{t_s, box.p_RO_R.x(), box.p_RO_R.y(), wrap_angle_rad(box.yaw_rad), speed.value_or(0.0), 0}});
    }
    numbers.push_back(frame.number);
  }
  // The ego motion is measured (the dataset's compensation) where every frame gave it.
  rec.ego_motion_known = tally.frames_without_velocity == 0;

  rec.sensors.push_back({"radar", vod::kSensorFile, 0.0, 0.0, 0.0, ListLevel::detections, AmplitudeUnit::relative_db, std::nullopt});
  // The calibration gives the radar's pose to the camera, not to the road: the road under the boxes does.
  const std::optional<GroundPlaneFit> ground = fit_ground_plane(rec);
  if (ground) {
    rec.sensors.back().z_m = ground->z_m;
    rec.sensors.back().pitch_rad = ground->pitch_rad;
  }
  out.extra_files[vod::kSensorFile] = vod::sensor_placeholder();

  std::vector<std::string> models;
  const ModelLibrary library = ModelLibrary::builtin();
  for (const auto& [name, model] : library.models()) models.push_back(name);
  for (const auto& [name, count] : tally.left_out) {
    const auto mapping = vod::class_mappings().find(name);
    out.warnings.push_back(fmt::format("{} boxes of class {} left out: {} (the object models: {})", count, name,
                                       mapping != vod::class_mappings().end() ? mapping->second.why
                                                                              : "not a class View-of-Delft documents",
                                       fmt::join(models, ", ")));
  }
  for (const auto& [name, count] : tally.parts_of_cyclists) {
    out.warnings.push_back(fmt::format("{} boxes of class {} left out: parts of a Cyclist box (the same road user boxed "
                                       "again, within {} m of its centre)",
                                       count, name, vod::kCyclistPartReach_m));
  }
  if (tally.earlier_scan_points > 0) {
    out.warnings.push_back(fmt::format("{} points of earlier scans (time < 0: an accumulated radar_3_scans or radar_5_scans "
                                       "folder?) left out: a cycle is one scan",
                                       tally.earlier_scan_points));
  }
  if (tally.frames_without_velocity > 0) {
    out.warnings.push_back(fmt::format("{} of {} frames have too few points spread in azimuth to show the ego's speed: taken "
                                       "as standing, and ego_motion_known is false",
                                       tally.frames_without_velocity, frames.size()));
  }
  if (tally.backwards_frames > 0) {
    out.warnings.push_back(fmt::format("{} frames: the poses say the radar moved the other way than its Doppler says (is "
                                       "v_r positive approaching in these files?)",
                                       tally.backwards_frames));
  }
  if (tally.boxes_without_speed > 0) {
    out.warnings.push_back(fmt::format("{} boxes hold no point that sees their length axis: their speed is taken as 0",
                                       tally.boxes_without_speed));
  }
  out.warnings.push_back(fmt::format("the sensor profile {} beside the recording is a placeholder (astyx_hires's values): "
                                     "derive this radar's own with rcsim profile derive",
                                     vod::kSensorFile));

  rec.description = fmt::format(
      "View-of-Delft: {} frames of the ZF FRGen21 3+1D radar, one frame one cycle (snapshots); {} boxes of cars, {} of "
      "trucks, {} of pedestrians, {} of cyclists and {} of bicycles; the ego's speed from each frame's compensated Doppler",
      frames.size(), tally.kept["passenger_car"], tally.kept["truck_trailer"], tally.kept["pedestrian"], tally.kept["cyclist"],
      tally.kept["bicycle"]);
  rec.source = {
      {"dataset", "View-of-Delft (Palffy, Pool, Baratam, Kooij and Gavrila, Multi-class Road User Detection with 3+1D "
                  "Radar in the View-of-Delft Dataset, IEEE RA-L 2022)"},
      {"licence", vod::kLicence},
      {"importer", "rcsim import --from vod"},
      {"sequence", root.filename().string()},
      {"frames", numbers},
      {"timeline", "each cycle is one labelled frame (a snapshot), cycle k the k-th of source.frames; t_s = k and "
                   "cycle_time_s = 1 only order the frames, they are no times"},
      {"amplitude_db", "RCS, the radar's own estimate in dBsm (also in rcs_dbsm): not an SNR"},
      {"range_rate_mps", "v_r, the relative radial speed as measured (positive receding), not ego-compensated"},
      {"targets", "the frame's own scan (time 0); each point x y z in the radar frame: range_m and azimuth_rad in the "
                  "horizontal plane, elevation_rad = atan2(z, hypot(x, y))"},
      {"boxes", "lidar/training/label_2 (KITTI, camera frame): the bottom centre through Tr_velo_to_cam of the LiDAR's "
                "and the radar's calibration into the radar frame, the yaw -(rotation + pi/2) about the LiDAR's z "
                "(VoD's devkit), length l and width w; speed_mps along the box's length axis from the "
                "v_r_compensated of the points within 0.3 m of it (0 where none sees that axis); each object is one "
                "box of one frame (id fNNNNN_KK: frame, line index)"},
      {"ego_motion", vod::ego_motion_source(tally, frames.size())},
      {"mounting", ground ? describe(*ground)
                          : std::string("height and pitch unknown: fewer than 10 boxes, or no plane through their bottoms")}};
  return out;
}

}  // namespace rcsim::replay
