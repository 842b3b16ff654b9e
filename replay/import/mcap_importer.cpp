#include "replay/import/mcap_importer.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <Eigen/Geometry>
#include <simdjson.h>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/list_level.hpp"
#include "common/quantile.hpp"
#include "common/safe_text.hpp"
#include "common/text_file.hpp"
#include "io/robot_log.hpp"
#include "io/recording_writer.hpp"
#include "io/ros2_messages.hpp"
#include "model/model_library.hpp"
#include "replay/import/foxglove_messages.hpp"
#include "replay/import/openlabel.hpp"
#include "replay/import/tf_tree.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

// The mapping file (schemas/mcap-mapping.md).
struct MappedSensor {
  RecordingSensor sensor;
  std::string topic;
  // Mounted as /tf_static says (no x_m, y_m, yaw_rad given): the radar's frame, "" for its
  // scans' frame_id.
  bool mounting_from_tf = false;
  std::string frame;
  std::optional<double> cycle_time_s;
  // Each scan at the log's time of its message, not its header.stamp (a driver that stamps 0).
  bool stamp_from_log = false;
  // A point cloud's (foxglove.PointCloud, sensor_msgs/msg/PointCloud2) fields that hold the radial speed and the amplitude.
  std::string range_rate_field = "range_rate", amplitude_field = "amplitude";
};

// The ego: an Odometry topic, or the chain of /tf transforms from the vehicle's frame to a world frame.
struct MappedEgo {
  std::string topic;
  std::string world_frame, vehicle_frame, tf_topic = "/tf", tf_static_topic = "/tf_static";
  bool from_tf() const { return !vehicle_frame.empty(); }
};

struct Mapping {
  std::string name;
  std::vector<MappedSensor> sensors;
  MappedEgo ego;
  // The annotated boxes: a topic of the log, or an OpenLABEL file beside it.
  std::string objects_topic;
  fs::path openlabel;
  std::map<std::string, std::string> classes;  // the log's class name -> an object model
  std::string objects_source() const { return openlabel.empty() ? objects_topic : openlabel.string(); }
  std::optional<double> annotation_step_s;
};

Mapping read_mapping(const fs::path& path) {
  const std::string file = path.string();
  const nlohmann::json json = parse_json_text(read_text_file(path), file);
  const JsonField root(json, file, "");
  root.expect_format("rcsim-mcap-mapping", 1);
  root.expect_only({"format", "version", "name", "sensors", "ego", "objects", "annotation_step_s"});
  Mapping m;
  if (root.has("name")) m.name = root.string("name");
  for (const JsonField& s : root.array("sensors")) {
    s.expect_only({"id", "topic", "type", "x_m", "y_m", "yaw_rad", "frame", "reports", "cycle_time_s", "fields", "stamp"});
    using namespace limits;
    MappedSensor mapped;
    mapped.sensor.id = s.string("id"), mapped.sensor.type = s.string("type"), mapped.topic = s.string("topic");
    // The mounting as given, or all of it from /tf_static.
    const int given = s.has("x_m") + s.has("y_m") + s.has("yaw_rad");
    if (given == 3) {
      mapped.sensor.x_m = s.number_within("x_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m");
      mapped.sensor.y_m = s.number_within("y_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m");
      mapped.sensor.yaw_rad = s.angle_rad("yaw_rad", kMaxMountYaw_rad);
      if (s.has("frame")) s.fail("frame", "names the frame whose transform mounts the radar: give it or x_m, y_m, yaw_rad, not both");
    } else if (given == 0) {
      mapped.mounting_from_tf = true;
      if (s.has("frame")) mapped.frame = s.string("frame");
    } else {
      s.fail(s.has("x_m") ? (s.has("y_m") ? "yaw_rad" : "y_m") : "x_m",
             "the mounting takes x_m, y_m and yaw_rad, or none of them to take it from the log's /tf_static");
    }
    if (const auto fields = s.optional_member("fields")) {
      fields->expect_only({"range_rate", "amplitude"});
      if (fields->has("range_rate")) mapped.range_rate_field = fields->string("range_rate");
      if (fields->has("amplitude")) mapped.amplitude_field = fields->string("amplitude");
    }
    if (s.has("reports")) {
      const std::string reports = s.string("reports");
      if (reports != "tracks" && reports != "detections") s.fail("reports", "must be \"tracks\" or \"detections\", got \"" + reports + "\"");
      mapped.sensor.reports = reports == "tracks" ? ListLevel::tracks : ListLevel::detections;
    } else {
      mapped.sensor.reports = ListLevel::detections;  // a RadarScan holds raw returns
    }
    if (s.has("stamp")) {
      const std::string stamp = s.string("stamp");
      if (stamp != "header" && stamp != "log") s.fail("stamp", "must be \"header\" (the scans' header.stamp) or \"log\" (the log's time of each), got \"" + stamp + "\"");
      mapped.stamp_from_log = stamp == "log";
    }
    if (s.has("cycle_time_s")) {
      mapped.cycle_time_s = s.number_within("cycle_time_s", 0.0, kMaxCycleTime_s, "s");
      require_positive(s, "cycle_time_s", *mapped.cycle_time_s);
    }
    if (mapped.sensor.id.empty()) s.fail("id", "must not be empty");
    if (const auto bad = find_control_character(mapped.sensor.id)) s.fail("id", "holds " + *bad + ": ids are one line");
    for (const MappedSensor& other : m.sensors) {
      if (other.sensor.id == mapped.sensor.id) s.fail("id", fmt::format("sensor '{}' is listed twice", mapped.sensor.id));
      if (other.topic == mapped.topic) s.fail("topic", fmt::format("topic '{}' is mapped twice", mapped.topic));
    }
    m.sensors.push_back(std::move(mapped));
  }
  if (m.sensors.empty()) root.fail("sensors", "map at least one radar's topic");
  const JsonField ego = root.member("ego");
  ego.expect_only({"topic", "tf"});
  if (ego.has("topic") == ego.has("tf")) ego.fail("takes an Odometry \"topic\" or a \"tf\" chain, one of them");
  if (ego.has("topic")) m.ego.topic = ego.string("topic");
  if (const auto tf = ego.optional_member("tf")) {
    tf->expect_only({"world_frame", "vehicle_frame", "topic", "static_topic"});
    m.ego.world_frame = tf->string("world_frame"), m.ego.vehicle_frame = tf->string("vehicle_frame");
    if (tf->has("topic")) m.ego.tf_topic = tf->string("topic");
    if (tf->has("static_topic")) m.ego.tf_static_topic = tf->string("static_topic");
    if (m.ego.world_frame.empty() || m.ego.vehicle_frame.empty() || m.ego.world_frame == m.ego.vehicle_frame) {
      tf->fail("vehicle_frame", "the vehicle's frame and the world frame must be two named frames");
    }
  }
  for (std::size_t i = 0; i < m.sensors.size(); ++i) {
    if (m.sensors[i].mounting_from_tf && !m.ego.from_tf()) {
      root.fail(fmt::format("sensors[{}]", i), "without x_m, y_m, yaw_rad the mounting comes from /tf_static, which needs the "
                                               "vehicle's frame: the ego as a \"tf\" chain");
    }
  }
  if (const auto objects = root.optional_member("objects")) {
    objects->expect_only({"topic", "openlabel", "classes"});
    if (objects->has("topic") == objects->has("openlabel")) {
      objects->fail("takes the boxes' \"topic\" in the log or an \"openlabel\" file beside it, one of them");
    }
    if (objects->has("topic")) m.objects_topic = objects->string("topic");
    // An OpenLABEL file named relative to the mapping file.
    if (objects->has("openlabel")) m.openlabel = path.parent_path() / objects->string("openlabel");
    if (const auto classes = objects->optional_member("classes")) {
      if (!classes->json().is_object()) objects->fail("classes", "must map the log's class names to object models");
      for (const auto& [from, to] : classes->json().items()) {
        if (!to.is_string()) objects->fail("classes." + from, "must name an object model (rcsim models)");
        m.classes[from] = to.get<std::string>();
      }
    }
  }
  if (root.has("annotation_step_s")) {
    m.annotation_step_s = root.number_within("annotation_step_s", 0.0, limits::kMaxCycleTime_s, "s");
    require_positive(root, "annotation_step_s", *m.annotation_step_s);
  }
  return m;
}

// One box as logged; its speed NaN where the log gives none.
struct LoggedBox {
  std::int64_t t_ns = 0;
  double x_m = 0.0, y_m = 0.0;
  float yaw_rad = 0.0f, speed_mps = 0.0f, length_m = 0.0f, width_m = 0.0f;
};

// One ego pose as logged; a chain of transforms gives poses only, their speeds and yaw rates
// follow from them.
struct LoggedEgo {
  std::int64_t t_ns = 0;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, speed_mps = 0.0, yaw_rate_radps = 0.0;
};

// A count of values at a resolution (steps in µs, sizes in mm): their median exactly at that
// resolution in memory bounded by the values' spread, not by how many there are.
class Histogram {
 public:
  void add(std::int64_t value) { ++counts_[value], ++n_; }
  bool empty() const { return n_ == 0; }
  // The median (the mean of the two middle values of an even count).
  double median() const {
    const auto value_at = [&](std::int64_t rank) {  // the rank-th value (from 0) in order
      for (const auto& [value, count] : counts_) {
        if (rank < count) return static_cast<double>(value);
        rank -= count;
      }
      return static_cast<double>(counts_.rbegin()->first);
    };
    return 0.5 * (value_at((n_ - 1) / 2) + value_at(n_ / 2));
  }

 private:
  std::map<std::int64_t, std::int64_t> counts_;
  std::int64_t n_ = 0;
};

constexpr double kNsPerUs = 1e3, kMmPerM = 1e3;

// An object as the survey finds it: in the order of first appearance.
struct SurveyedObject {
  std::string id, log_class;
  Histogram lengths_mm, widths_mm;
  bool speed_missing = false;  // some box without a speed: all speeds from the positions
};

// What the first pass over the log finds: the recording's clock and header, the ego log (held:
// 48 B a pose), and per sensor and object what their rows will need. The scans and boxes, the
// bulk of a log, are not held.
struct Survey {
  std::int64_t t0_ns = std::numeric_limits<std::int64_t>::max();
  std::vector<std::string> scan_frames;           // per sensor: its first scan's frame_id
  std::vector<std::int64_t> first_scan_ns, last_scan_ns;
  std::vector<Histogram> scan_steps_us;
  std::vector<LoggedEgo> ego;
  std::string odometry_frame, odometry_child_frame;  // the first Odometry's
  TfTree tf;
  std::vector<SurveyedObject> objects;
  std::map<std::string, std::size_t> object_index;
  Histogram annotation_steps_us;
  std::int64_t last_annotation_ns = std::numeric_limits<std::int64_t>::min();
  std::set<std::string> topics_seen;  // the mapped topics with messages
  robot_log::LogSummary log;          // the log's header, its topics, what a person should know

  std::int64_t last_ns = std::numeric_limits<std::int64_t>::min();
  void stamp(std::int64_t t_ns) { t0_ns = std::min(t0_ns, t_ns), last_ns = std::max(last_ns, t_ns); }
  std::size_t object(std::string_view id, std::string_view log_class) {
    auto [it, added] = object_index.try_emplace(std::string(id), objects.size());
    if (added) objects.push_back({std::string(id), std::string(log_class), {}, {}, false});
    if (objects[it->second].log_class.empty()) objects[it->second].log_class = log_class;
    return it->second;
  }
  void box(std::size_t o, const LoggedBox& b) {
    stamp(b.t_ns);
    // A size beyond the limits is refused in the second pass, naming the box; here it only must
    // not reach llround.
    const auto mm = [](float size_m) { return std::llround(std::clamp(static_cast<double>(size_m), 0.0, limits::kMaxSize_m) * kMmPerM); };
    objects[o].lengths_mm.add(mm(b.length_m));
    objects[o].widths_mm.add(mm(b.width_m));
    objects[o].speed_missing = objects[o].speed_missing || std::isnan(b.speed_mps);
    if (b.t_ns > last_annotation_ns) {
      if (last_annotation_ns != std::numeric_limits<std::int64_t>::min()) {
        annotation_steps_us.add(std::llround(static_cast<double>(b.t_ns - last_annotation_ns) / kNsPerUs));
      }
      last_annotation_ns = b.t_ns;
    }
  }
};

// What one pass over the log hands on, message by message in log order.
struct LogVisitor {
  std::function<void(int sensor, ros2::RadarScan& scan)> scan;
  std::function<void(const ros2::Odometry&)> odometry;
  std::function<void(const std::vector<ros2::TransformStamped>&, bool is_static)> transforms;
  std::function<void(const foxglove::SceneBox&)> box;
};

// A cloud's points (x, y, z, the radial speed, the amplitude; moved by X_SC into the radar's
// frame) as a scan's returns.
void add_points(ros2::RadarScan& scan, std::size_t count, const std::function<std::span<const double>(std::size_t)>& point,
                const Eigen::Isometry3d& X_SC) {
  scan.returns.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::span<const double> p = point(i);
    const Eigen::Vector3d p_S = X_SC * Eigen::Vector3d(p[0], p[1], p[2]);
    ros2::RadarReturn r;
    r.range = static_cast<float>(p_S.norm());
    r.azimuth = static_cast<float>(std::atan2(p_S.y(), p_S.x()));
    r.elevation = static_cast<float>(std::atan2(p_S.z(), std::hypot(p_S.x(), p_S.y())));
    r.doppler_velocity = static_cast<float>(p[3]);
    r.amplitude = static_cast<float>(p[4]);
    scan.returns.push_back(r);
  }
}

std::vector<std::string> cloud_fields(const MappedSensor& sensor) { return {"x", "y", "z", sensor.range_rate_field, sensor.amplitude_field}; }

// A radar's foxglove.PointCloud as a scan: each point (x, y, z in the cloud's frame, moved by its
// pose into the radar's) a return with the mapped range-rate and amplitude fields.
ros2::RadarScan scan_of_point_cloud(simdjson::ondemand::parser& parser, const std::string& text, const MappedSensor& sensor,
                                    std::uint64_t max_returns) {
  const foxglove::PointCloud cloud = foxglove::decode_point_cloud(parser, text, cloud_fields(sensor), max_returns);
  ros2::RadarScan scan;
  scan.header.frame_id = cloud.frame_id;
  scan.header.stamp.sec = static_cast<std::int32_t>(cloud.t_ns / 1'000'000'000);
  scan.header.stamp.nanosec = static_cast<std::uint32_t>(cloud.t_ns % 1'000'000'000);
  const Eigen::Quaterniond q(cloud.orientation[3], cloud.orientation[0], cloud.orientation[1], cloud.orientation[2]);
  if (q.norm() == 0.0) throw std::invalid_argument("pose.orientation: a zero quaternion is no rotation");
  Eigen::Isometry3d X_SC = Eigen::Isometry3d::Identity();
  X_SC.linear() = q.normalized().toRotationMatrix();
  X_SC.translation() = Eigen::Vector3d(cloud.position[0], cloud.position[1], cloud.position[2]);
  add_points(scan, cloud.size(), [&](std::size_t i) { return cloud.point(i); }, X_SC);
  return scan;
}

// A radar driver's sensor_msgs/msg/PointCloud2 as a scan, its points in its header's frame.
ros2::RadarScan scan_of_point_cloud2(std::string_view cdr, const MappedSensor& sensor, std::uint64_t max_returns, std::size_t& invalid_points) {
  const ros2::CloudPoints cloud = ros2::decode_point_cloud2(cdr, cloud_fields(sensor), max_returns);
  ros2::RadarScan scan;
  scan.header = cloud.header;
  add_points(scan, cloud.size(), [&](std::size_t i) { return std::span<const double>(cloud.values.data() + i * cloud.field_count, cloud.field_count); },
             Eigen::Isometry3d::Identity());
  invalid_points += cloud.invalid_points;
  return scan;
}

// What one pass over the log found: the mapped topics with messages, the log's summary, the
// invalid points of clouds that are not dense.
struct LogPass {
  std::set<std::string> topics_seen;
  robot_log::LogSummary summary;
  std::size_t invalid_points = 0;
};

// One pass over the log (an MCAP file or a ROS 2 bag): every message on a mapped topic decoded and
// handed on; a message of another schema than the mapped one, or one that does not decode,
// refused naming the topic and the message by its log time.
LogPass read_log(const fs::path& log, const Mapping& mapping, const LogVisitor& visit) {
  const robot_log::Log source(log);
  simdjson::ondemand::parser json_parser;
  std::map<std::string, int, std::less<>> sensor_of_topic;
  for (std::size_t s = 0; s < mapping.sensors.size(); ++s) sensor_of_topic[mapping.sensors[s].topic] = static_cast<int>(s);
  const MappedEgo& ego = mapping.ego;
  LogPass pass;
  // The returns the log's scans may hold in all (schemas/limits.md): one per byte of the log, at
  // least one scan's worth. A return is 20 bytes of CDR, which real measurements do not compress
  // 20:1; scans of zeros in zstd chunks do, 1000:1 and more.
  const std::uint64_t log_bytes = source.bytes();
  const std::uint64_t max_log_returns = std::max<std::uint64_t>(log_bytes, limits::kMaxReturnsPerScan);
  std::uint64_t log_returns = 0;
  std::string text;  // a JSON message's bytes (simdjson pads its own copy)
  pass.summary = source.for_each_message([&](const robot_log::LogMessage& m) {
    const auto sensor = sensor_of_topic.find(m.topic);
    const bool is_ego = m.topic == ego.topic, is_objects = m.topic == mapping.objects_topic;
    const bool is_tf = ego.from_tf() && (m.topic == ego.tf_topic || m.topic == ego.tf_static_topic);
    if (sensor == sensor_of_topic.end() && !is_ego && !is_objects && !is_tf) return;
    pass.topics_seen.emplace(m.topic);
    const std::string where = fmt::format("topic '{}', the message at log time {} ns", m.topic, m.log_time_ns);
    const auto expect = [&](std::string_view name, std::string_view encoding, std::string_view or_else = "") {
      if (m.schema_name != name || m.encoding != encoding) {
        throw InputError(log.string(), where,
                         fmt::format("schema '{}' in '{}': the mapping takes {} in '{}'{} on this topic", m.schema_name, m.encoding, name,
                                     encoding, or_else));
      }
    };
    try {
      if (sensor != sensor_of_topic.end()) {
        // A RadarScan or a PointCloud2 in CDR, or a foxglove.PointCloud in JSON.
        const MappedSensor& mapped = mapping.sensors[static_cast<std::size_t>(sensor->second)];
        const bool cloud = m.schema_name == "foxglove.PointCloud" && m.encoding == "json";
        const bool cloud2 = m.schema_name == ros2::kPointCloud2Schema && m.encoding == "cdr";
        if (!cloud && !cloud2) expect(ros2::kRadarScanSchema, "cdr", ", sensor_msgs/msg/PointCloud2 in 'cdr' or foxglove.PointCloud in 'json'");
        // Each scan's count checked against what the log has left before its returns are allocated.
        const std::uint64_t left = max_log_returns - log_returns;
        ros2::RadarScan scan;
        try {
          if (cloud) text.assign(m.data);
          scan = cloud    ? scan_of_point_cloud(json_parser, text, mapped, left)
                 : cloud2 ? scan_of_point_cloud2(m.data, mapped, left, pass.invalid_points)
                          : ros2::decode_radar_scan(m.data, left);
        } catch (const std::exception& e) {
          if (left >= limits::kMaxReturnsPerScan || std::string_view(e.what()).find("the log has left") == std::string_view::npos) {
            if (cloud2 && std::string_view(e.what()).find("no field") != std::string_view::npos) {
              throw ros2::CdrError(fmt::format("{}; name the radial speed's and the amplitude's in the mapping's sensors[{}].fields",
                                               e.what(), sensor->second));
            }
            throw;
          }
          throw InputError(log.string(), where,
                           fmt::format("{}: its scans held {} returns before this one, and a log holds at most {} (one per byte of its {} "
                                       "bytes, at least {}: schemas/limits.md; a zstd bomb?)",
                                       e.what(), log_returns, max_log_returns, log_bytes, limits::kMaxReturnsPerScan));
        }
        if (mapped.stamp_from_log) {
          scan.header.stamp.sec = static_cast<std::int32_t>(m.log_time_ns / 1'000'000'000);
          scan.header.stamp.nanosec = static_cast<std::uint32_t>(m.log_time_ns % 1'000'000'000);
        } else if (scan.header.stamp.ns() == 0) {
          throw InputError(log.string(), where,
                           fmt::format("header.stamp is 0: the driver does not stamp its scans; map sensors[{}].stamp: \"log\" to take "
                                       "each scan at the log's time of its message", sensor->second));
        }
        log_returns += scan.returns.size();
        if (visit.scan) visit.scan(sensor->second, scan);
      } else if (is_ego) {
        expect(ros2::kOdometrySchema, "cdr");
        if (visit.odometry) visit.odometry(ros2::decode_odometry(m.data));
      } else if (is_tf) {
        expect(ros2::kTfMessageSchema, "cdr");
        if (visit.transforms) visit.transforms(ros2::decode_tf_message(m.data), m.topic == ego.tf_static_topic);
      } else {
        expect("foxglove.SceneUpdate", "json");
        text.assign(m.data);
        if (visit.box) foxglove::for_each_scene_box(json_parser, text, visit.box);
      }
    } catch (const ros2::CdrError& e) {
      throw InputError(log.string(), where, e.what());
    } catch (const TfError& e) {
      throw InputError(log.string(), where, e.what());
    } catch (const simdjson::simdjson_error& e) {
      throw InputError(log.string(), where, fmt::format("not a {}: {}", m.schema_name, e.what()));
    } catch (const std::logic_error& e) {  // a field missing or not a number (std::stod too)
      throw InputError(log.string(), where, fmt::format("not a {}: {}", m.schema_name, e.what()));
    }
  });
  return pass;
}

float as_float(double v) { return static_cast<float>(v); }

LoggedBox logged_box(const foxglove::SceneBox& b) {
  return {b.t_ns, b.x_m, b.y_m, as_float(b.yaw_rad), as_float(b.speed_mps.value_or(std::nan(""))), as_float(b.length_m), as_float(b.width_m)};
}

// The first pass: the survey of the log.
Survey survey_log(const fs::path& log, const Mapping& mapping) {
  Survey survey;
  const std::size_t sensors = mapping.sensors.size();
  survey.scan_frames.resize(sensors);
  survey.first_scan_ns.assign(sensors, std::numeric_limits<std::int64_t>::max());
  survey.last_scan_ns.assign(sensors, std::numeric_limits<std::int64_t>::min());
  survey.scan_steps_us.resize(sensors);
  LogVisitor visit;
  visit.scan = [&](int sensor, ros2::RadarScan& scan) {
    const auto s = static_cast<std::size_t>(sensor);
    const std::int64_t t_ns = scan.header.stamp.ns();
    survey.stamp(t_ns);
    if (survey.scan_frames[s].empty()) survey.scan_frames[s] = scan.header.frame_id;
    if (survey.last_scan_ns[s] != std::numeric_limits<std::int64_t>::min() && t_ns > survey.last_scan_ns[s]) {
      survey.scan_steps_us[s].add(std::llround(static_cast<double>(t_ns - survey.last_scan_ns[s]) / kNsPerUs));
    }
    survey.first_scan_ns[s] = std::min(survey.first_scan_ns[s], t_ns);
    survey.last_scan_ns[s] = std::max(survey.last_scan_ns[s], t_ns);
  };
  visit.odometry = [&](const ros2::Odometry& o) {
    if (survey.ego.empty()) survey.odometry_frame = o.header.frame_id, survey.odometry_child_frame = o.child_frame_id;
    survey.ego.push_back({o.header.stamp.ns(), o.x_m, o.y_m, ros2::yaw_of_quaternion(o.qx, o.qy, o.qz, o.qw), o.vx_mps, o.wz_radps});
  };
  visit.transforms = [&](const std::vector<ros2::TransformStamped>& transforms, bool is_static) { survey.tf.add(transforms, is_static); };
  visit.box = [&](const foxglove::SceneBox& b) { survey.box(survey.object(b.id, b.log_class), logged_box(b)); };
  LogPass pass = read_log(log, mapping, visit);
  survey.topics_seen = std::move(pass.topics_seen);
  survey.log = std::move(pass.summary);
  if (pass.invalid_points > 0) {
    survey.log.warnings.push_back(fmt::format("{} invalid points (not finite) of clouds that are not dense left out", pass.invalid_points));
  }
  for (const MappedSensor& s : mapping.sensors) {
    if (!survey.topics_seen.count(s.topic)) {
      throw InputError(log.string(), s.topic, fmt::format("no messages on sensor '{}''s topic (the log's topics: {})", s.sensor.id,
                                                          fmt::join(survey.log.topics, ", ")));
    }
  }
  if (!mapping.objects_topic.empty() && !survey.topics_seen.count(mapping.objects_topic)) {
    throw InputError(log.string(), mapping.objects_topic, "no messages on the objects topic (a mapping without \"objects\" imports none)");
  }
  const MappedEgo& ego = mapping.ego;
  if (ego.from_tf()) {
    if (!survey.topics_seen.count(ego.tf_topic)) throw InputError(log.string(), ego.tf_topic, "no transforms: the ego's chain is read from them");
    survey.tf.finish();
  } else if (!survey.topics_seen.count(ego.topic)) {
    throw InputError(log.string(), ego.topic, "no messages on the ego topic");
  }
  return survey;
}

double seconds_since(std::int64_t t_ns, std::int64_t t0_ns) { return static_cast<double>(t_ns - t0_ns) * 1e-9; }

// The ego as the chain of transforms from the vehicle's frame to the world frame: a pose at each
// stamp of the chain's densest moving transform; speed along the heading and yaw rate by central
// differences of the poses (one-sided at the ends).
void ego_from_tf(Survey& survey, const fs::path& log, const MappedEgo& ego) {
  std::vector<std::int64_t> stamps;
  try {
    stamps = survey.tf.chain_stamps(ego.vehicle_frame, ego.world_frame);
    for (const std::int64_t t_ns : stamps) {
      const Eigen::Isometry3d X_WV = survey.tf.pose(ego.vehicle_frame, ego.world_frame, t_ns);
      const Eigen::Matrix3d R_WV = X_WV.linear();
      survey.ego.push_back({t_ns, X_WV.translation().x(), X_WV.translation().y(), std::atan2(R_WV(1, 0), R_WV(0, 0)), 0.0, 0.0});
    }
  } catch (const TfError& e) {
    throw InputError(log.string(), ego.tf_topic, fmt::format("the ego from '{}' to '{}': {}", ego.vehicle_frame, ego.world_frame, e.what()));
  }
  if (stamps.size() < 2) {
    throw InputError(log.string(), ego.tf_topic, fmt::format("the chain from '{}' to '{}' moves at {} stamp(s): no ego motion to read",
                                                          ego.vehicle_frame, ego.world_frame, stamps.size()));
  }
  std::vector<LoggedEgo>& e = survey.ego;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const LoggedEgo& a = e[i == 0 ? 0 : i - 1];
    const LoggedEgo& b = e[i + 1 == e.size() ? i : i + 1];
    const double dt_s = static_cast<double>(b.t_ns - a.t_ns) * 1e-9;
    e[i].speed_mps = speed_along_heading_mps(Vec2((b.x_m - a.x_m) / dt_s, (b.y_m - a.y_m) / dt_s), e[i].yaw_rad);
    e[i].yaw_rate_radps = angle_difference_rad(b.yaw_rad, a.yaw_rad) / dt_s;
  }
}

// Each radar mounted by /tf_static where the mapping gives no mounting: its frame's pose in the
// vehicle's at its first scan, to the plane.
void mount_from_tf(const Survey& survey, const fs::path& log, const Mapping& mapping, Recording& rec) {
  for (std::size_t s = 0; s < mapping.sensors.size(); ++s) {
    const MappedSensor& mapped = mapping.sensors[s];
    if (!mapped.mounting_from_tf) continue;
    const std::string& frame = mapped.frame.empty() ? survey.scan_frames[s] : mapped.frame;
    RecordingSensor& sensor = rec.sensors[s];
    try {
      const Eigen::Isometry3d X_VS = survey.tf.pose(frame, mapping.ego.vehicle_frame, survey.first_scan_ns[s]);
      const Eigen::Matrix3d R_VS = X_VS.linear();
      sensor.x_m = X_VS.translation().x(), sensor.y_m = X_VS.translation().y(), sensor.yaw_rad = std::atan2(R_VS(1, 0), R_VS(0, 0));
    } catch (const TfError& e) {
      throw InputError(log.string(), mapped.topic, fmt::format("sensor '{}''s mounting from /tf_static: {}", sensor.id, e.what()));
    }
    if (std::abs(sensor.x_m) > limits::kMaxMountOffset_m || std::abs(sensor.y_m) > limits::kMaxMountOffset_m) {
      throw InputError(log.string(), mapped.topic,
                       fmt::format("sensor '{}''s frame '{}' lies at ({:.3f}, {:.3f}) m from '{}': beyond the limits of "
                                   "schemas/limits.md",
                                   sensor.id, frame, sensor.x_m, sensor.y_m, mapping.ego.vehicle_frame));
    }
  }
}

// The ego's pose at t_ns from the odometry (times increasing), interpolated; beyond its ends by more
// than the margin refused.
Pose2 odometry_pose(const std::vector<LoggedEgo>& ego, std::int64_t t_ns, const std::string& what) {
  const auto after = std::lower_bound(ego.begin(), ego.end(), t_ns, [](const LoggedEgo& e, std::int64_t t) { return e.t_ns < t; });
  const auto sample = [&](const LoggedEgo& e) {
    return EgoSample{seconds_since(e.t_ns, ego.front().t_ns), e.x_m, e.y_m, e.yaw_rad, e.speed_mps, e.yaw_rate_radps};
  };
  const double t_s = seconds_since(t_ns, ego.front().t_ns);
  if (t_s < -kEgoExtrapolationMargin_s || seconds_since(t_ns, ego.back().t_ns) > kEgoExtrapolationMargin_s) {
    throw std::out_of_range(fmt::format("{} at {} ns lies beyond the odometry's {} to {} ns by more than {} s", what, t_ns,
                                        ego.front().t_ns, ego.back().t_ns, kEgoExtrapolationMargin_s));
  }
  const EgoSample e = after == ego.begin()  ? sample(ego.front())
                      : after == ego.end()  ? sample(ego.back())
                                            : interpolate_ego(sample(*(after - 1)), sample(*after), t_s);
  return {e.x_m, e.y_m, e.yaw_rad};
}

// One object's box, the object by its index in the survey.
struct ObjectBox {
  std::size_t object = 0;
  LoggedBox box;
};

// A pose given in `frame` at t_ns, moved into the ego's world frame: in the world frame (or in
// none named) as it is; with a /tf ego, from any frame of the tree through the transforms at its
// time; with an Odometry ego, from the odometry's child frame (the vehicle's) through the
// odometry's pose at its time. Anything else throws std::out_of_range naming the frame.
Pose2 in_world(const Survey& survey, const Mapping& mapping, const std::string& frame, std::int64_t t_ns, const Pose2& X_CO,
               const std::string& what) {
  const bool tf = mapping.ego.from_tf();
  const std::string& world = tf ? mapping.ego.world_frame : survey.odometry_frame;
  const std::string& vehicle = tf ? mapping.ego.vehicle_frame : survey.odometry_child_frame;
  if (frame.empty() || frame == world) return X_CO;
  Pose2 X_WC;
  if (tf) {
    if (!survey.tf.has_frame(frame)) {
      throw std::out_of_range(fmt::format("{} is in frame '{}', which is not in the /tf tree (its frames: {})", what, frame,
                                          fmt::join(survey.tf.frames(), ", ")));
    }
    const Eigen::Isometry3d X = survey.tf.pose(frame, world, t_ns);
    X_WC = {X.translation().x(), X.translation().y(), std::atan2(X.linear()(1, 0), X.linear()(0, 0))};
  } else if (frame == vehicle) {
    X_WC = odometry_pose(survey.ego, t_ns, what);
  } else {
    throw std::out_of_range(fmt::format("{} is in frame '{}': neither the odometry's world frame '{}' nor its vehicle frame '{}' "
                                        "(map the ego as a /tf chain to use other frames)",
                                        what, frame, world, vehicle));
  }
  return compose(X_WC, X_CO);
}

// The boxes of an OpenLABEL file beside the log (read whole), in the ego's world frame and in time
// order, each cuboid moved from its coordinate system (in_world). Planar: z and the height are
// dropped.
std::vector<ObjectBox> openlabel_boxes(Survey& survey, const Mapping& mapping) {
  const openlabel::Labels labels = openlabel::read_openlabel(mapping.openlabel);
  std::vector<ObjectBox> boxes;
  for (const openlabel::LabelledBox& b : labels.boxes) {
    Pose2 X_WO;
    const std::string what = fmt::format("object '{}''s cuboid", b.uid);
    try {
      X_WO = in_world(survey, mapping, b.coordinate_system, b.t_ns, Pose2{b.x_m, b.y_m, b.yaw_rad}, what);
    } catch (const std::out_of_range& e) {
      throw InputError(mapping.openlabel.string(), "openlabel.objects." + b.uid, e.what());
    } catch (const TfError& e) {
      throw InputError(mapping.openlabel.string(), "openlabel.objects." + b.uid, what + ": " + e.what());
    }
    boxes.push_back({survey.object(b.uid, b.type), {b.t_ns, X_WO.x_m, X_WO.y_m, as_float(X_WO.yaw_rad),
                                                    as_float(b.speed_mps.value_or(std::nan(""))), as_float(b.length_m), as_float(b.width_m)}});
  }
  std::stable_sort(boxes.begin(), boxes.end(), [](const ObjectBox& a, const ObjectBox& b) { return a.box.t_ns < b.box.t_ns; });
  for (const ObjectBox& b : boxes) survey.box(b.object, b.box);
  return boxes;
}

// A scan whose frame_id is not its radar's: each return moved through /tf into the radar's frame
// at the scan's time (the radial speed is the radar's measurement and stays).
void into_radar_frame(ros2::RadarScan& scan, const Survey& survey, const Mapping& mapping, const std::string& radar_frame, const fs::path& log,
                      const std::string& topic) {
  const std::string& frame = scan.header.frame_id;
  if (frame.empty() || frame == radar_frame) return;
  const std::int64_t t_ns = scan.header.stamp.ns();
  if (!mapping.ego.from_tf()) {
    throw InputError(log.string(), topic, fmt::format("a scan at {} ns in frame '{}', not its radar's '{}': map the ego as a /tf chain to "
                                                      "move it", t_ns, frame, radar_frame));
  }
  Eigen::Isometry3d X_SF;
  try {
    for (const std::string& f : {frame, radar_frame}) {
      if (!survey.tf.has_frame(f)) throw TfError(fmt::format("frame '{}' is not in the /tf tree (its frames: {})", f, fmt::join(survey.tf.frames(), ", ")));
    }
    X_SF = survey.tf.pose(frame, radar_frame, t_ns);
  } catch (const TfError& e) {
    throw InputError(log.string(), topic, fmt::format("a scan at {} ns in frame '{}', moved into its radar's '{}': {}", t_ns, frame, radar_frame, e.what()));
  }
  for (ros2::RadarReturn& r : scan.returns) {
    const double ground_m = r.range * std::cos(static_cast<double>(r.elevation));
    const Eigen::Vector3d p_S = X_SF * Eigen::Vector3d(ground_m * std::cos(static_cast<double>(r.azimuth)), ground_m * std::sin(static_cast<double>(r.azimuth)),
                                                       r.range * std::sin(static_cast<double>(r.elevation)));
    r.range = static_cast<float>(p_S.norm());
    r.azimuth = static_cast<float>(std::atan2(p_S.y(), p_S.x()));
    r.elevation = static_cast<float>(std::atan2(p_S.z(), std::hypot(p_S.x(), p_S.y())));
  }
}

// Where the import's rows go, in their files' order: a Recording in memory, or a RecordingWriter.
struct RowSink {
  virtual ~RowSink() = default;
  virtual void ego(const EgoSample& e) = 0;
  virtual void box(std::size_t object, const AnnotatedBox& b) = 0;
  virtual void cycle(const SensorCycle& c, const std::vector<RecordedTarget>& targets) = 0;
};

// The ego log's rows: times increasing, no hole beyond kMaxEgoLogStep_s, the yaw unwrapped (so
// that interpolation never turns the long way; ego.csv allows any yaw).
// A recording keeps its times to the microsecond (t_s with 6 decimals, schemas/recording.md): two
// stamps of the ego, one sensor or one object within the same microsecond would read back as one
// time twice.
double written_us(double t_s) { return std::round(t_s * 1e6); }

// With skip_edges, a pose stamped as the one before (to the microsecond) is left out and counted; else refused.
std::size_t write_ego(std::vector<LoggedEgo>& ego, std::int64_t t0_ns, const fs::path& log, const std::string& topic, bool skip_edges,
                      RowSink& sink) {
  std::stable_sort(ego.begin(), ego.end(), [](const LoggedEgo& a, const LoggedEgo& b) { return a.t_ns < b.t_ns; });
  EgoSample previous;
  bool written_any = false;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < ego.size(); ++i) {
    const LoggedEgo& e = ego[i];
    EgoSample row{seconds_since(e.t_ns, t0_ns), e.x_m, e.y_m, e.yaw_rad, e.speed_mps, e.yaw_rate_radps};
    if (written_any && written_us(row.t_s) <= written_us(previous.t_s)) {
      if (skip_edges) {
        ++skipped;
        continue;
      }
      throw InputError(log.string(), topic,
                       fmt::format("two ego poses stamped {} ns, within one microsecond (--skip-edges leaves the second out)", e.t_ns));
    }
    if (!(std::abs(row.x_m) <= limits::kMaxCoordinate_m && std::abs(row.y_m) <= limits::kMaxCoordinate_m && std::isfinite(row.yaw_rad) &&
          std::abs(row.speed_mps) <= limits::kMaxSpeed_mps && std::abs(row.yaw_rate_radps) <= limits::kMaxYawRate_radps)) {
      throw InputError(log.string(), topic, fmt::format("the ego pose stamped {} ns lies beyond the limits of schemas/limits.md "
                                                        "(x {}, y {}, yaw {}, speed {}, yaw rate {})",
                                                        e.t_ns, row.x_m, row.y_m, row.yaw_rad, row.speed_mps, row.yaw_rate_radps));
    }
    if (written_any) {
      if (row.t_s - previous.t_s > kMaxEgoLogStep_s) {
        throw InputError(log.string(), topic, fmt::format("{:.3f} s without an ego pose after {:.6f} s (at most {} s are interpolated)",
                                                          row.t_s - previous.t_s, previous.t_s, kMaxEgoLogStep_s));
      }
      row.yaw_rad = previous.yaw_rad + angle_difference_rad(row.yaw_rad, previous.yaw_rad);
    }
    sink.ego(row);
    previous = row;
    written_any = true;
  }
  return skipped;
}

// How far the stamps of one topic's messages may run out of log order: the second pass puts them
// in order through a window this long (memory: that much of the log).
constexpr std::int64_t kReorderWindow_ns = 2'000'000'000;

// The second pass's scans, put in time order (then sensor order) through the window and written
// as cycles, each numbered, checked and its returns made targets.
class CycleStream {
 public:
  CycleStream(const fs::path& log, const Mapping& mapping, std::int64_t t0_ns, double first_ego_s, double last_ego_s, bool skip_edges,
              RowSink& sink)
      : log_(log), mapping_(mapping), t0_ns_(t0_ns), first_ego_s_(first_ego_s), last_ego_s_(last_ego_s), skip_edges_(skip_edges), sink_(sink),
        last_t_us_(mapping.sensors.size(), -std::numeric_limits<double>::infinity()) {}

  void add(int sensor, ros2::RadarScan& scan) {
    const std::int64_t t_ns = scan.header.stamp.ns();
    const std::pair<std::int64_t, int> key{t_ns, sensor};
    const std::string& topic = mapping_.sensors[static_cast<std::size_t>(sensor)].topic;
    if (key == written_ || pending_.count(key)) {
      if (skip_edges_) {
        ++skipped_duplicates_;
        return;
      }
      throw InputError(log_.string(), topic, fmt::format("two scans stamped {:.9f} s after the log's start (--skip-edges leaves the "
                                                         "second out)", seconds_since(t_ns, t0_ns_)));
    }
    if (key < written_) {
      throw InputError(log_.string(), topic,
                       fmt::format("a scan stamped {} ns comes after one stamped {} ns, {:.3f} s later, in the log: the import "
                                   "puts the radars' scans in order within {} s",
                                   t_ns, newest_ns_, seconds_since(newest_ns_, t_ns), kReorderWindow_ns / 1'000'000'000));
    }
    pending_.emplace(key, std::move(scan.returns));
    newest_ns_ = std::max(newest_ns_, t_ns);
    while (!pending_.empty() && pending_.begin()->first.first < newest_ns_ - kReorderWindow_ns) write_first();
  }
  void finish() {
    while (!pending_.empty()) write_first();
  }
  std::size_t targets() const { return targets_; }
  std::size_t skipped_outside() const { return skipped_outside_; }
  std::size_t skipped_duplicates() const { return skipped_duplicates_; }

 private:
  void write_first() {
    const auto [key, returns] = std::move(*pending_.begin());
    pending_.erase(pending_.begin());
    written_ = key;
    const auto s = static_cast<std::size_t>(key.second);
    const std::string& topic = mapping_.sensors[s].topic;
    const double t_s = seconds_since(key.first, t0_ns_);
    if (written_us(t_s) <= last_t_us_[s]) {
      if (skip_edges_) {
        ++skipped_duplicates_;
        return;
      }
      throw InputError(log_.string(), topic,
                       fmt::format("two scans stamped within one microsecond, the second {:.9f} s after the log's start (a "
                                   "recording keeps times to the microsecond; --skip-edges leaves the second out)",
                                   t_s));
    }
    if (t_s < first_ego_s_ - kEgoExtrapolationMargin_s || t_s > last_ego_s_ + kEgoExtrapolationMargin_s) {
      if (skip_edges_) {
        ++skipped_outside_;
        return;
      }
      throw InputError(log_.string(), topic,
                       fmt::format("a scan at {:.6f} s lies beyond the ego log's {:.6f} to {:.6f} s by more than {} s (--skip-edges "
                                   "leaves such scans out)", t_s, first_ego_s_, last_ego_s_, kEgoExtrapolationMargin_s));
    }
    last_t_us_[s] = written_us(t_s);
    targets_buffer_.clear();
    for (const ros2::RadarReturn& r : returns) {
      RecordedTarget t;
      t.t_s = t_s, t.cycle = cycle_, t.sensor = key.second;
      // The planar model's range: the slant range over the ground.
      t.range_m = static_cast<double>(r.range) * std::cos(static_cast<double>(r.elevation));
      t.azimuth_rad = r.azimuth, t.elevation_rad = r.elevation;
      t.range_rate_mps = r.doppler_velocity, t.amplitude_db = r.amplitude;
      // Written so that NaN fails every one.
      if (!(t.range_m >= 0.0 && t.range_m <= limits::kMaxRange_m) || !(std::abs(t.azimuth_rad) <= limits::kMaxAzimuth_rad) ||
          !(std::abs(t.range_rate_mps) <= limits::kMaxSpeed_mps) || !(std::abs(t.amplitude_db) <= limits::kMaxLevel_dB) ||
          !(std::abs(t.elevation_rad) <= 1.58)) {
        throw InputError(log_.string(), topic,
                         fmt::format("a return at {:.6f} s beyond the limits of schemas/limits.md (range {}, azimuth {}, "
                                     "elevation {}, doppler_velocity {}, amplitude {})",
                                     t_s, r.range, r.azimuth, r.elevation, r.doppler_velocity, r.amplitude));
      }
      targets_buffer_.push_back(t);
    }
    sink_.cycle({t_s, key.second}, targets_buffer_);
    targets_ += targets_buffer_.size();
    ++cycle_;
  }

  const fs::path& log_;
  const Mapping& mapping_;
  std::int64_t t0_ns_;
  double first_ego_s_, last_ego_s_;
  bool skip_edges_;
  std::size_t skipped_outside_ = 0, skipped_duplicates_ = 0;
  RowSink& sink_;
  std::map<std::pair<std::int64_t, int>, std::vector<ros2::RadarReturn>> pending_;
  std::pair<std::int64_t, int> written_{std::numeric_limits<std::int64_t>::min(), 0};
  std::int64_t newest_ns_ = std::numeric_limits<std::int64_t>::min();
  std::vector<double> last_t_us_;  // per sensor: its last scan's time as the recording writes it, in microseconds
  std::vector<RecordedTarget> targets_buffer_;
  std::size_t targets_ = 0;
  int cycle_ = 0;
};

// The second pass's boxes, put in time order (then object order) through the window; a box logged
// without a speed gets one along its heading from its object's neighbouring boxes' positions
// (central differences; one-sided at an end or where the neighbour lies beyond the window).
class BoxStream {
 public:
  BoxStream(const fs::path& log, const Mapping& mapping, const Survey& survey, std::int64_t t0_ns, RowSink& sink)
      : log_(log), mapping_(mapping), survey_(survey), t0_ns_(t0_ns), sink_(sink), pending_(survey.objects.size()),
        previous_(survey.objects.size()) {}

  void add(std::size_t object, const LoggedBox& box) {
    const std::pair<std::int64_t, std::size_t> key{box.t_ns, object};
    const std::string& id = survey_.objects[object].id;
    if (!(box.length_m > 0.0f && box.length_m <= limits::kMaxSize_m && box.width_m > 0.0f && box.width_m <= limits::kMaxSize_m)) {
      throw InputError(log_.string(), mapping_.objects_source(),
                       fmt::format("entity '{}' at {} ns: a box of {} x {} m (each side in (0, {}] m)", id, box.t_ns, box.length_m,
                                   box.width_m, limits::kMaxSize_m));
    }
    if (key == written_ || order_.count(key)) {
      throw InputError(log_.string(), mapping_.objects_source(),
                       fmt::format("entity '{}' twice at {:.6f} s", id, seconds_since(box.t_ns, t0_ns_)));
    }
    if (key < written_) {
      throw InputError(log_.string(), mapping_.objects_source(),
                       fmt::format("entity '{}''s box stamped {} ns comes after one stamped {} ns, {:.3f} s later: the import "
                                   "puts the boxes in order within {} s",
                                   id, box.t_ns, newest_ns_, seconds_since(newest_ns_, box.t_ns), kReorderWindow_ns / 1'000'000'000));
    }
    std::deque<LoggedBox>& q = pending_[object];
    // An object's boxes in time order (its own are rarely out of order: a sorted insert).
    q.insert(std::upper_bound(q.begin(), q.end(), box.t_ns, [](std::int64_t t, const LoggedBox& b) { return t < b.t_ns; }), box);
    order_.insert(key);
    newest_ns_ = std::max(newest_ns_, box.t_ns);
    while (!order_.empty() && order_.begin()->first < newest_ns_ - kReorderWindow_ns) write_first();
  }
  void finish() {
    while (!order_.empty()) write_first();
  }

 private:
  void write_first() {
    const auto key = *order_.begin();
    order_.erase(order_.begin());
    written_ = key;
    const std::size_t o = key.second;
    const LoggedBox b = pending_[o].front();
    pending_[o].pop_front();
    AnnotatedBox box{seconds_since(b.t_ns, t0_ns_), b.x_m, b.y_m, b.yaw_rad, std::isnan(b.speed_mps) ? 0.0 : b.speed_mps, 0};
    const std::optional<AnnotatedBox>& previous = previous_[o];
    if (previous && written_us(box.t_s) <= written_us(previous->t_s)) {
      throw InputError(log_.string(), mapping_.objects_source(),
                       fmt::format("entity '{}' twice at {:.6f} s (within one microsecond: a recording keeps times to the microsecond)",
                                   survey_.objects[o].id, box.t_s));
    }
    if (survey_.objects[o].speed_missing) {
      const AnnotatedBox& a = previous ? *previous : box;
      AnnotatedBox c = box;
      if (!pending_[o].empty()) {
        const LoggedBox& next = pending_[o].front();
        c = {seconds_since(next.t_ns, t0_ns_), next.x_m, next.y_m, next.yaw_rad, 0.0, 0};
      }
      if (c.t_s > a.t_s) box.speed_mps = speed_along_heading_mps(Vec2((c.x_m - a.x_m) / (c.t_s - a.t_s), (c.y_m - a.y_m) / (c.t_s - a.t_s)), box.yaw_rad);
    }
    previous_[o] = box;
    sink_.box(o, box);
  }

  const fs::path& log_;
  const Mapping& mapping_;
  const Survey& survey_;
  std::int64_t t0_ns_;
  RowSink& sink_;
  std::vector<std::deque<LoggedBox>> pending_;  // per object, in time order
  std::set<std::pair<std::int64_t, std::size_t>> order_;
  std::vector<std::optional<AnnotatedBox>> previous_;
  std::pair<std::int64_t, std::size_t> written_{std::numeric_limits<std::int64_t>::min(), 0};
  std::int64_t newest_ns_ = std::numeric_limits<std::int64_t>::min();
};

// The whole import: the survey, the header, then the rows streamed into `sink`. Returns the
// recording's header (no rows) and how many targets were written.
struct ImportedLog {
  Recording header;  // no rows
  std::size_t targets = 0;
  std::vector<std::string> warnings;
};

ImportedLog import_log(const fs::path& log, const DatasetImportOptions& options, const std::function<RowSink&(const Recording&)>& open_sink) {
  if (options.mapping.empty()) {
    throw InputError(log.string(), "--mapping", "an MCAP log needs a mapping file: which topic is which radar, the ego, the boxes "
                                                "(schemas/mcap-mapping.md)");
  }
  if (!options.ego_log.empty()) throw InputError(log.string(), "--ego-log", "an MCAP log carries its ego motion (the mapping's ego topic)");
  if (!options.frames.empty()) throw InputError(log.string(), "--frames", "takes the frames of a dataset of single frames (--from astyx, vod)");
  const Mapping mapping = read_mapping(options.mapping);
  Survey survey = survey_log(log, mapping);
  if (mapping.ego.from_tf()) ego_from_tf(survey, log, mapping.ego);
  std::stable_sort(survey.ego.begin(), survey.ego.end(), [](const LoggedEgo& a, const LoggedEgo& b) { return a.t_ns < b.t_ns; });
  const std::vector<ObjectBox> labelled = mapping.openlabel.empty() ? std::vector<ObjectBox>{} : openlabel_boxes(survey, mapping);
  // The recording's clock: seconds since the earliest stamp of the mapped topics.
  for (const LoggedEgo& e : survey.ego) survey.stamp(e.t_ns);
  const std::int64_t t0_ns = survey.t0_ns;
  // A recording's times are seconds since its start, at most limits::kMaxTime_s: a stamp near 1970
  // or 2038 among the others is refused here, not by replay.
  if (seconds_since(survey.last_ns, t0_ns) > limits::kMaxTime_s) {
    throw InputError(log.string(), "", fmt::format("its stamps run from {} ns to {} ns, {:.0f} s: more than the {:.0f} s a recording's times "
                                                   "hold (schemas/limits.md; a stamp near 1970 or 2038?)",
                                                   t0_ns, survey.last_ns, seconds_since(survey.last_ns, t0_ns), limits::kMaxTime_s));
  }

  Recording rec;
  rec.name = mapping.name.empty() ? robot_log::Log(log).name() : mapping.name;  // a file's stem, a bag's directory name
  rec.clock = Clock::per_sensor;
  for (const MappedSensor& s : mapping.sensors) rec.sensors.push_back(s.sensor);
  mount_from_tf(survey, log, mapping, rec);
  for (std::size_t s = 0; s < rec.sensors.size(); ++s) {
    const MappedSensor& mapped = mapping.sensors[s];
    const Histogram& steps = survey.scan_steps_us[s];
    if (!mapped.cycle_time_s && steps.empty()) {
      throw InputError(log.string(), mapped.topic, fmt::format("sensor '{}' has one scan: no step shows its cycle time (give the mapping's "
                                                               "sensors[{}].cycle_time_s)", mapped.sensor.id, s));
    }
    // Not value_or: the median of no steps must not be evaluated.
    rec.sensors[s].cycle_time_s = mapped.cycle_time_s ? *mapped.cycle_time_s : steps.median() / 1e6;
    if (!(rec.sensors[s].cycle_time_s > 0.0 && rec.sensors[s].cycle_time_s <= limits::kMaxCycleTime_s)) {
      throw InputError(log.string(), mapped.topic, fmt::format("the scans' median step {} s is no cycle time", rec.sensors[s].cycle_time_s));
    }
  }
  const ModelLibrary& library = ModelLibrary::builtin();
  for (const SurveyedObject& o : survey.objects) {
    // Ids are one line of a CSV file: a control character is refused here, described, not echoed.
    if (const auto bad = find_control_character(o.id)) {
      throw InputError(log.string(), mapping.objects_source(), fmt::format("an entity's id holds {}: ids are one line", *bad));
    }
    const auto mapped = mapping.classes.find(o.log_class);
    const std::string model = mapped != mapping.classes.end() ? mapped->second : o.log_class;
    if (!library.contains(model)) {
      throw InputError(log.string(), mapping.objects_source(),
                       fmt::format("entity '{}' has class '{}', no object model (rcsim models); map it in the mapping's "
                                   "objects.classes", o.id, o.log_class));
    }
    rec.objects.push_back({o.id, model, o.lengths_mm.median() / kMmPerM, o.widths_mm.median() / kMmPerM, nlohmann::json{{"log_class", o.log_class}}});
  }
  rec.cycle_time_s = mapping.annotation_step_s.value_or(survey.annotation_steps_us.empty() ? rec.sensors.front().cycle_time_s
                                                                                          : survey.annotation_steps_us.median() / 1e6);
  const robot_log::Log source(log);
  rec.description = fmt::format("{} {}: {} radar{} on their own clocks, {} annotated objects", source.kind(), source.name(),
                                rec.sensors.size(), rec.sensors.size() == 1 ? "" : "s", rec.objects.size());
  rec.source = {{"importer", "rcsim import --from mcap"},
                {"log", fs::path(log).lexically_normal().filename().string().empty() ? source.name() : log.filename().string()},
                {"mapping", options.mapping.filename().string()},
                {"boxes", mapping.openlabel.empty() ? "topic " + mapping.objects_topic : "OpenLABEL " + mapping.openlabel.filename().string()},
                {"first_timestamp_ns", t0_ns},
                {"profile", survey.log.profile},
                {"library", survey.log.library}};

  RowSink& sink = open_sink(rec);
  const std::size_t ego_duplicates =
      write_ego(survey.ego, t0_ns, log, mapping.ego.from_tf() ? mapping.ego.tf_topic : mapping.ego.topic, options.skip_edges, sink);
  CycleStream cycles(log, mapping, t0_ns, seconds_since(survey.ego.front().t_ns, t0_ns), seconds_since(survey.ego.back().t_ns, t0_ns),
                     options.skip_edges, sink);
  BoxStream boxes(log, mapping, survey, t0_ns, sink);
  for (const ObjectBox& b : labelled) boxes.add(b.object, b.box);
  std::vector<std::string> radar_frames;
  for (std::size_t s = 0; s < mapping.sensors.size(); ++s) radar_frames.push_back(mapping.sensors[s].frame.empty() ? survey.scan_frames[s] : mapping.sensors[s].frame);
  LogVisitor visit;
  visit.scan = [&](int sensor, ros2::RadarScan& scan) {
    const auto s = static_cast<std::size_t>(sensor);
    into_radar_frame(scan, survey, mapping, radar_frames[s], log, mapping.sensors[s].topic);
    cycles.add(sensor, scan);
  };
  // Each entity's box moved from its frame_id into the world.
  visit.box = [&](const foxglove::SceneBox& b) {
    LoggedBox box = logged_box(b);
    const std::string what = fmt::format("entity '{}' at {} ns", b.id, b.t_ns);
    try {
      const Pose2 X_WO = in_world(survey, mapping, std::string(b.frame_id), b.t_ns, Pose2{b.x_m, b.y_m, b.yaw_rad}, what);
      box.x_m = X_WO.x_m, box.y_m = X_WO.y_m, box.yaw_rad = as_float(X_WO.yaw_rad);
    } catch (const std::out_of_range& e) {
      throw InputError(log.string(), mapping.objects_topic, e.what());
    } catch (const TfError& e) {
      throw InputError(log.string(), mapping.objects_topic, what + ": " + e.what());
    }
    boxes.add(survey.object_index.at(std::string(b.id)), box);
  };
  read_log(log, mapping, visit);
  cycles.finish(), boxes.finish();
  ImportedLog imported{std::move(rec), cycles.targets(), survey.log.warnings};
  if (options.skip_edges) {
    imported.warnings.push_back(fmt::format("--skip-edges left out {} scan(s) beyond the ego log, {} scan(s) and {} ego pose(s) stamped "
                                            "as the one before", cycles.skipped_outside(), cycles.skipped_duplicates(), ego_duplicates));
  }
  return imported;
}

// Rows into a Recording.
struct RecordingRows : RowSink {
  explicit RecordingRows(Recording& r) : rec(r) { rec.boxes.assign(rec.objects.size(), {}); }
  void ego(const EgoSample& e) override { rec.ego.push_back(e); }
  void box(std::size_t object, const AnnotatedBox& b) override { rec.boxes[object].push_back(b); }
  void cycle(const SensorCycle& c, const std::vector<RecordedTarget>& targets) override {
    rec.cycles.push_back(c);
    rec.targets.insert(rec.targets.end(), targets.begin(), targets.end());
  }
  Recording& rec;
};

// Rows into a recording's files.
struct WrittenRows : RowSink {
  WrittenRows(const fs::path& dir, const Recording& header)
      : writer(dir, sensor_ids(header), TargetColumns{false, false, false, true}, true), objects(header.objects) {}
  static std::vector<std::string> sensor_ids(const Recording& header) {
    std::vector<std::string> ids;
    for (const RecordingSensor& s : header.sensors) ids.push_back(s.id);
    return ids;
  }
  void ego(const EgoSample& e) override { writer.ego(e); }
  void box(std::size_t object, const AnnotatedBox& b) override { writer.box(objects[object].id, b); }
  void cycle(const SensorCycle& c, const std::vector<RecordedTarget>& targets) override {
    writer.cycle(c);
    for (const RecordedTarget& t : targets) writer.target(t);
  }
  RecordingWriter writer;
  std::vector<RecordingObject> objects;
};

}  // namespace

DatasetRecording import_mcap(const fs::path& log, const DatasetImportOptions& options) {
  DatasetRecording out;
  std::unique_ptr<RecordingRows> rows;
  out.warnings = import_log(log, options, [&](const Recording& h) -> RowSink& {
                   out.recording = h;
                   rows = std::make_unique<RecordingRows>(out.recording);
                   return *rows;
                 }).warnings;
  return out;
}

ImportSummary import_mcap_to(const fs::path& log, const DatasetImportOptions& options, const fs::path& dir) {
  std::unique_ptr<WrittenRows> rows;
  std::size_t cycles = 0;
  struct Counting : RowSink {
    RowSink* inner = nullptr;
    std::size_t* cycles = nullptr;
    void ego(const EgoSample& e) override { inner->ego(e); }
    void box(std::size_t object, const AnnotatedBox& b) override { inner->box(object, b); }
    void cycle(const SensorCycle& c, const std::vector<RecordedTarget>& targets) override { inner->cycle(c, targets), ++*cycles; }
  } counting;
  const ImportedLog imported = import_log(log, options, [&](const Recording& h) -> RowSink& {
    rows = std::make_unique<WrittenRows>(dir, h);
    counting.inner = rows.get(), counting.cycles = &cycles;
    return counting;
  });
  rows->writer.finish(imported.header);
  const Recording& header = imported.header;
  return {header.name, cycles, header.sensors.size(), header.objects.size(), imported.targets, imported.warnings};
}

}  // namespace rcsim::replay
