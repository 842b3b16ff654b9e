#include "replay/import/astyx_importer.hpp"
#include "replay/import/ground_plane.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/safe_text.hpp"
#include "common/text_file.hpp"
#include "model/model_library.hpp"
#include "replay/import/doppler_ego_motion.hpp"
#include "replay/import/rigid_transform.hpp"

namespace rcsim::replay {

namespace fs = std::filesystem;

namespace astyx {

namespace {

// The files that list a dataset's frames: the HiRes2019 set's and the demo's.
constexpr const char* kListings[] = {"dataset.json", "dataset_info.json"};
// The radars of the dataset: each names its files' folder and its calibration entry.
constexpr const char* kRadars[] = {"radar_6455", "radar_hires1"};
constexpr const char* kRadarHeader[] = {"X", "Y", "Z", "V_r", "Mag"};
constexpr std::size_t kRadarColumns = std::size(kRadarHeader);
// The largest `data` key read as a frame number (the whole dataset has 546 frames).
constexpr long long kMaxFrameKey = 1'000'000'000;

std::optional<fs::path> listing_in(const fs::path& dir) {
  for (const char* name : kListings) {
    if (fs::is_regular_file(dir / name)) return dir / name;
  }
  return std::nullopt;
}

// The Astyx datasets directly below `dir` (the parent a user may give by mistake).
std::vector<fs::path> datasets_below(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ignored)) {
    if (entry.is_directory(ignored) && listing_in(entry.path())) found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string quoted_paths(const std::vector<fs::path>& paths) {
  std::vector<std::string> names;
  for (const fs::path& p : paths) names.push_back(p.string());
  return fmt::format("{}", fmt::join(names, " or "));
}

// A file a listing names: a path relative to the dataset directory that stays inside it, also
// after symbolic links (issue 51: a link inside the dataset led to /etc/passwd, whose first line
// the refusal of its header printed). `real_dir` is the dataset directory's canonical path.
fs::path dataset_file(const JsonField& entry, std::string_view key, const fs::path& dir, const fs::path& real_dir) {
  const fs::path relative = entry.string(key);
  if (relative.is_absolute()) entry.fail(key, "must be a path relative to the dataset directory");
  for (const fs::path& part : relative) {
    if (part == "..") entry.fail(key, "must not leave the dataset directory ('..')");
  }
  const fs::path path = dir / relative;
  std::error_code error;
  const fs::path real = fs::weakly_canonical(path, error);
  if (!error && !real_dir.empty()) {
    const auto [left, unused] = std::mismatch(real_dir.begin(), real_dir.end(), real.begin(), real.end());
    if (left != real_dir.end()) {
      entry.fail(key, fmt::format("leads out of the dataset directory through a symbolic link (to {}): a dataset's "
                                  "files are inside it", real.string()));
    }
  }
  return path;
}

// A file a frame needs, there and a regular file (issue 51: a FIFO was called "missing").
void require_regular_file(const fs::path& file, const char* missing) {
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (!fs::exists(status)) throw InputError(file.string(), "", fmt::format("missing: {}", missing));
  if (!fs::is_regular_file(status)) {
    throw InputError(file.string(), "", "not a regular file (a directory, FIFO, device or socket): a dataset's files are");
  }
}

int frame_key(const JsonField& data, const std::string& key) {
  long long number = -1;
  const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), number);
  if (key.empty() || error != std::errc() || end != key.data() + key.size() || number < 0 || number > kMaxFrameKey) {
    data.fail(key, fmt::format("a frame's key must be its number (0 to {})", kMaxFrameKey));
  }
  return static_cast<int>(number);
}

// "0-399", "0-4,8": the frame numbers as ranges, for messages and descriptions.
std::string as_ranges(const std::vector<int>& numbers) {
  std::string text;
  for (std::size_t i = 0; i < numbers.size();) {
    std::size_t j = i;
    while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
    if (!text.empty()) text.push_back(',');
    text.append(j == i ? fmt::format("{}", numbers[i]) : fmt::format("{}-{}", numbers[i], numbers[j]));
    i = j + 1;
  }
  return text;
}

std::vector<int> numbers_of(const std::vector<Frame>& frames) {
  std::vector<int> numbers;
  for (const Frame& f : frames) numbers.push_back(f.number);
  return numbers;
}

// A number of a radar file's row: decimal and finite.
double row_number(std::string_view text, const std::string& file, int line, std::string_view column) {
  return finite_number_field(text, file, fmt::format("line {}, column '{}'", line, column));
}

bool is_blank(std::string_view line) { return line.find_first_not_of(" \t") == std::string_view::npos; }

// A fixed-size array of finite numbers (center3d, dimension3d, orientation_quat).
std::vector<double> numbers_array(const JsonField& field, std::string_view key, std::size_t size, const char* meaning) {
  const std::vector<JsonField> items = field.array(key);
  if (items.size() != size) field.fail(key, fmt::format("must hold {} numbers ({}), got {}", size, meaning, items.size()));
  std::vector<double> values;
  for (std::size_t i = 0; i < size; ++i) {
    const nlohmann::json& v = items[i].json();
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      field.fail(key, fmt::format("element {} must be a finite number ({})", i, meaning));
    }
    values.push_back(v.get<double>());
  }
  return values;
}

// The radar's mounting in the reference frame (the vehicle frame of the recording).
struct Mount {
  Eigen::Matrix4d T_VS = Eigen::Matrix4d::Identity();
  Pose2 X_VS;
};

Mount read_mount(const fs::path& file, const std::string& radar) {
  const std::string path = file.string();
  require_regular_file(file, "every frame needs its calibration file");
  const nlohmann::json json = parse_json_file(path);
  const JsonField root(json, path, "");
  for (const JsonField& sensor : root.array("sensors")) {
    if (!sensor.has("sensor_uid") || !sensor.json().at("sensor_uid").is_string() ||
        sensor.json().at("sensor_uid").get<std::string>() != radar) {
      continue;
    }
    Mount mount;
    mount.T_VS = read_rigid_transform(sensor.member("calib_data"), "T_to_ref_COS");
    const Eigen::Matrix4d& T = mount.T_VS;
    if (std::abs(T(0, 3)) > limits::kMaxMountOffset_m || std::abs(T(1, 3)) > limits::kMaxMountOffset_m) {
      sensor.fail("calib_data.T_to_ref_COS", fmt::format("translation ({}, {}) m beyond ±{} m: is it in millimetres?",
                                                          T(0, 3), T(1, 3), limits::kMaxMountOffset_m));
    }
    mount.X_VS = {T(0, 3), T(1, 3), std::atan2(T(1, 0), T(0, 0))};
    return mount;
  }
  root.fail("sensors", fmt::format("no sensor with sensor_uid \"{}\" (the radar)", radar));
}

// JSON text with the bare NaN, Infinity and -Infinity that the dataset's CAN files hold (Python's
// json writer) as null, so that a strict parser reads it; a field read as a number then refuses
// null by name. Strings are left as they are.
std::string nan_as_null(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 16);
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') in_string = true;
    bool replaced = false;
    for (const std::string_view word : {"-Infinity", "Infinity", "NaN"}) {
      if (text.substr(i, word.size()) == word) {
        out += "null";
        i += word.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

struct EgoAtFrame {
  double speed_mps = 0.0, yaw_rate_radps = 0.0;
};

EgoAtFrame read_canbus(const fs::path& file) {
  const std::string path = file.string();
  require_regular_file(file, "the dataset lists CAN data for this frame");
  const nlohmann::json json = parse_json_text(nan_as_null(read_text_file(file)), path);
  const JsonField root(json, path, "");
  // vehicle_speed in km/h; YAW_RATE in deg/s, taken as counter-clockwise positive (ISO 8855, as
  // ego.csv): the dataset does not say (docs/importers.md).
  const EgoAtFrame ego{root.number("vehicle_speed") / 3.6, deg_to_rad(root.number("YAW_RATE"))};
  if (!(std::abs(ego.speed_mps) <= limits::kMaxSpeed_mps)) {
    root.fail("vehicle_speed", fmt::format("{} m/s exceeds the limit of {} m/s", ego.speed_mps, limits::kMaxSpeed_mps));
  }
  if (!(std::abs(ego.yaw_rate_radps) <= limits::kMaxYawRate_radps)) {
    root.fail("YAW_RATE",
              fmt::format("{} rad/s exceeds the limit of {} rad/s", ego.yaw_rate_radps, limits::kMaxYawRate_radps));
  }
  return ego;
}

// The dataset's classes as object models; the others are left out with a warning.
const std::map<std::string, std::string, std::less<>>& model_of_class() {
  static const std::map<std::string, std::string, std::less<>> models{
      {"Car", "passenger_car"},        {"Truck", "truck_trailer"},         {"Bus", "truck_trailer"},
      {"Trailer", "truck_trailer"},    {"Towed Object", "truck_trailer"},  {"Other Vehicle", "truck_trailer"},
      {"Person", "pedestrian"},        {"Person with Object", "pedestrian"}, {"Cyclist", "cyclist"}};
  return models;
}

// The dataset's classes without an object model: riders of motorcycles.
bool is_motorcyclist(std::string_view name) { return name == "Motorcyclist"; }

// One labelled box of a frame, in the radar's reference frame.
struct Box {
  std::string id, dataset_class, model;  // model empty: left out
  Pose2 X_VO;
  double length_m = 0.0, width_m = 0.0, height_m = 0.0, z_m = 0.0;
  nlohmann::json occlusion, label_certainty;  // numbers, as the file gives them (whole numbers stay whole)
};

struct Labels {
  double frame_index = 0.0;
  std::vector<Box> boxes;
};

Labels read_labels(const Frame& frame) {
  const std::string path = frame.groundtruth.string();
  require_regular_file(frame.groundtruth, "every frame needs its labels");
  const nlohmann::json json = parse_json_file(path);
  const JsonField root(json, path, "");
  Labels labels;
  labels.frame_index = root.number("frame_index");
  if (labels.frame_index < 0.0 || labels.frame_index != std::floor(labels.frame_index) || labels.frame_index > kMaxFrameKey) {
    root.fail("frame_index", "must be a whole number >= 0: the frame's index in the original recording");
  }
  const std::vector<JsonField> objects = root.array("objects");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const JsonField& o = objects[i];
    Box box;
    box.dataset_class = o.string("classname");
    if (const auto bad = find_control_character(box.dataset_class)) o.fail("classname", "the name holds " + *bad);
    if (box.dataset_class.size() > 64) o.fail("classname", "longer than 64 bytes: not a class name");
    std::string name = box.dataset_class;
    std::replace(name.begin(), name.end(), '_', ' ');  // the demo writes Towed_Object, Person_with_Object
    if (const auto model = model_of_class().find(name); model != model_of_class().end()) box.model = model->second;
    box.id = fmt::format("f{:06}_{:02}", frame.number, i);
    const std::vector<double> c = numbers_array(o, "center3d", 3, "x, y, z in m");
    const std::vector<double> d = numbers_array(o, "dimension3d", 3, "length, width, height in m");
    const std::vector<double> q = numbers_array(o, "orientation_quat", 4, "w, x, y, z");
    for (std::size_t k = 0; k < 3; ++k) {
      if (!(std::abs(c[k]) <= limits::kMaxRange_m)) {
        o.fail("center3d", fmt::format("|{}| exceeds the limit of {} m", c[k], limits::kMaxRange_m));
      }
      if (!(d[k] > 0.0 && d[k] <= limits::kMaxSize_m)) {
        o.fail("dimension3d", fmt::format("{} m: a box's length, width and height lie in (0, {}] m", d[k], limits::kMaxSize_m));
      }
    }
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(norm > 1e-6) || !std::isfinite(norm)) o.fail("orientation_quat", "has zero norm: no orientation");
    box.X_VO = {c[0], c[1], yaw_of_quaternion_rad(q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm)};
    box.length_m = d[0];
    box.width_m = d[1];
    box.height_m = d[2];
    box.z_m = c[2];
    (void)o.number("occlusion");  // refuses what is no finite number, by name
    (void)o.number("label_certainty");
    box.occlusion = o.json().at("occlusion");
    box.label_certainty = o.json().at("label_certainty");
    labels.boxes.push_back(std::move(box));
  }
  return labels;
}

}  // namespace

Dataset find_dataset(const fs::path& raw_dir) {
  if (!fs::exists(raw_dir)) {
    const fs::path parent = raw_dir.parent_path().empty() ? fs::path(".") : raw_dir.parent_path();
    const std::vector<fs::path> near = fs::is_directory(parent) ? datasets_below(parent) : std::vector<fs::path>{};
    throw InputError(raw_dir.string(), "",
                     near.empty() ? std::string("no such directory")
                                  : fmt::format("no such directory; the Astyx datasets beside it: {}", quoted_paths(near)));
  }
  if (!fs::is_directory(raw_dir)) throw InputError(raw_dir.string(), "", "not a directory");
  Dataset dataset;
  dataset.dir = raw_dir;
  const std::optional<fs::path> listing = listing_in(raw_dir);
  if (!listing) {
    const std::vector<fs::path> below = datasets_below(raw_dir);
    if (!below.empty()) {
      throw InputError(raw_dir.string(), "",
                       fmt::format("holds {} Astyx dataset{}: give one of them as RAW_DIR, {} (one recording each)",
                                   below.size(), below.size() == 1 ? "" : "s", quoted_paths(below)));
    }
    fs::path absolute = fs::absolute(raw_dir).lexically_normal();
    if (absolute.filename().empty()) absolute = absolute.parent_path();  // "DIR/": the trailing separator
    if (const fs::path parent = absolute.parent_path(); listing_in(parent)) {
      throw InputError(raw_dir.string(), "",
                       fmt::format("a folder of the Astyx dataset {}: give the dataset directory itself", parent.string()));
    }
    throw InputError(raw_dir.string(), "",
                     "no Astyx dataset here (a directory with dataset.json or dataset_info.json beside radar_6455/ or "
                     "radar_hires1/, groundtruth_obj3d/ and calibration/)");
  }
  dataset.listing = *listing;
  const std::string file = listing->string();
  const nlohmann::json json = parse_json_file(file);
  const JsonField root(json, file, "");
  const JsonField data = root.member("data");
  std::error_code no_real_dir;
  const fs::path real_dir = fs::canonical(raw_dir, no_real_dir);
  for (const auto& [key, unused] : data.json().items()) {
    const JsonField entry = data.member(key);
    Frame frame;
    frame.number = frame_key(data, key);
    std::string radar;
    for (const char* r : kRadars) {
      if (entry.has(r)) radar = r;
    }
    if (radar.empty()) entry.fail(fmt::format("no radar file ({})", fmt::join(kRadars, " or ")));
    if (dataset.radar.empty()) dataset.radar = radar;
    if (radar != dataset.radar) {
      entry.fail(radar, fmt::format("frames of two radars ({} and {}): one dataset, one radar", dataset.radar, radar));
    }
    frame.radar = dataset_file(entry, radar, raw_dir, real_dir);
    frame.groundtruth = dataset_file(entry, "groundtruth_obj3d", raw_dir, real_dir);
    frame.calibration = dataset_file(entry, "calibration", raw_dir, real_dir);
    if (entry.has("canbus")) frame.canbus = dataset_file(entry, "canbus", raw_dir, real_dir);
    dataset.frames.push_back(std::move(frame));
  }
  if (dataset.frames.empty()) data.fail("lists no frames");
  std::sort(dataset.frames.begin(), dataset.frames.end(), [](const Frame& a, const Frame& b) { return a.number < b.number; });
  for (std::size_t i = 1; i < dataset.frames.size(); ++i) {
    if (dataset.frames[i].number == dataset.frames[i - 1].number) {
      data.fail(fmt::format("frame {} is listed twice (keys with leading zeros?)", dataset.frames[i].number));
    }
  }
  return dataset;
}

std::vector<Frame> choose_frames(const Dataset& dataset, const std::string& frames) {
  if (frames.empty()) return dataset.frames;
  const auto find = [&](long long number) {
    const auto it = std::lower_bound(dataset.frames.begin(), dataset.frames.end(), number,
                                     [](const Frame& f, long long n) { return f.number < n; });
    return it != dataset.frames.end() && it->number == number ? &*it : nullptr;
  };
  // Ranges that overlap are refused before any is expanded (issue 51: '0-999,0-999,...' was
  // copied 21,000 times, 6.8 GB, before the duplicates were found); then every number expanded
  // is a distinct frame of the dataset or refused at once, so the list costs what it holds.
  std::vector<FrameRange> ranges = parse_frame_list(frames);
  std::sort(ranges.begin(), ranges.end(), [](const FrameRange& a, const FrameRange& b) { return a.first < b.first; });
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    if (ranges[i].first <= ranges[i - 1].last) {
      const auto text = [](const FrameRange& r) { return r.first == r.last ? fmt::format("{}", r.first) : fmt::format("{}-{}", r.first, r.last); };
      throw InputError("--frames", "", fmt::format("frame {} is chosen twice ({} and {} overlap)", ranges[i].first,
                                                   text(ranges[i - 1]), text(ranges[i])));
    }
  }
  std::vector<Frame> chosen;
  for (const FrameRange& range : ranges) {
    for (long long number = range.first; number <= range.last; ++number) {
      const Frame* frame = find(number);
      if (frame == nullptr) {
        throw InputError("--frames", "",
                         fmt::format("frame {} is not in {} (it lists frames {})", number, dataset.listing.string(),
                                     as_ranges(numbers_of(dataset.frames))));
      }
      chosen.push_back(*frame);
    }
  }
  std::sort(chosen.begin(), chosen.end(), [](const Frame& a, const Frame& b) { return a.number < b.number; });
  for (std::size_t i = 1; i < chosen.size(); ++i) {
    if (chosen[i].number == chosen[i - 1].number) {
      throw InputError("--frames", "", fmt::format("frame {} is chosen twice in '{}'", chosen[i].number, frames));
    }
  }
  return chosen;
}

std::vector<RadarPoint> read_radar_file(const fs::path& path) {
  const std::string file = path.string();
  require_regular_file(path, "every frame needs its radar file");
  LineReader lines(path);
  std::string_view line;
  bool header = false;
  while (!header && lines.next(line)) {
    if (is_blank(line)) continue;  // the dataset's files open with a blank line
    const std::vector<std::string_view> names = whitespace_fields(line);
    header = names.size() == kRadarColumns && std::equal(names.begin(), names.end(), std::begin(kRadarHeader));
    if (!header) {
      const bool printable = line.size() <= 80 && !find_control_character(line);
      throw InputError(file, fmt::format("line {}", lines.line_number()),
                       fmt::format("expected the header 'X Y Z V_r Mag'{}", printable ? fmt::format(", got '{}'", line) : ""));
    }
  }
  if (!header) throw InputError(file, "", "no header 'X Y Z V_r Mag': an empty file");
  std::vector<RadarPoint> points;
  while (lines.next(line)) {
    if (is_blank(line)) continue;
    const int n = lines.line_number();
    const std::vector<std::string_view> fields = whitespace_fields(line);
    if (fields.size() != kRadarColumns) {
      throw InputError(file, fmt::format("line {}", n),
                       fmt::format("{} fields, expected {} (X Y Z V_r Mag): a truncated row?", fields.size(), kRadarColumns));
    }
    RadarPoint p{row_number(fields[0], file, n, "X"),   row_number(fields[1], file, n, "Y"),
                 row_number(fields[2], file, n, "Z"),   row_number(fields[3], file, n, "V_r"),
                 row_number(fields[4], file, n, "Mag"), n};
    const auto fail = [&](const char* column, const std::string& message) {
      throw InputError(file, fmt::format("line {}, column '{}'", n, column), message);
    };
    for (const auto& [column, value] : {std::pair{"X", p.x_m}, std::pair{"Y", p.y_m}, std::pair{"Z", p.z_m}}) {
      if (std::abs(value) > limits::kMaxRange_m) {
        fail(column, fmt::format("|{}| exceeds the limit of {} m", value, limits::kMaxRange_m));
      }
    }
    // A level stands for half a step either side: beyond, no Doppler level of this radar.
    const double half_step = 0.5 * kDopplerStep_mps;
    if (!(p.v_r_mps >= kLowestVr_mps - half_step && p.v_r_mps <= kHighestVr_mps + half_step)) {
      fail("V_r", fmt::format("{} m/s lies outside the radar's Doppler levels {} to {} m/s", p.v_r_mps, kLowestVr_mps,
                              kHighestVr_mps));
    }
    if (std::abs(p.mag) > limits::kMaxLevel_dB) {
      fail("Mag", fmt::format("|{}| exceeds the limit of {} dB", p.mag, limits::kMaxLevel_dB));
    }
    points.push_back(p);
  }
  return points;
}

RecordedTarget planar_target(const RadarPoint& point, const Eigen::Matrix4d& T_VS, const Pose2& X_VS) {
  const Eigen::Vector4d p_V = T_VS * Eigen::Vector4d(point.x_m, point.y_m, point.z_m, 1.0);
  const Vec2 p_ST_S = rotate(-X_VS.yaw_rad, Vec2(p_V.x(), p_V.y()) - X_VS.translation());
  RecordedTarget t;
  t.range_m = p_ST_S.norm();  // horizontal: the model is planar
  t.azimuth_rad = std::atan2(p_ST_S.y(), p_ST_S.x());
  t.elevation_rad = std::atan2(point.z_m, std::hypot(point.x_m, point.y_m));
  t.range_rate_mps = 0.0 - point.v_r_mps;  // V_r is positive approaching (astyx_importer.hpp); never -0
  t.amplitude_db = point.mag;
  return t;
}

double yaw_of_quaternion_rad(double w, double x, double y, double z) {
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

}  // namespace astyx

namespace astyx {
namespace {

constexpr const char* kLicence = "CC BY-NC-SA 4.0, Copyright (c) 2019 Astyx GmbH";

// What the Doppler speed fits of the frames without CAN data came to.
struct DopplerSpeeds {
  std::size_t fitted = 0, unfitted = 0, inliers = 0, candidates = 0;
  double max_speed_mps = 0.0;
};

nlohmann::json ego_motion_report(bool known, const DopplerSpeeds& doppler) {
  if (!known) {
    return {{"method", "speed from the stationary world's aliased Doppler, frame by frame (fit_speed_aliased in "
                       "replay/import/doppler_ego_motion.hpp); yaw rate 0"},
            {"why", "the HiRes2019 frames have neither CAN data nor timestamps. The radar's own Doppler gives the "
                    "speed, which the simulation needs: a parked car seen from a moving ego spreads over many "
                    "range-Doppler cells. ego_motion_known stays false: the speed comes from the recorded targets' "
                    "radial speeds, so replay neither compares radial speeds nor classes targets by them"},
            {"frames_fitted", doppler.fitted},
            {"frames_without_fit", doppler.unfitted},
            {"inlier_share", doppler.candidates > 0 ? static_cast<double>(doppler.inliers) / static_cast<double>(doppler.candidates) : 0.0},
            {"max_speed_mps", doppler.max_speed_mps}};
  }
  return {{"method", "each frame's CAN data: vehicle_speed (km/h) / 3.6, YAW_RATE (deg/s) x pi / 180"},
          {"yaw_rate_sign",
           "not stated by the dataset; taken as counter-clockwise positive (ISO 8855, as ego.csv). The standing "
           "frames read -0.43 and -0.25 deg/s (an offset, not removed); with that offset and LAT_ACCEL's standing "
           "value removed, LAT_ACCEL / speed has the sign of YAW_RATE in both moving frames, which shows only that "
           "the two share a convention"},
          {"speed_check",
           "on the demo frames 1 to 3 (moving), the stationary world's V_r fits V_r = v cos(angle) with v = 0.4, 8.6 "
           "and 15.6 m/s, against CAN speeds of 0.6, 7.8 and 15.3 m/s"}};
}

// The frames' targets at cycle k, in the vehicle's horizontal plane.
void add_frame_targets(const Frame& frame, const Mount& mount, int k, Recording& rec) {
  for (const RadarPoint& p : read_radar_file(frame.radar)) {
    RecordedTarget t = planar_target(p, mount.T_VS, mount.X_VS);
    if (!(t.range_m <= limits::kMaxRange_m)) {  // a mounting can push a point beyond
      throw InputError(frame.radar.string(), fmt::format("line {}", p.line),
                       fmt::format("{} m from the radar exceeds the limit of {} m", t.range_m, limits::kMaxRange_m));
    }
    t.t_s = static_cast<double>(k);
    t.cycle = k;
    t.sensor = 0;
    rec.targets.push_back(t);
  }
}

// Without CAN: the ego's speed from the stationary world's aliased Doppler of one frame's targets.
void fit_frame_speed(const Recording& rec, std::size_t first_target, const Mount& mount, EgoSample& ego, DopplerSpeeds& doppler) {
  std::vector<DopplerTarget> doppler_targets;
  doppler_targets.reserve(rec.targets.size() - first_target);
  for (std::size_t i = first_target; i < rec.targets.size(); ++i) {
    const RecordedTarget& t = rec.targets[i];
    doppler_targets.push_back({t.azimuth_rad, t.elevation_rad, t.range_rate_mps});
  }
  const AliasedSpeedFit fit =
      fit_speed_aliased(doppler_targets, mount.X_VS.yaw_rad, kRangeRateInterval_mps.min_mps, kRangeRateInterval_mps.max_mps);
  doppler.inliers += fit.inliers;
  doppler.candidates += fit.candidates;
  if (fit.valid) {
    ego.speed_mps = fit.speed_mps;
    doppler.max_speed_mps = std::max(doppler.max_speed_mps, fit.speed_mps);
    ++doppler.fitted;
  } else {
    ++doppler.unfitted;
  }
}

// The labelled boxes of one frame as objects of their own (one box each), counting what is kept
// (by model) and left out (by class).
void add_frame_boxes(const Labels& labels, const Frame& frame, double t_s, Recording& rec, std::map<std::string, int>& kept,
                     std::map<std::string, int>& left_out) {
  for (const Box& b : labels.boxes) {
    if (b.model.empty()) {
      ++left_out[b.dataset_class];
      continue;
    }
    ++kept[b.model];
    RecordingObject object{b.id, b.model, b.length_m, b.width_m};
    object.attributes = {{"dataset_class", b.dataset_class}, {"occlusion", b.occlusion},
                         {"label_certainty", b.label_certainty}, {"height_m", b.height_m},
                         {"z_m", b.z_m},                        {"frame", frame.number}};
    rec.objects.push_back(std::move(object));
    // The world is the reference frame: the ego stands at its origin in every frame.
    rec.boxes.push_back({{t_s, b.X_VO.x_m, b.X_VO.y_m, wrap_angle_rad(b.X_VO.yaw_rad), 0.0, 0}});
  }
}

std::vector<std::string> left_out_warnings(const std::map<std::string, int>& left_out) {
  std::vector<std::string> models, warnings;
  if (!left_out.empty()) {
    const ModelLibrary library = ModelLibrary::builtin();
    for (const auto& [name, model] : library.models()) models.push_back(name);
  }
  for (const auto& [name, count] : left_out) {
    std::string normalised = name;
    std::replace(normalised.begin(), normalised.end(), '_', ' ');
    warnings.push_back(fmt::format("{} boxes of class {} left out: {} (the object models: {})", count, name,
                                   is_motorcyclist(normalised) ? "no object model for motorcycles"
                                                                  : "not a class the dataset documents, and no object model for it",
                                   fmt::join(models, ", ")));
  }
  return warnings;
}

// What the frames are: CAN on all of them (the ego motion known) or on none.
bool ego_motion_known(const Dataset& dataset, const std::vector<Frame>& frames) {
  const bool known = std::all_of(frames.begin(), frames.end(), [](const Frame& f) { return !f.canbus.empty(); });
  if (known) return true;
  for (const Frame& f : frames) {
    if (!f.canbus.empty()) {
      throw InputError(dataset.listing.string(), fmt::format("data.{}", f.number),
                       "some frames have CAN data (canbus) and some none: import them apart (--frames)");
    }
  }
  return false;
}

// The recording's provenance (schemas/recording.md `source`).
nlohmann::json astyx_source(const std::string& dataset_name, const std::vector<int>& numbers, const nlohmann::json& frame_indices,
                            bool ego_known, const DopplerSpeeds& doppler) {
  return {
      {"dataset", "Astyx HiRes2019 (Meyer and Kuschk, Automotive Radar Dataset for Deep Learning Based 3D Object "
                  "Detection, EuRAD 2019)"},
      {"licence", kLicence},
      {"importer", "rcsim import --from astyx"},
      {"sequence", dataset_name},
      {"frames", numbers},
      {"frame_index", frame_indices},
      {"timeline", "each cycle is one labelled frame (a snapshot), cycle k the k-th of source.frames; t_s = k and "
                   "cycle_time_s = 1 only order the frames, they are no times; frame_index is each frame's index "
                   "in the original recording"},
      {"amplitude_db", "Mag, the radar's own dB-like level (range-compensated: not an SNR, not an RCS)"},
      {"range_rate_mps", fmt::format("-V_r: the dataset's V_r is positive for a target that comes closer (the "
                                     "stationary world on the demo frames), aliased into {} levels of {} m/s; not "
                                     "ego-compensated",
                                     kDopplerLevels, kDopplerStep_mps)},
      {"targets", "each point X Y Z: range_m and azimuth_rad in the horizontal plane, elevation_rad = atan2(Z, "
                  "hypot(X, Y))"},
      {"boxes", "groundtruth_obj3d: center3d and the yaw of orientation_quat (w, x, y, z) in the radar's reference "
                "frame, dimension3d length and width; the labels hold no velocities, so speed_mps is 0; each object "
                "is one box of one frame (id fNNNNNN_KK: frame, index in its file)"},
      {"ego_motion", ego_motion_report(ego_known, doppler)}};
}

}  // namespace
}  // namespace astyx

DatasetRecording import_astyx(const fs::path& raw_dir, const DatasetImportOptions& options) {
  if (!options.mapping.empty()) throw InputError("--mapping", "", "maps the topics of an MCAP log (--from mcap)");
  if (!options.ego_log.empty()) {
    throw InputError("--ego-log", "",
                     "Astyx frames are single snapshots without a clock: no ego log can cover them (the demo frames' "
                     "speed and yaw rate are read from their canbus/ files)");
  }
  const astyx::Dataset dataset = astyx::find_dataset(raw_dir);
  const std::vector<astyx::Frame> frames = astyx::choose_frames(dataset, options.frames);
  const bool ego_known = astyx::ego_motion_known(dataset, frames);

  DatasetRecording out;
  Recording& rec = out.recording;
  const std::string dataset_name = fs::absolute(raw_dir).lexically_normal().filename().string();
  rec.name = (dataset_name.empty() ? fs::absolute(raw_dir).lexically_normal().parent_path().filename().string() : dataset_name) +
             (options.frames.empty() ? "" : " frames " + astyx::as_ranges(astyx::numbers_of(frames)));
  rec.cycle_time_s = 1.0;
  rec.timeline = Timeline::snapshots;
  rec.ego_motion_known = ego_known;

  std::optional<astyx::Mount> mount;
  std::string mount_file;
  std::vector<int> numbers;
  nlohmann::json frame_indices = nlohmann::json::array();
  std::map<std::string, int> left_out;  // class -> boxes
  std::map<std::string, int> kept;      // model -> boxes
  astyx::DopplerSpeeds doppler;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const astyx::Frame& frame = frames[k];
    const double t_s = static_cast<double>(k);
    const astyx::Mount m = astyx::read_mount(frame.calibration, dataset.radar);
    if (!mount) {
      mount = m;
      mount_file = frame.calibration.string();
    } else if ((m.T_VS - mount->T_VS).cwiseAbs().maxCoeff() > 1e-9) {
      throw InputError(frame.calibration.string(), "sensors." + dataset.radar + ".calib_data.T_to_ref_COS",
                       "differs from " + mount_file + "'s: a recording holds one mounting per sensor");
    }
    astyx::EgoAtFrame ego;
    if (ego_known) ego = astyx::read_canbus(frame.canbus);
    rec.ego.push_back({t_s, 0.0, 0.0, 0.0, ego.speed_mps, ego.yaw_rate_radps});
    const std::size_t first_target = rec.targets.size();
    astyx::add_frame_targets(frame, *mount, static_cast<int>(k), rec);
    if (!ego_known) astyx::fit_frame_speed(rec, first_target, *mount, rec.ego.back(), doppler);
    const astyx::Labels labels = astyx::read_labels(frame);
    numbers.push_back(frame.number);
    frame_indices.push_back(static_cast<long long>(labels.frame_index));
    astyx::add_frame_boxes(labels, frame, t_s, rec, kept, left_out);
  }
  out.warnings = astyx::left_out_warnings(left_out);

  rec.sensors.push_back({dataset.radar, astyx::kSensorProfile, mount->X_VS.x_m, mount->X_VS.y_m, mount->X_VS.yaw_rad,
                         ListLevel::detections, AmplitudeUnit::relative_db, astyx::kRangeRateInterval_mps});
  // The calibration gives no height: the road under the boxes does (a radar that measures elevation reads it).
  const std::optional<GroundPlaneFit> ground = fit_ground_plane(rec);
  if (ground) {
    rec.sensors.back().z_m = ground->z_m;
    rec.sensors.back().pitch_rad = ground->pitch_rad;
  }
  const bool demo = dataset.listing.filename() == "dataset_info.json";
  rec.description = fmt::format(
      "Astyx HiRes2019 {}: {} labelled frames ({}) of the imaging radar {}, one frame one cycle (snapshots); {} boxes "
      "of cars, {} of trucks and buses, {} of pedestrians and {} of cyclists; {}",
      demo ? "demo frames" : "dataset", frames.size(), astyx::as_ranges(numbers), dataset.radar, kept["passenger_car"],
      kept["truck_trailer"], kept["pedestrian"], kept["cyclist"], ego_known ? "ego motion from CAN" : "no ego motion (snapshots without CAN)");
  rec.source = astyx::astyx_source(dataset_name, numbers, frame_indices, ego_known, doppler);
  rec.source["mounting"] = ground ? describe(*ground)
                                  : std::string("height and pitch unknown: fewer than 10 boxes, or no plane through their bottoms");
  if (doppler.unfitted > 0) {
    out.warnings.push_back(fmt::format("{} of {} frames: too few stationary points agree on a speed; the ego is taken "
                                       "as standing there (source.ego_motion)",
                                       doppler.unfitted, frames.size()));
  }
  return out;
}

}  // namespace rcsim::replay
