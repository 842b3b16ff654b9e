#include "common/quantile.hpp"
#include "replay/import/aimotive_importer.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>

#include "common/safe_text.hpp"
#include "common/angles.hpp"
#include "common/decibel.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "replay/import/annotation_smoothing.hpp"
#include "replay/import/doppler_ego_motion.hpp"
#include "replay/import/ego_log.hpp"
#include "replay/import/rigid_transform.hpp"

namespace rcsim::replay {

namespace fs = std::filesystem;

namespace aimotive {

namespace {

constexpr const char* kBoxDir = "dynamic/box/3d_body";
constexpr const char* kRadarDir = "sensor/radar";
constexpr const char* kCalibrationFile = "sensor/calibration/calibration.json";
constexpr const char* kSensorProfile = "aimotive_lrr";  // src/sensor/sensors/aimotive_lrr.json

// A value and its limit (schemas/limits.md), for the checks of what the import reads and derives.
struct Bound {
  const char* field;
  double value, limit;
  const char* unit;
};

// The first bound exceeded (NaN exceeds every one), if any: a copy, as the list is a temporary.
std::optional<Bound> first_exceeded(std::initializer_list<Bound> bounds) {
  for (const Bound& b : bounds) {
    if (!(std::abs(b.value) <= b.limit)) return b;
  }
  return std::nullopt;
}

std::string exceeded_message(const Bound& b) {
  return fmt::format("|{}| exceeds the limit of {} {}", b.value, b.limit, b.unit);
}

bool is_sequence(const fs::path& dir) {
  return fs::is_directory(dir / kBoxDir) && fs::is_directory(dir / kRadarDir) && fs::is_regular_file(dir / kCalibrationFile);
}

std::int64_t parse_timestamp_ns(const JsonField& root) {
  const auto found = root.json().find("Timestamp");
  if (found == root.json().end()) root.fail("Timestamp", "missing");
  const nlohmann::json& value = *found;
  std::int64_t ns = 0;
  if (value.is_number_integer()) return value.get<std::int64_t>();
  const std::string text = value.is_string() ? value.get<std::string>() : std::string();
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), ns);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || ns < 0) {
    root.fail("Timestamp", "must be a non-negative integer of nanoseconds");
  }
  return ns;
}

}  // namespace

fs::path find_sequence(const fs::path& raw_dir) {
  if (!fs::is_directory(raw_dir)) throw InputError(raw_dir.string(), "", "not a directory");
  if (is_sequence(raw_dir)) return raw_dir;
  std::vector<fs::path> found;
  for (auto it = fs::recursive_directory_iterator(raw_dir); it != fs::recursive_directory_iterator(); ++it) {
    if (it.depth() > 5) it.disable_recursion_pending();
    if (it->is_directory() && is_sequence(it->path())) {
      found.push_back(it->path());
      it.disable_recursion_pending();
    }
  }
  if (found.empty()) {
    throw InputError(raw_dir.string(), "",
                     fmt::format("no aiMotive sequence here (a directory with {}, {}/ and {})", kBoxDir, kRadarDir,
                                 kCalibrationFile));
  }
  if (found.size() > 1) {
    std::sort(found.begin(), found.end());
    throw InputError(raw_dir.string(), "",
                     fmt::format("{} sequences here (first {}): give one sequence directory, one recording each",
                                 found.size(), found.front().string()));
  }
  return found.front();
}

std::vector<RadarMount> read_radar_mounts(const fs::path& sequence) {
  const std::string path = (sequence / kCalibrationFile).string();
  const nlohmann::json json = parse_json_file(path);
  const JsonField root(json, path, "");
  std::vector<std::string> labels;
  for (const auto& entry : fs::directory_iterator(sequence / kRadarDir)) {
    if (entry.is_directory()) labels.push_back(entry.path().filename().string());
  }
  std::sort(labels.begin(), labels.end());
  if (labels.empty()) throw InputError((sequence / kRadarDir).string(), "", "no radar directories");
  std::vector<RadarMount> mounts;
  for (const std::string& label : labels) {
    const JsonField sensor = root.member(label);
    RadarMount mount;
    mount.label = label;
    mount.T_body_sensor = read_rigid_transform(sensor, "RT_body_from_sensor");
    const Eigen::Matrix4d& T = mount.T_body_sensor;
    mount.X_VS = {T(0, 3), T(1, 3), std::atan2(T(1, 0), T(0, 0))};
    if (std::abs(T(0, 3)) > limits::kMaxMountOffset_m || std::abs(T(1, 3)) > limits::kMaxMountOffset_m) {
      sensor.fail("RT_body_from_sensor", fmt::format("translation ({}, {}) m beyond ±{} m: is it in millimetres?", T(0, 3),
                                                     T(1, 3), limits::kMaxMountOffset_m));
    }
    mounts.push_back(mount);
  }
  return mounts;
}

std::vector<Keyframe> list_keyframes(const fs::path& sequence) {
  std::vector<Keyframe> frames;
  for (const auto& entry : fs::directory_iterator(sequence / kBoxDir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.rfind("frame_", 0) != 0) continue;
    Keyframe k;
    k.number = entry.path().stem().string().substr(6);
    k.box_file = entry.path();
    frames.push_back(k);
  }
  std::sort(frames.begin(), frames.end(), [](const Keyframe& a, const Keyframe& b) { return a.number < b.number; });
  if (frames.size() < 2) throw InputError((sequence / kBoxDir).string(), "", "fewer than two keyframes (frame_N.json)");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const nlohmann::json json = parse_json_file(frames[i].box_file.string());
    frames[i].timestamp_ns = parse_timestamp_ns(JsonField(json, frames[i].box_file.string(), ""));
    if (i > 0 && frames[i].timestamp_ns <= frames[i - 1].timestamp_ns) {
      throw InputError(frames[i].box_file.string(), "Timestamp",
                       "not after the previous keyframe's (" + frames[i - 1].box_file.filename().string() + ")");
    }
  }
  return frames;
}

std::vector<RadarDetection> read_radar_file(const fs::path& path) {
  if (!fs::is_regular_file(path)) throw InputError(path.string(), "", "missing: every keyframe needs every radar's file");
  const nlohmann::json json = parse_json_file(path.string());
  const JsonField root(json, path.string(), "");
  std::vector<RadarDetection> detections;
  for (const JsonField& t : root.array("targets")) {
    RadarDetection d{t.number("range"), t.number("azimuth"), t.number("elevation"), t.number("speed"),
                     t.number("rcs"), t.number("power"), t.number("noise")};
    if (d.range_m < 0.0) t.fail("range", "must not be negative");
    if (d.range_m > limits::kMaxRange_m) t.fail("range", fmt::format("exceeds the limit of {} m", limits::kMaxRange_m));
    if (std::abs(d.azimuth_rad) > kPi || std::abs(d.elevation_rad) > kPi / 2) t.fail("azimuth", "angles must be in radians");
    if (std::abs(d.speed_mps) > limits::kMaxSpeed_mps) t.fail("speed", fmt::format("exceeds the limit of {} m/s", limits::kMaxSpeed_mps));
    // The recording's amplitude is power - noise (planar_target): each level, and their difference,
    // within the limit a recording's reader holds amplitudes to (schemas/limits.md).
    for (const auto& [field, level_db] : {std::pair{"power", d.power_db}, std::pair{"noise", d.noise_db}}) {
      if (std::abs(level_db) > limits::kMaxLevel_dB) t.fail(field, fmt::format("exceeds the limit of {} dB", limits::kMaxLevel_dB));
    }
    // A radar cross-section in m^2: 0 or below has no level in dBsm (the sample drive's least is 0.087).
    if (!(d.rcs_m2 > 0.0)) t.fail("rcs", "must be positive: a radar cross-section in m^2");
    if (power_to_db(d.rcs_m2) > limits::kMaxLevel_dB) {
      t.fail("rcs", fmt::format("exceeds the limit of {} dBsm", limits::kMaxLevel_dB));
    }
    if (std::abs(d.power_db - d.noise_db) > limits::kMaxLevel_dB) {
      t.fail("noise", fmt::format("power - noise exceeds the limit of {} dB", limits::kMaxLevel_dB));
    }
    detections.push_back(d);
  }
  return detections;
}

RecordedTarget planar_target(const RadarDetection& d, const RadarMount& mount) {
  const double c = std::cos(d.elevation_rad);
  const Eigen::Vector4d p_S(d.range_m * c * std::cos(d.azimuth_rad), d.range_m * c * std::sin(d.azimuth_rad),
                            d.range_m * std::sin(d.elevation_rad), 1.0);
  const Eigen::Vector4d p_B = mount.T_body_sensor * p_S;
  const Vec2 p_ST_S = rotate(-mount.X_VS.yaw_rad, Vec2(p_B.x(), p_B.y()) - mount.X_VS.translation());
  RecordedTarget t;
  t.range_m = p_ST_S.norm();
  t.azimuth_rad = std::atan2(p_ST_S.y(), p_ST_S.x());
  t.range_rate_mps = d.speed_mps;
  t.amplitude_db = d.power_db - d.noise_db;
  t.snr_db = t.amplitude_db;
  t.rcs_dbsm = power_to_db(d.rcs_m2);  // 10 log10(sigma / 1 m^2); read_radar_file refuses sigma <= 0
  t.elevation_rad = d.elevation_rad;
  return t;
}

}  // namespace aimotive

namespace {

using aimotive::Keyframe;
using aimotive::RadarDetection;
using aimotive::RadarMount;

// The dataset's object types as object models; others are left out (with a warning).
const std::map<std::string, std::string>& model_of_type() {
  static const std::map<std::string, std::string> models{
      {"CAR", "passenger_car"}, {"VAN", "passenger_car"}, {"PICKUP", "passenger_car"},
      {"TRUCK", "truck_trailer"}, {"BUS", "truck_trailer"}};
  return models;
}

// "CAR 04" -> "car_04".
std::string object_id(std::string actor) {
  for (char& ch : actor) ch = ch == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return actor;
}

// One annotated box of one keyframe, as the dataset gives it: in the body (vehicle) frame.
struct BodyBox {
  std::string id, model;
  Pose2 X_VO;
  double length_m = 0.0, width_m = 0.0;
  Vec2 v_rel_V = Vec2::Zero();  // the box's velocity relative to the ego, body frame
};

// boxes[k]: the boxes of keyframe k that have an object model (the others counted in warnings).
std::vector<std::vector<BodyBox>> read_body_boxes(const std::vector<Keyframe>& frames, std::vector<std::string>& warnings) {
  std::vector<std::vector<BodyBox>> boxes(frames.size());
  std::map<std::string, std::string> model_of_id;
  std::map<std::string, int> skipped;  // type -> boxes left out
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string file = frames[k].box_file.string();
    const nlohmann::json json = parse_json_file(file);
    const JsonField root(json, file, "");
    std::map<std::string, std::string> actor_of_id;  // this keyframe's objects: one box each
    for (const JsonField& o : root.array("CapturedObjects")) {
      const std::string type = o.string("ObjectType");
      const auto model = model_of_type().find(type);
      if (model == model_of_type().end()) {
        ++skipped[type];
        continue;
      }
      BodyBox box;
      const std::string actor = o.string("ActorName");
      // The name becomes an object id in objects.csv, one row per line.
      if (const auto bad = find_control_character(actor)) o.fail("ActorName", "the name holds " + *bad);
      box.id = object_id(actor);
      if (const auto [earlier, added] = actor_of_id.emplace(box.id, actor); !added) {
        o.fail("ActorName", fmt::format("'{}' is object '{}', which this keyframe already has a box of ('{}')", actor, box.id,
                                        earlier->second));
      }
      box.model = model->second;
      const double qw = o.number("BoundingBox3D Orientation Quat W"), qx = o.number("BoundingBox3D Orientation Quat X"),
                   qy = o.number("BoundingBox3D Orientation Quat Y"), qz = o.number("BoundingBox3D Orientation Quat Z");
      box.X_VO = {o.number("BoundingBox3D Origin X"), o.number("BoundingBox3D Origin Y"),
                  std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))};
      box.length_m = o.number("BoundingBox3D Extent X");
      box.width_m = o.number("BoundingBox3D Extent Y");
      if (!(box.length_m > 0.0) || !(box.width_m > 0.0)) o.fail("BoundingBox3D Extent X", "box extents must be positive");
      box.v_rel_V = {o.number("Relative Velocity X"), o.number("Relative Velocity Y")};
      // A box within a radar's reach, of a vehicle's size and speed.
      if (const auto b = aimotive::first_exceeded({{"BoundingBox3D Origin X", box.X_VO.x_m, limits::kMaxRange_m, "m"},
                                                     {"BoundingBox3D Origin Y", box.X_VO.y_m, limits::kMaxRange_m, "m"},
                                                     {"BoundingBox3D Extent X", box.length_m, limits::kMaxSize_m, "m"},
                                                     {"BoundingBox3D Extent Y", box.width_m, limits::kMaxSize_m, "m"},
                                                     {"Relative Velocity X", box.v_rel_V.x(), limits::kMaxSpeed_mps, "m/s"},
                                                     {"Relative Velocity Y", box.v_rel_V.y(), limits::kMaxSpeed_mps, "m/s"}})) {
        o.fail(b->field, aimotive::exceeded_message(*b));
      }
      const auto [known, added] = model_of_id.emplace(box.id, box.model);
      if (!added && known->second != box.model) {
        o.fail("ObjectType", "'" + type + "' for " + box.id + ", which earlier keyframes call a " + known->second);
      }
      boxes[k].push_back(std::move(box));
    }
  }
  for (const auto& [type, count] : skipped) {
    warnings.push_back(fmt::format("{} boxes of type {} left out: no object model for it", count, type));
  }
  return boxes;
}

// The ego's yaw rate from the annotated vehicles' headings in the body frame: vehicles follow the
// road, so their headings seen from the ego drift by minus the ego's yaw rate. Per object the
// heading's slope by local quadratic regression; per keyframe the median over the objects.
// Empty where fewer than two objects are annotated for `min_cycles` keyframes or more.
std::vector<double> yaw_rate_from_box_headings(const std::vector<std::vector<BodyBox>>& boxes,
                                               const std::vector<double>& t_s, double half_window_s) {
  constexpr std::size_t kMinCycles = 5;
  std::map<std::string, std::vector<std::pair<std::size_t, double>>> headings;  // id -> (keyframe, yaw_VO)
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    for (const BodyBox& b : boxes[k]) headings[b.id].emplace_back(k, b.X_VO.yaw_rad);
  }
  std::vector<std::vector<double>> slopes(boxes.size());
  for (const auto& [id, series] : headings) {
    if (series.size() < kMinCycles) continue;
    std::vector<double> t, yaw;
    for (const auto& [k, yaw_rad] : series) {
      t.push_back(t_s[k]);
      // Unwrapped against the previous sample, so that a heading near pi does not jump.
      yaw.push_back(yaw.empty() ? yaw_rad : yaw.back() + angle_difference_rad(yaw_rad, yaw.back()));
    }
    const auto fits = smooth_local_quadratic(t, yaw, half_window_s);
    for (std::size_t i = 0; i < series.size(); ++i) slopes[series[i].first].push_back(fits[i].slope_per_s);
  }
  std::vector<double> yaw_rate_radps(boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    if (slopes[k].size() < 2) return {};
    yaw_rate_radps[k] = 0.0 - median(slopes[k]);  // never -0
  }
  return yaw_rate_radps;
}

// The boxes into the world through the ego pose of their keyframe; sizes the median over keyframes.
void add_world_boxes(const std::vector<std::vector<BodyBox>>& boxes, const std::vector<double>& t_s, Recording& rec) {
  std::map<std::string, std::size_t> index;  // object id -> position in rec.objects
  std::map<std::string, std::vector<double>> lengths, widths;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const EgoSample& ego = rec.ego[k];
    const Pose2 X_WV{ego.x_m, ego.y_m, ego.yaw_rad};
    for (const BodyBox& b : boxes[k]) {
      const auto [it, added] = index.emplace(b.id, rec.objects.size());
      if (added) {
        rec.objects.push_back({b.id, b.model, 0.0, 0.0});
        rec.boxes.emplace_back();
      }
      // The box's own velocity: the ego's at that point (v + w x p) plus the relative one.
      const Vec2 p_VO_V = b.X_VO.translation();
      const Vec2 v_VO_V = Vec2(ego.speed_mps, 0.0) + ego.yaw_rate_radps * Vec2(-p_VO_V.y(), p_VO_V.x()) + b.v_rel_V;
      const Pose2 X_WO = compose(X_WV, b.X_VO);
      rec.boxes[it->second].push_back({t_s[k], X_WO.x_m, X_WO.y_m, X_WO.yaw_rad,
                                       speed_along_heading_mps(v_VO_V, b.X_VO.yaw_rad), 0});
      lengths[b.id].push_back(b.length_m);
      widths[b.id].push_back(b.width_m);
    }
  }
  for (RecordingObject& object : rec.objects) {
    object.length_m = median(lengths[object.id]);
    object.width_m = median(widths[object.id]);
  }
}

}  // namespace

namespace {

// A recording has one row per sensor cycle (schemas/recording.md): keyframes at most 1.5 cycle
// times apart, as `rcsim replay` reads ego.csv, and within the limits of a cycle time and a span.
void check_keyframe_spacing(const std::vector<Keyframe>& frames, const std::vector<double>& steps_s, double cycle_time_s) {
  if (cycle_time_s > limits::kMaxCycleTime_s) {
    throw InputError(frames[1].box_file.string(), "Timestamp",
                     fmt::format("keyframes {} s apart (median): beyond the limit of a cycle time, {} s", cycle_time_s,
                                 limits::kMaxCycleTime_s));
  }
  double span_s = 0.0;
  for (std::size_t k = 0; k < steps_s.size(); ++k) {
    span_s += steps_s[k];
    if (steps_s[k] > 1.5 * cycle_time_s) {
      throw InputError(frames[k + 1].box_file.string(), "Timestamp",
                       fmt::format("{:.6f} s after the previous keyframe, more than 1.5 x the median spacing of {:.6f} "
                                   "s: a keyframe is missing (a recording has one row per cycle)",
                                   steps_s[k], cycle_time_s));
    }
    if (span_s > limits::kMaxTime_s) {
      throw InputError(frames[k + 1].box_file.string(), "Timestamp",
                       fmt::format("{} s after the first keyframe: beyond the limit of {} s", span_s, limits::kMaxTime_s));
    }
  }
}

// What the import derived, held to the limits `rcsim replay` holds the written recording to
// (schemas/limits.md): the ego motion estimated from the Doppler (or interpolated from --ego-log)
// and the boxes moved into the world. Named by the keyframe they come from.
void check_derived_limits(const Recording& rec, const std::vector<Keyframe>& frames, const fs::path& sequence) {
  using aimotive::Bound;
  const auto check = [](const std::string& file, std::initializer_list<Bound> bounds) {
    if (const auto b = aimotive::first_exceeded(bounds)) throw InputError(file, b->field, aimotive::exceeded_message(*b));
  };
  for (std::size_t k = 0; k < rec.ego.size() && k < frames.size(); ++k) {
    const EgoSample& e = rec.ego[k];
    check((sequence / "sensor/radar").string() + " at keyframe " + frames[k].number + " (the ego motion)",
          {Bound{"ego x_m", e.x_m, limits::kMaxCoordinate_m, "m"}, Bound{"ego y_m", e.y_m, limits::kMaxCoordinate_m, "m"},
           Bound{"ego yaw_rad", e.yaw_rad, limits::kMaxUnwrappedYaw_rad, "rad"},
           Bound{"ego speed_mps", e.speed_mps, limits::kMaxSpeed_mps, "m/s"},
           Bound{"ego yaw_rate_radps", e.yaw_rate_radps, limits::kMaxYawRate_radps, "rad/s"}});
  }
  for (std::size_t o = 0; o < rec.objects.size(); ++o) {
    for (const AnnotatedBox& b : rec.boxes[o]) {
      const auto k = static_cast<std::size_t>(std::lower_bound(rec.ego.begin(), rec.ego.end(), b.t_s,
                                                               [](const EgoSample& e, double t) { return e.t_s < t; }) -
                                              rec.ego.begin());
      check(frames[std::min(k, frames.size() - 1)].box_file.string() + " (" + rec.objects[o].id + " in the world)",
            {Bound{"x_m", b.x_m, limits::kMaxCoordinate_m, "m"}, Bound{"y_m", b.y_m, limits::kMaxCoordinate_m, "m"},
             Bound{"speed_mps", b.speed_mps, limits::kMaxSpeed_mps, "m/s"}});
    }
  }
}

// sensor/radar/LABEL/LABEL_N.json: one radar's detections at keyframe N.
fs::path radar_file(const fs::path& sequence, const RadarMount& mount, const Keyframe& frame) {
  return sequence / "sensor/radar" / mount.label / (mount.label + "_" + frame.number + ".json");
}

// The ego log: the user's (--ego-log), interpolated to the keyframes, with the Doppler estimate
// reported beside it; else the estimate. A dataset ego file whose layout is not published is
// named in a warning, not guessed at.
nlohmann::json choose_ego(const fs::path& sequence, const DatasetImportOptions& options, const std::vector<double>& t_s,
                          DopplerEgoTrack& estimate, DatasetRecording& out) {
  if (options.ego_log.empty()) {
    for (const auto& entry : fs::directory_iterator(sequence / "sensor", fs::directory_options::skip_permission_denied)) {
      if (entry.path().filename() == "gnssins") {
        out.warnings.push_back(fmt::format("{} exists, but the layout of the aiMotive ego files is not published: the ego "
                                           "motion is estimated from the Doppler instead; convert the log to ego.csv's "
                                           "columns and give it with --ego-log",
                                           entry.path().string()));
      }
    }
    if (estimate.samples.empty()) {
      throw InputError((sequence / "sensor/radar").string(), "",
                       "no cycle has enough stationary targets to estimate the ego motion from their Doppler");
    }
    out.recording.ego = std::move(estimate.samples);
    return estimate.report;
  }
  out.recording.ego = ego_at_times(read_ego_log(options.ego_log), t_s, options.ego_log);
  nlohmann::json report = {{"method", "ego log given with --ego-log, interpolated linearly to the keyframes"},
                           {"file", fs::absolute(options.ego_log).lexically_normal().string()}};
  if (!estimate.samples.empty()) {
    report["doppler_check"] = ego_difference_report(out.recording.ego, estimate.samples);
    report["doppler_estimate"] = estimate.report;
  }
  return report;
}

}  // namespace

DatasetRecording import_aimotive(const fs::path& raw_dir, const DatasetImportOptions& options) {
  if (!options.mapping.empty()) throw InputError("--mapping", "", "maps the topics of an MCAP log (--from mcap)");
  if (!options.frames.empty()) {
    throw InputError("--frames", "",
                     "an aiMotive sequence is one drive and is imported whole: --frames chooses frames of a dataset of "
                     "single frames (--from astyx, vod)");
  }
  const fs::path sequence = aimotive::find_sequence(raw_dir);
  const std::vector<RadarMount> mounts = aimotive::read_radar_mounts(sequence);
  const std::vector<Keyframe> frames = aimotive::list_keyframes(sequence);
  DatasetRecording out;
  Recording& rec = out.recording;
  rec.name = sequence.filename().string();

  // detections[k][s]: radar s at keyframe k.
  std::vector<std::vector<std::vector<RadarDetection>>> detections(frames.size());
  std::vector<double> t_s(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    t_s[k] = 1e-9 * static_cast<double>(frames[k].timestamp_ns - frames.front().timestamp_ns);
    for (const RadarMount& m : mounts) {
      detections[k].push_back(aimotive::read_radar_file(radar_file(sequence, m, frames[k])));
    }
  }
  std::vector<double> steps_s;
  for (std::size_t k = 1; k < t_s.size(); ++k) steps_s.push_back(t_s[k] - t_s[k - 1]);
  rec.cycle_time_s = median(steps_s);
  check_keyframe_spacing(frames, steps_s, rec.cycle_time_s);

  // The ego motion from the stationary world's Doppler.
  std::vector<std::vector<std::vector<DopplerTarget>>> doppler(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    for (const auto& radar : detections[k]) {
      auto& list = doppler[k].emplace_back();
      for (const RadarDetection& d : radar) list.push_back({d.azimuth_rad, d.elevation_rad, d.speed_mps});
    }
  }
  std::vector<Pose2> X_VS;
  std::vector<std::string> labels;
  for (const RadarMount& m : mounts) X_VS.push_back(m.X_VS), labels.push_back(m.label);
  // The boxes first: their heading drift gives the yaw rate (the Doppler one is only reported).
  const std::vector<std::vector<BodyBox>> boxes = read_body_boxes(frames, out.warnings);
  const std::vector<double> yaw_rate_radps = yaw_rate_from_box_headings(boxes, t_s, 0.5);
  DopplerEgoTrack ego = ego_track_from_doppler(t_s, doppler, X_VS, labels,
                                               yaw_rate_radps.empty() ? nullptr : &yaw_rate_radps);
  out.warnings.insert(out.warnings.end(), ego.warnings.begin(), ego.warnings.end());
  const nlohmann::json ego_report = choose_ego(sequence, options, t_s, ego, out);

  for (std::size_t s = 0; s < mounts.size(); ++s) {
    // The built-in profile derived from these radars (docs/sensor-profiles.md).
    rec.sensors.push_back({mounts[s].label, aimotive::kSensorProfile, mounts[s].X_VS.x_m, mounts[s].X_VS.y_m,
                           mounts[s].X_VS.yaw_rad, ListLevel::detections});
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    for (std::size_t s = 0; s < mounts.size(); ++s) {
      for (const RadarDetection& d : detections[k][s]) {
        RecordedTarget t = aimotive::planar_target(d, mounts[s]);
        if (!(t.range_m <= limits::kMaxRange_m)) {  // a calibration matrix that scales can push a range beyond
          throw InputError(radar_file(sequence, mounts[s], frames[k]).string(), "range",
                           fmt::format("{} m in the mount's plane exceeds the limit of {} m", t.range_m, limits::kMaxRange_m));
        }
        t.t_s = t_s[k];
        t.cycle = static_cast<int>(k);
        t.sensor = static_cast<int>(s);
        rec.targets.push_back(t);
      }
    }
  }
  add_world_boxes(boxes, t_s, rec);
  check_derived_limits(rec, frames, sequence);

  rec.description = fmt::format(
      "aiMotive Multimodal Dataset sequence {}: {} keyframes at {:.1f} Hz, radars {}, {} annotated objects; "
      "{}",
      rec.name, frames.size(), 1.0 / rec.cycle_time_s, fmt::join(labels, " and "), rec.objects.size(),
      options.ego_log.empty() ? "ego motion estimated from the radars' Doppler (no ego log)"
                              : "ego motion from the ego log given with --ego-log");
  rec.source = {{"dataset", "aiMotive Multimodal Dataset (Matuszka et al. 2022, arXiv:2211.09445)"},
                {"licence", "CC BY-NC-SA 4.0"},
                {"importer", "rcsim import --from aimotive"},
                {"sequence", rec.name},
                {"first_timestamp_ns", frames.front().timestamp_ns},
                {"amplitude_db", "power - noise (SNR) of each detection"},
                {"ego_motion", ego_report},
                // Where the radars' own frame times are not (schemas/recording.md, version 4).
                {"sensor_clocks",
                 {{"method", "keyframe: the radar files carry no time stamp of their own (one file per keyframe), so every "
                             "frame is stamped with its keyframe's time; the radars run at about 18 Hz, unsynchronised, so a "
                             "frame's true time lies up to half a radar period from it. rcsim import --sensor-clocks "
                             "estimated times each radar's own clock by the static world's shift"}}}};
  return out;
}

}  // namespace rcsim::replay
