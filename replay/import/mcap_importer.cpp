#include "replay/import/mcap_importer.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <optional>
#include <set>
#include <Eigen/Geometry>
#include <simdjson.h>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/list_level.hpp"
#include "common/quantile.hpp"
#include "common/text_file.hpp"
#include "io/mcap_reader.hpp"
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
  // A foxglove.PointCloud's fields that hold the radial speed and the amplitude.
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
    s.expect_only({"id", "topic", "type", "x_m", "y_m", "yaw_rad", "frame", "reports", "cycle_time_s", "fields"});
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
    if (s.has("cycle_time_s")) {
      mapped.cycle_time_s = s.number_within("cycle_time_s", 0.0, kMaxCycleTime_s, "s");
      require_positive(s, "cycle_time_s", *mapped.cycle_time_s);
    }
    if (mapped.sensor.id.empty()) s.fail("id", "must not be empty");
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

// One sensor cycle as logged: its stamp and its returns.
struct LoggedCycle {
  std::int64_t t_ns = 0;
  int sensor = 0;
  std::vector<ros2::RadarReturn> returns;
};

// One box as logged (an hour of a busy road holds millions: kept compact); its speed NaN where
// the log gives none.
struct LoggedBox {
  std::int64_t t_ns = 0;
  double x_m = 0.0, y_m = 0.0;
  float yaw_rad = 0.0f, speed_mps = 0.0f, length_m = 0.0f, width_m = 0.0f;
};

struct LoggedObject {
  std::string id, log_class;
  std::vector<LoggedBox> boxes;
  bool speed_missing = false;  // some box without a speed: all speeds from the positions
};

// One ego pose as logged (an hour at 100 Hz is 360,000: kept compact); a chain of transforms
// gives poses only, their speeds and yaw rates follow from them.
struct LoggedEgo {
  std::int64_t t_ns = 0;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, speed_mps = 0.0, yaw_rate_radps = 0.0;
};

// What the log holds on the mapped topics, in log order.
struct LoggedDrive {
  std::vector<LoggedCycle> cycles;
  std::vector<std::string> scan_frames;  // per sensor: its first scan's frame_id
  std::vector<LoggedEgo> ego;
  std::string odometry_frame, odometry_child_frame;  // the first Odometry's
  TfTree tf;
  std::vector<LoggedObject> objects;
  std::map<std::string, std::size_t> object_index;
  std::set<std::string> topics_seen;
  std::string profile, library;
};

void add_box(std::string_view id, std::string_view log_class, const LoggedBox& box, LoggedDrive& drive) {
  auto [it, added] = drive.object_index.try_emplace(std::string(id), drive.objects.size());
  if (added) drive.objects.push_back({std::string(id), std::string(log_class), {}, false});
  LoggedObject& object = drive.objects[it->second];
  if (object.log_class.empty()) object.log_class = log_class;
  object.boxes.push_back(box);
  object.speed_missing = object.speed_missing || std::isnan(box.speed_mps);
}

// Every box of a foxglove.SceneUpdate into its object's boxes.
void add_scene_update(simdjson::ondemand::parser& parser, const std::string& text, LoggedDrive& drive) {
  foxglove::for_each_scene_box(parser, text, [&](const foxglove::SceneBox& b) {
    const auto f = [](double v) { return static_cast<float>(v); };
    add_box(b.id, b.log_class,
            {b.t_ns, b.x_m, b.y_m, f(b.yaw_rad), f(b.speed_mps.value_or(std::nan(""))), f(b.length_m), f(b.width_m)}, drive);
  });
}

// A radar's foxglove.PointCloud as a scan: each point (x, y, z in the cloud's frame, moved by its
// pose into the radar's) a return with the mapped range-rate and amplitude fields.
ros2::RadarScan scan_of_point_cloud(simdjson::ondemand::parser& parser, const std::string& text, const MappedSensor& sensor) {
  const foxglove::PointCloud cloud =
      foxglove::decode_point_cloud(parser, text, {"x", "y", "z", sensor.range_rate_field, sensor.amplitude_field});
  ros2::RadarScan scan;
  scan.header.frame_id = cloud.frame_id;
  scan.header.stamp.sec = static_cast<std::int32_t>(cloud.t_ns / 1'000'000'000);
  scan.header.stamp.nanosec = static_cast<std::uint32_t>(cloud.t_ns % 1'000'000'000);
  const Eigen::Quaterniond q(cloud.orientation[3], cloud.orientation[0], cloud.orientation[1], cloud.orientation[2]);
  const Eigen::Vector3d t(cloud.position[0], cloud.position[1], cloud.position[2]);
  for (const std::vector<double>& p : cloud.points) {
    const Eigen::Vector3d p_S = q.normalized() * Eigen::Vector3d(p[0], p[1], p[2]) + t;
    const double ground_m = std::hypot(p_S.x(), p_S.y());
    ros2::RadarReturn r;
    r.range = static_cast<float>(p_S.norm());
    r.azimuth = static_cast<float>(std::atan2(p_S.y(), p_S.x()));
    r.elevation = static_cast<float>(std::atan2(p_S.z(), ground_m));
    r.doppler_velocity = static_cast<float>(p[3]);
    r.amplitude = static_cast<float>(p[4]);
    scan.returns.push_back(r);
  }
  return scan;
}

LoggedDrive read_log(const fs::path& log, const Mapping& mapping) {
  mcap::Reader reader(log);
  LoggedDrive drive;
  drive.profile = reader.summary().profile, drive.library = reader.summary().library;
  simdjson::ondemand::parser json_parser;
  std::map<std::string, int> sensor_of_topic;
  for (std::size_t s = 0; s < mapping.sensors.size(); ++s) sensor_of_topic[mapping.sensors[s].topic] = static_cast<int>(s);
  drive.scan_frames.resize(mapping.sensors.size());
  const MappedEgo& ego = mapping.ego;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& channel, const mcap::Schema* schema) {
    const auto sensor = sensor_of_topic.find(channel.topic);
    const bool is_ego = channel.topic == ego.topic, is_objects = channel.topic == mapping.objects_topic;
    const bool is_tf = ego.from_tf() && (channel.topic == ego.tf_topic || channel.topic == ego.tf_static_topic);
    if (sensor == sensor_of_topic.end() && !is_ego && !is_objects && !is_tf) return;
    drive.topics_seen.insert(channel.topic);
    const std::string schema_name = schema != nullptr ? schema->name : std::string("(none)");
    const std::string where = fmt::format("topic '{}', message {} at log time {} ns", channel.topic, m.sequence, m.log_time_ns);
    const auto expect = [&](std::string_view name, std::string_view encoding, std::string_view or_else = "") {
      if (schema_name != name || channel.message_encoding != encoding) {
        throw InputError(log.string(), where,
                         fmt::format("schema '{}' in '{}': the mapping takes {} in '{}'{} on this topic", schema_name,
                                     channel.message_encoding, name, encoding, or_else));
      }
    };
    try {
      if (sensor != sensor_of_topic.end()) {
        // A RadarScan in CDR, or a foxglove.PointCloud in JSON.
        const bool cloud = schema_name == "foxglove.PointCloud" && channel.message_encoding == "json";
        if (!cloud) expect(ros2::kRadarScanSchema, "cdr", " or foxglove.PointCloud in 'json'");
        ros2::RadarScan scan = cloud ? scan_of_point_cloud(json_parser, m.data, mapping.sensors[static_cast<std::size_t>(sensor->second)])
                                     : ros2::decode_radar_scan(m.data);
        std::string& frame = drive.scan_frames[static_cast<std::size_t>(sensor->second)];
        if (frame.empty()) frame = scan.header.frame_id;
        drive.cycles.push_back({scan.header.stamp.ns(), sensor->second, std::move(scan.returns)});
      } else if (is_ego) {
        expect(ros2::kOdometrySchema, "cdr");
        const ros2::Odometry o = ros2::decode_odometry(m.data);
        if (drive.ego.empty()) drive.odometry_frame = o.header.frame_id, drive.odometry_child_frame = o.child_frame_id;
        drive.ego.push_back({o.header.stamp.ns(), o.x_m, o.y_m, ros2::yaw_of_quaternion(o.qx, o.qy, o.qz, o.qw), o.vx_mps, o.wz_radps});
      } else if (is_tf) {
        expect(ros2::kTfMessageSchema, "cdr");
        drive.tf.add(ros2::decode_tf_message(m.data), channel.topic == ego.tf_static_topic);
      } else {
        expect("foxglove.SceneUpdate", "json");
        add_scene_update(json_parser, m.data, drive);
      }
    } catch (const ros2::CdrError& e) {
      throw InputError(log.string(), where, e.what());
    } catch (const TfError& e) {
      throw InputError(log.string(), where, e.what());
    } catch (const simdjson::simdjson_error& e) {
      throw InputError(log.string(), where, fmt::format("not a {}: {}", schema_name, e.what()));
    } catch (const std::logic_error& e) {  // a field missing or not a number (std::stod too)
      throw InputError(log.string(), where, fmt::format("not a {}: {}", schema_name, e.what()));
    }
  });
  for (const MappedSensor& s : mapping.sensors) {
    if (!drive.topics_seen.count(s.topic)) {
      std::vector<std::string> topics;
      for (const auto& [id, c] : reader.channels()) topics.push_back(c.topic);
      throw InputError(log.string(), s.topic, fmt::format("no messages on sensor '{}''s topic (the log's topics: {})", s.sensor.id,
                                                          fmt::join(topics, ", ")));
    }
  }
  if (ego.from_tf()) {
    if (!drive.topics_seen.count(ego.tf_topic)) throw InputError(log.string(), ego.tf_topic, "no transforms: the ego's chain is read from them");
    drive.tf.finish();
  } else if (!drive.topics_seen.count(ego.topic)) {
    throw InputError(log.string(), ego.topic, "no messages on the ego topic");
  }
  return drive;
}

double seconds_since(std::int64_t t_ns, std::int64_t t0_ns) { return static_cast<double>(t_ns - t0_ns) * 1e-9; }

// The median step of increasing times (s); `fallback` where there are fewer than two.
double median_step_s(const std::vector<double>& t_s, double fallback) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < t_s.size(); ++i) steps.push_back(t_s[i] - t_s[i - 1]);
  return steps.empty() ? fallback : median(steps);
}

// The ego as the chain of transforms from the vehicle's frame to the world frame: a pose at each
// stamp of the chain's densest moving transform; speed along the heading and yaw rate by central
// differences of the poses (one-sided at the ends).
void ego_from_tf(LoggedDrive& drive, const fs::path& log, const MappedEgo& ego) {
  std::vector<std::int64_t> stamps;
  try {
    stamps = drive.tf.chain_stamps(ego.vehicle_frame, ego.world_frame);
    for (const std::int64_t t_ns : stamps) {
      const Eigen::Isometry3d X_WV = drive.tf.pose(ego.vehicle_frame, ego.world_frame, t_ns);
      const Eigen::Matrix3d R_WV = X_WV.linear();
      drive.ego.push_back({t_ns, X_WV.translation().x(), X_WV.translation().y(), std::atan2(R_WV(1, 0), R_WV(0, 0)), 0.0, 0.0});
    }
  } catch (const TfError& e) {
    throw InputError(log.string(), ego.tf_topic, fmt::format("the ego from '{}' to '{}': {}", ego.vehicle_frame, ego.world_frame, e.what()));
  }
  if (stamps.size() < 2) {
    throw InputError(log.string(), ego.tf_topic, fmt::format("the chain from '{}' to '{}' moves at {} stamp(s): no ego motion to read",
                                                          ego.vehicle_frame, ego.world_frame, stamps.size()));
  }
  std::vector<LoggedEgo>& e = drive.ego;
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
void mount_from_tf(const LoggedDrive& drive, const fs::path& log, const Mapping& mapping, Recording& rec) {
  for (std::size_t s = 0; s < mapping.sensors.size(); ++s) {
    const MappedSensor& mapped = mapping.sensors[s];
    if (!mapped.mounting_from_tf) continue;
    const std::string& frame = mapped.frame.empty() ? drive.scan_frames[s] : mapped.frame;
    const auto first = std::find_if(drive.cycles.begin(), drive.cycles.end(),
                                    [&](const LoggedCycle& c) { return c.sensor == static_cast<int>(s); });
    RecordingSensor& sensor = rec.sensors[s];
    try {
      const Eigen::Isometry3d X_VS = drive.tf.pose(frame, mapping.ego.vehicle_frame, first->t_ns);
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

// The boxes of an OpenLABEL file beside the log, in the ego's world frame: a cuboid in the world
// frame (or in none named) as it is; one in another frame of /tf (the vehicle's, a sensor's)
// through the transforms at its time; with an Odometry ego, one in the odometry's child frame (the
// vehicle's) through the odometry's pose at its time. Planar: z and the height are dropped.
void add_openlabel(LoggedDrive& drive, const Mapping& mapping) {
  const openlabel::Labels labels = openlabel::read_openlabel(mapping.openlabel);
  const bool tf = mapping.ego.from_tf();
  const std::string& world = tf ? mapping.ego.world_frame : drive.odometry_frame;
  const std::string& vehicle = tf ? mapping.ego.vehicle_frame : drive.odometry_child_frame;
  const auto f = [](double v) { return static_cast<float>(v); };
  for (const openlabel::LabelledBox& b : labels.boxes) {
    Pose2 X_WO{b.x_m, b.y_m, b.yaw_rad};
    const std::string& frame = b.coordinate_system;
    const std::string what = fmt::format("object '{}''s cuboid", b.uid);
    try {
      if (!frame.empty() && frame != world) {
        Pose2 X_WC;
        if (tf) {
          const Eigen::Isometry3d X = drive.tf.pose(frame, world, b.t_ns);
          X_WC = {X.translation().x(), X.translation().y(), std::atan2(X.linear()(1, 0), X.linear()(0, 0))};
        } else if (frame == vehicle) {
          X_WC = odometry_pose(drive.ego, b.t_ns, what);
        } else {
          throw std::out_of_range(fmt::format("{} is in coordinate system '{}': neither the odometry's world frame '{}' nor its "
                                              "vehicle frame '{}' (map the ego as a /tf chain to use other frames)",
                                              what, frame, world, vehicle));
        }
        X_WO = compose(X_WC, X_WO);
      }
    } catch (const std::out_of_range& e) {
      throw InputError(mapping.openlabel.string(), "openlabel.objects." + b.uid, e.what());
    } catch (const TfError& e) {
      throw InputError(mapping.openlabel.string(), "openlabel.objects." + b.uid, what + ": " + e.what());
    }
    add_box(b.uid, b.type, {b.t_ns, X_WO.x_m, X_WO.y_m, f(X_WO.yaw_rad), f(b.speed_mps.value_or(std::nan(""))), f(b.length_m), f(b.width_m)},
            drive);
  }
}

void add_ego(LoggedDrive& drive, std::int64_t t0_ns, const fs::path& log, const std::string& topic, Recording& rec) {
  std::vector<LoggedEgo>& ego = drive.ego;  // times increasing
  rec.ego.reserve(ego.size());
  for (std::size_t i = 0; i < ego.size(); ++i) {
    const LoggedEgo& e = ego[i];
    if (i > 0 && e.t_ns == ego[i - 1].t_ns) throw InputError(log.string(), topic, fmt::format("two ego poses stamped {} ns", e.t_ns));
    rec.ego.push_back({seconds_since(e.t_ns, t0_ns), e.x_m, e.y_m, e.yaw_rad, e.speed_mps, e.yaw_rate_radps});
    if (i > 0 && rec.ego.back().t_s - rec.ego[i - 1].t_s > kMaxEgoLogStep_s) {
      throw InputError(log.string(), topic,
                       fmt::format("{:.3f} s without an ego pose after {:.6f} s (at most {} s are interpolated)",
                                   rec.ego.back().t_s - rec.ego[i - 1].t_s, rec.ego[i - 1].t_s, kMaxEgoLogStep_s));
    }
  }
  ego = {};  // memory back
  // The yaw unwrapped, so that interpolation never turns the long way (ego.csv allows any yaw).
  for (std::size_t i = 1; i < rec.ego.size(); ++i) {
    rec.ego[i].yaw_rad = rec.ego[i - 1].yaw_rad + angle_difference_rad(rec.ego[i].yaw_rad, rec.ego[i - 1].yaw_rad);
  }
}

void add_cycles(LoggedDrive& drive, std::int64_t t0_ns, const fs::path& log, const Mapping& mapping, Recording& rec) {
  std::stable_sort(drive.cycles.begin(), drive.cycles.end(), [](const LoggedCycle& a, const LoggedCycle& b) {
    return a.t_ns != b.t_ns ? a.t_ns < b.t_ns : a.sensor < b.sensor;
  });
  std::size_t returns = 0;
  for (const LoggedCycle& c : drive.cycles) returns += c.returns.size();
  rec.targets.reserve(returns);
  rec.cycles.reserve(drive.cycles.size());
  std::vector<std::vector<double>> times(rec.sensors.size());
  const double first_ego_s = rec.ego.front().t_s, last_ego_s = rec.ego.back().t_s;
  for (const LoggedCycle& c : drive.cycles) {
    const double t_s = seconds_since(c.t_ns, t0_ns);
    const auto s = static_cast<std::size_t>(c.sensor);
    const std::string& topic = mapping.sensors[s].topic;
    if (!times[s].empty() && t_s <= times[s].back()) {
      throw InputError(log.string(), topic, fmt::format("two scans stamped {:.9f} s after the log's start", t_s));
    }
    if (t_s < first_ego_s - kEgoExtrapolationMargin_s || t_s > last_ego_s + kEgoExtrapolationMargin_s) {
      throw InputError(log.string(), topic,
                       fmt::format("a scan at {:.6f} s lies beyond the ego log's {:.6f} to {:.6f} s by more than {} s", t_s,
                                   first_ego_s, last_ego_s, kEgoExtrapolationMargin_s));
    }
    times[s].push_back(t_s);
    const int cycle = static_cast<int>(rec.cycles.size());
    rec.cycles.push_back({t_s, c.sensor});
    for (const ros2::RadarReturn& r : c.returns) {
      RecordedTarget t;
      t.t_s = t_s, t.cycle = cycle, t.sensor = c.sensor;
      // The planar model's range: the slant range over the ground.
      t.range_m = static_cast<double>(r.range) * std::cos(static_cast<double>(r.elevation));
      t.azimuth_rad = r.azimuth, t.elevation_rad = r.elevation;
      t.range_rate_mps = r.doppler_velocity, t.amplitude_db = r.amplitude;
      if (!std::isfinite(t.range_m) || t.range_m < 0.0 || t.range_m > limits::kMaxRange_m ||
          std::abs(t.azimuth_rad) > limits::kMaxAzimuth_rad || std::abs(t.range_rate_mps) > limits::kMaxSpeed_mps ||
          !std::isfinite(t.amplitude_db) || std::abs(t.amplitude_db) > limits::kMaxLevel_dB || std::abs(t.elevation_rad) > 1.58) {
        throw InputError(log.string(), topic,
                         fmt::format("a return at {:.6f} s beyond the limits of schemas/limits.md (range {}, azimuth {}, "
                                     "elevation {}, doppler_velocity {}, amplitude {})",
                                     t_s, r.range, r.azimuth, r.elevation, r.doppler_velocity, r.amplitude));
      }
      rec.targets.push_back(t);
    }
  }
  drive.cycles = {};  // the targets hold them now: memory back
  for (std::size_t s = 0; s < rec.sensors.size(); ++s) {
    const MappedSensor& mapped = mapping.sensors[s];
    rec.sensors[s].cycle_time_s = mapped.cycle_time_s.value_or(median_step_s(times[s], 0.05));
    if (!(rec.sensors[s].cycle_time_s > 0.0 && rec.sensors[s].cycle_time_s <= limits::kMaxCycleTime_s)) {
      throw InputError(log.string(), mapped.topic, fmt::format("the scans' median step {} s is no cycle time", rec.sensors[s].cycle_time_s));
    }
  }
}

// Boxes logged without speed_mps: each one's speed along its heading from its neighbours'
// positions (central differences, one-sided at the ends; times increasing).
void set_speeds_from_positions(std::vector<AnnotatedBox>& boxes) {
  if (boxes.size() < 2) return;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const AnnotatedBox& a = boxes[i == 0 ? 0 : i - 1];
    const AnnotatedBox& b = boxes[i + 1 == boxes.size() ? i : i + 1];
    const Vec2 v_W((b.x_m - a.x_m) / (b.t_s - a.t_s), (b.y_m - a.y_m) / (b.t_s - a.t_s));
    boxes[i].speed_mps = speed_along_heading_mps(v_W, boxes[i].yaw_rad);
  }
}

void add_objects(LoggedDrive& drive, std::int64_t t0_ns, const fs::path& log, const Mapping& mapping, Recording& rec,
                 std::vector<double>& annotation_times_s) {
  const ModelLibrary& library = ModelLibrary::builtin();
  rec.boxes.clear();
  for (LoggedObject& o : drive.objects) {
    const auto mapped = mapping.classes.find(o.log_class);
    const std::string model = mapped != mapping.classes.end() ? mapped->second : o.log_class;
    if (!library.contains(model)) {
      throw InputError(log.string(), mapping.objects_source(),
                       fmt::format("entity '{}' has class '{}', no object model (rcsim models); map it in the mapping's "
                                   "objects.classes", o.id, o.log_class));
    }
    std::vector<AnnotatedBox> boxes;
    boxes.reserve(o.boxes.size());
    std::vector<double> lengths_m, widths_m;
    for (const LoggedBox& b : o.boxes) {
      boxes.push_back({seconds_since(b.t_ns, t0_ns), b.x_m, b.y_m, b.yaw_rad, std::isnan(b.speed_mps) ? 0.0 : b.speed_mps, 0});
      annotation_times_s.push_back(boxes.back().t_s);
      lengths_m.push_back(b.length_m), widths_m.push_back(b.width_m);
    }
    o.boxes = {};  // done with: memory back
    std::stable_sort(boxes.begin(), boxes.end(), [](const AnnotatedBox& a, const AnnotatedBox& b) { return a.t_s < b.t_s; });
    for (std::size_t i = 1; i < boxes.size(); ++i) {
      if (boxes[i].t_s <= boxes[i - 1].t_s) {
        throw InputError(log.string(), mapping.objects_source(), fmt::format("entity '{}' twice at {:.6f} s", o.id, boxes[i].t_s));
      }
    }
    if (o.speed_missing) set_speeds_from_positions(boxes);
    rec.objects.push_back({o.id, model, median(lengths_m), median(widths_m), nlohmann::json{{"log_class", o.log_class}}});
    rec.boxes.push_back(std::move(boxes));
  }
}

}  // namespace

DatasetRecording import_mcap(const fs::path& log, const DatasetImportOptions& options) {
  if (options.mapping.empty()) {
    throw InputError(log.string(), "--mapping", "an MCAP log needs a mapping file: which topic is which radar, the ego, the boxes "
                                                "(schemas/mcap-mapping.md)");
  }
  if (!options.ego_log.empty()) throw InputError(log.string(), "--ego-log", "an MCAP log carries its ego motion (the mapping's ego topic)");
  if (!options.frames.empty()) throw InputError(log.string(), "--frames", "takes the frames of a dataset of single frames (--from astyx)");
  const Mapping mapping = read_mapping(options.mapping);
  LoggedDrive drive = read_log(log, mapping);
  if (mapping.ego.from_tf()) ego_from_tf(drive, log, mapping.ego);
  std::stable_sort(drive.ego.begin(), drive.ego.end(), [](const LoggedEgo& a, const LoggedEgo& b) { return a.t_ns < b.t_ns; });
  if (!mapping.openlabel.empty()) add_openlabel(drive, mapping);
  // The recording's clock: seconds since the earliest stamp of the mapped topics.
  std::int64_t t0_ns = drive.ego.front().t_ns;
  for (const LoggedEgo& e : drive.ego) t0_ns = std::min(t0_ns, e.t_ns);
  for (const LoggedCycle& c : drive.cycles) t0_ns = std::min(t0_ns, c.t_ns);
  for (const LoggedObject& o : drive.objects) {
    for (const LoggedBox& b : o.boxes) t0_ns = std::min(t0_ns, b.t_ns);
  }
  DatasetRecording out;
  Recording& rec = out.recording;
  rec.name = mapping.name.empty() ? log.stem().string() : mapping.name;
  rec.clock = Clock::per_sensor;
  for (const MappedSensor& s : mapping.sensors) rec.sensors.push_back(s.sensor);
  mount_from_tf(drive, log, mapping, rec);
  add_ego(drive, t0_ns, log, mapping.ego.from_tf() ? mapping.ego.tf_topic : mapping.ego.topic, rec);
  add_cycles(drive, t0_ns, log, mapping, rec);
  std::vector<double> annotation_times_s;
  add_objects(drive, t0_ns, log, mapping, rec, annotation_times_s);
  std::sort(annotation_times_s.begin(), annotation_times_s.end());
  annotation_times_s.erase(std::unique(annotation_times_s.begin(), annotation_times_s.end()), annotation_times_s.end());
  rec.cycle_time_s = mapping.annotation_step_s.value_or(median_step_s(annotation_times_s, rec.sensors.front().cycle_time_s));
  rec.description = fmt::format("MCAP log {}: {} radar{} on their own clocks, {} annotated objects", log.filename().string(),
                                rec.sensors.size(), rec.sensors.size() == 1 ? "" : "s", rec.objects.size());
  rec.source = {{"importer", "rcsim import --from mcap"},
                {"log", log.filename().string()},
                {"mapping", options.mapping.filename().string()},
                {"boxes", mapping.openlabel.empty() ? "topic " + mapping.objects_topic : "OpenLABEL " + mapping.openlabel.filename().string()},
                {"first_timestamp_ns", t0_ns},
                {"profile", drive.profile},
                {"library", drive.library}};
  return out;
}

}  // namespace rcsim::replay
