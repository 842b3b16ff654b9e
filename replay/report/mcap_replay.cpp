#include "replay/report/mcap_replay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <variant>
#include <vector>

#include "common/pose2.hpp"
#include "io/mcap_writer.hpp"
#include "metrics/target_class.hpp"
#include "replay/report/svg_plot.hpp"
#include "replay/store/decoded_rows.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

namespace mcap_replay_internal {

using Json = nlohmann::ordered_json;

constexpr double kBoxHeightM = 1.5;    // the boxes are 2-D: drawn 1.5 m tall
constexpr double kTargetSizeM = 0.5;   // a target's sphere or cube
constexpr int kViewFieldSegments = 32;
// Every channel names the format (schemas/mcap-replay.md).
const std::map<std::string, std::string> kFormat = {{"format", "rcsim-mcap-replay"}, {"version", "1"}};

// JSON Schemas of the messages (Foxglove knows its own by name; the schema lets a client list
// the fields). Kept to the fields written.
const char* const kTimeSchema = R"({"type": "object", "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}}})";
std::string vector3_schema() { return R"({"type": "object", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}}})"; }
std::string quaternion_schema() {
  return R"({"type": "object", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}, "w": {"type": "number"}}})";
}
std::string frame_transform_schema() {
  return fmt::format(R"({{"title": "foxglove.FrameTransform", "type": "object", "properties": {{"timestamp": {}, "parent_frame_id": {{"type": "string"}}, "child_frame_id": {{"type": "string"}}, "translation": {}, "rotation": {}}}}})",
                     kTimeSchema, vector3_schema(), quaternion_schema());
}
std::string scene_update_schema() {
  const std::string pose = fmt::format(R"({{"type": "object", "properties": {{"position": {}, "orientation": {}}}}})", vector3_schema(), quaternion_schema());
  const std::string color = R"({"type": "object", "properties": {"r": {"type": "number"}, "g": {"type": "number"}, "b": {"type": "number"}, "a": {"type": "number"}}})";
  const std::string shape = fmt::format(R"({{"type": "array", "items": {{"type": "object", "properties": {{"pose": {}, "size": {}, "color": {}}}}}}})", pose, vector3_schema(), color);
  const std::string line = fmt::format(R"({{"type": "array", "items": {{"type": "object", "properties": {{"type": {{"type": "integer"}}, "pose": {}, "thickness": {{"type": "number"}}, "scale_invariant": {{"type": "boolean"}}, "points": {{"type": "array", "items": {}}}, "color": {}, "colors": {{"type": "array"}}, "indices": {{"type": "array"}}}}}}}})",
                                       pose, vector3_schema(), color);
  const std::string text = fmt::format(R"({{"type": "array", "items": {{"type": "object", "properties": {{"pose": {}, "billboard": {{"type": "boolean"}}, "font_size": {{"type": "number"}}, "scale_invariant": {{"type": "boolean"}}, "color": {}, "text": {{"type": "string"}}}}}}}})",
                                       pose, color);
  const std::string entity = fmt::format(R"({{"type": "object", "properties": {{"timestamp": {0}, "frame_id": {{"type": "string"}}, "id": {{"type": "string"}}, "lifetime": {0}, "frame_locked": {{"type": "boolean"}}, "metadata": {{"type": "array"}}, "arrows": {{"type": "array"}}, "cubes": {1}, "spheres": {1}, "cylinders": {{"type": "array"}}, "lines": {2}, "triangles": {{"type": "array"}}, "texts": {3}, "models": {{"type": "array"}}}}}})",
                                         kTimeSchema, shape, line, text);
  return fmt::format(R"({{"title": "foxglove.SceneUpdate", "type": "object", "properties": {{"deletions": {{"type": "array"}}, "entities": {{"type": "array", "items": {}}}}}}})", entity);
}
std::string cycle_figures_schema() {
  Json properties = Json::object();
  for (const DecodedColumn& c : decoded_columns(DecodedTable::cycles)) {
    properties[c.name] = {{"type", c.sql_type == "TEXT" ? "string" : (c.sql_type == "INTEGER" ? "integer" : "number")}};
  }
  return Json{{"title", "rcsim.CycleFigures"}, {"type", "object"}, {"properties", properties}}.dump();
}

std::uint64_t time_ns(double t_s) { return static_cast<std::uint64_t>(std::llround(std::max(0.0, t_s) * 1e9)); }
Json time_json(std::uint64_t ns) { return {{"sec", ns / 1000000000}, {"nsec", ns % 1000000000}}; }
Json vec3(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
Json yaw_quaternion(double yaw_rad) { return {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(0.5 * yaw_rad)}, {"w", std::cos(0.5 * yaw_rad)}}; }
Json pose_json(double x_m, double y_m, double z_m, double yaw_rad) { return {{"position", vec3(x_m, y_m, z_m)}, {"orientation", yaw_quaternion(yaw_rad)}}; }

// "#1f5fbf" as Foxglove's colour, components 0..1.
Json colour(const char* hex, double alpha = 1.0) {
  const auto component = [&](int i) { return std::stoi(std::string(hex + 1 + 2 * i, 2), nullptr, 16) / 255.0; };
  return {{"r", component(0)}, {"g", component(1)}, {"b", component(2)}, {"a", alpha}};
}

Json entity(std::uint64_t ns, const std::string& frame_id, const std::string& id, std::uint64_t lifetime_ns) {
  return {{"timestamp", time_json(ns)}, {"frame_id", frame_id}, {"id", id}, {"lifetime", time_json(lifetime_ns)},
          {"frame_locked", false}, {"metadata", Json::array()}, {"arrows", Json::array()}, {"cubes", Json::array()},
          {"spheres", Json::array()}, {"cylinders", Json::array()}, {"lines", Json::array()}, {"triangles", Json::array()},
          {"texts", Json::array()}, {"models", Json::array()}};
}

Json scene_update(Json entities) { return {{"deletions", Json::array()}, {"entities", std::move(entities)}}; }

Json transform(std::uint64_t ns, const std::string& parent, const std::string& child, const Pose2& X_PC) {
  return {{"timestamp", time_json(ns)}, {"parent_frame_id", parent}, {"child_frame_id", child},
          {"translation", vec3(X_PC.x_m, X_PC.y_m, 0.0)}, {"rotation", yaw_quaternion(X_PC.yaw_rad)}};
}

const char* class_colour(const StoredTarget& t) {
  if (t.target_class == metrics::TargetClass::stationary_background) return svg::kBackgroundColour;
  if (t.target_class == metrics::TargetClass::other) return svg::kOtherColour;
  return t.simulated ? svg::kSimulatedColour : svg::kRecordedColour;
}

// The view field as a closed line in the sensor's frame: its origin, the arc, back.
Json view_field_entity(const report::SensorInfo& s, const std::string& frame, std::uint64_t ns) {
  Json points = Json::array({vec3(0, 0, 0)});
  for (int i = 0; i <= kViewFieldSegments; ++i) {
    const double a = -s.azimuth_half_rad + 2.0 * s.azimuth_half_rad * i / kViewFieldSegments;
    const Vec2 p = point_from_polar(s.max_range_m, a);
    points.push_back(vec3(p.x(), p.y(), 0.0));
  }
  points.push_back(vec3(0, 0, 0));
  Json e = entity(ns, frame, "view_field", 0);
  e["frame_locked"] = true;
  e["lines"].push_back({{"type", 0}, {"pose", pose_json(0, 0, 0, 0)}, {"thickness", 2.0}, {"scale_invariant", true},
                        {"points", points}, {"color", colour("#2b8a3e", 0.8)}, {"colors", Json::array()}, {"indices", Json::array()}});
  return e;
}

Json figures_json(const std::vector<DecodedValue>& row) {
  Json out = Json::object();
  const auto& columns = decoded_columns(DecodedTable::cycles);
  for (std::size_t i = 0; i < row.size(); ++i) {
    std::visit(
        [&](const auto& v) {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) {
            out[columns[i].name] = nullptr;
          } else {
            out[columns[i].name] = v;
          }
        },
        row[i]);
  }
  return out;
}

// The rows of one block of cycles, by cycle.
struct CycleBlock {
  std::map<int, std::vector<std::vector<DecodedValue>>> figures;  // cycle -> a row per sensor
  std::map<int, std::vector<StoredCycle>> cycles;
  std::map<int, std::vector<StoredTarget>> targets;
  std::map<int, std::vector<StoredObjectState>> boxes;
};

class McapReplayWriter {
 public:
  McapReplayWriter(ReportDatabase& db, std::int64_t run_id, std::ostream& out)
      : db_(db), run_id_(run_id), run_(report::load_run(db, run_id)), writer_(out) {
    scene_ = writer_.add_schema("foxglove.SceneUpdate", "jsonschema", scene_update_schema());
    transform_ = writer_.add_schema("foxglove.FrameTransform", "jsonschema", frame_transform_schema());
    figures_ = writer_.add_schema("rcsim.CycleFigures", "jsonschema", cycle_figures_schema());
    tf_channel_ = writer_.add_channel("/tf", "json", transform_, kFormat);
    boxes_channel_ = writer_.add_channel(mcap_replay_topic("", "boxes"), "json", scene_, kFormat);
    for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
      SensorChannels c;
      c.frame = mcap_frame_name(run_.sensors[i].id, static_cast<int>(i), frames_);
      frames_.push_back(c.frame);
      c.recorded = writer_.add_channel(mcap_replay_topic(c.frame, "recorded"), "json", scene_, kFormat);
      c.simulated = writer_.add_channel(mcap_replay_topic(c.frame, "simulated"), "json", scene_, kFormat);
      c.view_field = writer_.add_channel(mcap_replay_topic(c.frame, "view_field"), "json", scene_, kFormat);
      c.figures = writer_.add_channel(mcap_replay_topic(c.frame, "figures"), "json", figures_, kFormat);
      sensor_channels_.push_back(c);
    }
    lifetime_ns_ = time_ns(run_.info.cycle_time_s);
  }

  McapReplayCounts write() {
    const int last = last_stored_cycle(db_, run_id_);
    for (int first = 0; first <= last; first += kBlockCycles) write_block(read_block({first, std::min(last, first + kBlockCycles - 1)}));
    counts_.bytes = writer_.finish();
    counts_.sensors = static_cast<int>(run_.sensors.size());
    return counts_;
  }

 private:
  struct SensorChannels {
    std::string frame;  // the sensor's frame id and its topics' middle part
    std::uint16_t recorded = 0, simulated = 0, view_field = 0, figures = 0;
  };

  CycleBlock read_block(CycleSpan span) {
    CycleBlock b;
    for_each_decoded_row(db_, DecodedTable::cycles, run_id_, span, [&](const auto& row) {
      b.figures[static_cast<int>(std::get<std::int64_t>(row[1]))].push_back(row);
    });
    for_each_cycle(db_, run_id_, span, [&](const StoredCycle& c) { b.cycles[c.cycle].push_back(c); });
    if (run_.info.has_targets()) {
      for_each_target(db_, run_id_, span, [&](const StoredTarget& t) { b.targets[t.cycle].push_back(t); });
      for_each_object_state(db_, run_id_, span, [&](const StoredObjectState& s) { b.boxes[s.cycle].push_back(s); });
    }
    return b;
  }

  void message(std::uint16_t channel, std::uint64_t ns, const Json& body) {
    writer_.write_message(channel, ns, body.dump());
    ++counts_.messages;
  }

  // What holds for the whole run, at its first cycle's time: the mountings and the view fields.
  void write_static(std::uint64_t ns) {
    for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
      const report::SensorInfo& s = run_.sensors[i];
      message(tf_channel_, ns, transform(ns, "ego", sensor_channels_[i].frame, s.X_VS));
      message(sensor_channels_[i].view_field, ns, scene_update(Json::array({view_field_entity(s, sensor_channels_[i].frame, ns)})));
    }
  }

  void write_block(const CycleBlock& b) {
    for (const auto& [cycle, sensors] : b.cycles) {
      const std::uint64_t ns = time_ns(sensors.front().t_s);
      if (!static_written_) write_static(ns), static_written_ = true;
      write_ego(ns, sensors);
      write_boxes(ns, b.boxes.count(cycle) ? b.boxes.at(cycle) : std::vector<StoredObjectState>{});
      const auto targets = b.targets.find(cycle);
      for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
        write_targets(ns, static_cast<int>(i), targets == b.targets.end() ? nullptr : &targets->second);
      }
      for (const auto& row : b.figures.at(cycle)) {
        const auto sensor = static_cast<std::size_t>(std::get<std::int64_t>(row[2]));
        if (sensor < sensor_channels_.size()) message(sensor_channels_[sensor].figures, ns, figures_json(row));
      }
      ++counts_.cycles;
    }
  }

  // The ego in the world from a sensor's pose and mounting: X_WV = X_WS X_VS^-1 (a summary run
  // keeps no poses: the ego stays at the world's origin).
  void write_ego(std::uint64_t ns, const std::vector<StoredCycle>& sensors) {
    for (const StoredCycle& c : sensors) {
      if (!c.X_WS || c.sensor < 0 || static_cast<std::size_t>(c.sensor) >= run_.sensors.size()) continue;
      const Pose2 X_WV = compose(*c.X_WS, inverse(run_.sensors[static_cast<std::size_t>(c.sensor)].X_VS));
      message(tf_channel_, ns, transform(ns, "world", "ego", X_WV));
      return;
    }
    if (!ego_at_origin_) message(tf_channel_, ns, transform(ns, "world", "ego", Pose2{})), ego_at_origin_ = true;
  }

  void write_boxes(std::uint64_t ns, const std::vector<StoredObjectState>& boxes) {
    Json e = entity(ns, "world", "boxes", lifetime_ns_);
    for (const StoredObjectState& s : boxes) {
      const report::ObjectInfo* o = s.object >= 0 && static_cast<std::size_t>(s.object) < run_.objects.size() ? &run_.objects[static_cast<std::size_t>(s.object)] : nullptr;
      const Json pose = pose_json(s.X_WO.x_m, s.X_WO.y_m, 0.5 * kBoxHeightM, s.X_WO.yaw_rad);
      e["cubes"].push_back({{"pose", pose}, {"size", vec3(o ? o->length_m : 4.5, o ? o->width_m : 1.8, kBoxHeightM)},
                            {"color", colour("#868e96", 0.35)}});
      e["texts"].push_back({{"pose", pose_json(s.X_WO.x_m, s.X_WO.y_m, kBoxHeightM + 0.5, 0.0)}, {"billboard", true},
                            {"font_size", 14.0}, {"scale_invariant", true}, {"color", colour("#343a40")},
                            {"text", run_.object_label(s.object)}});
    }
    message(boxes_channel_, ns, scene_update(Json::array({e})));
  }

  // A sensor's recorded targets as spheres and its simulated ones as cubes, in its own frame.
  void write_targets(std::uint64_t ns, int sensor, const std::vector<StoredTarget>* targets) {
    const std::string& frame = sensor_channels_[static_cast<std::size_t>(sensor)].frame;
    Json recorded = entity(ns, frame, "recorded", lifetime_ns_), simulated = entity(ns, frame, "simulated", lifetime_ns_);
    if (targets != nullptr) {
      for (const StoredTarget& t : *targets) {
        if (t.sensor != sensor) continue;
        const Vec2 p = t.p_ST_S();
        const double z_m = std::isfinite(t.elevation_rad) ? t.range_m * std::sin(t.elevation_rad) : 0.0;
        Json shape = {{"pose", pose_json(p.x(), p.y(), z_m, 0.0)}, {"size", vec3(kTargetSizeM, kTargetSizeM, kTargetSizeM)},
                      {"color", colour(class_colour(t))}};
        (t.simulated ? simulated["cubes"] : recorded["spheres"]).push_back(std::move(shape));
      }
    }
    message(sensor_channels_[static_cast<std::size_t>(sensor)].recorded, ns, scene_update(Json::array({recorded})));
    message(sensor_channels_[static_cast<std::size_t>(sensor)].simulated, ns, scene_update(Json::array({simulated})));
  }

  ReportDatabase& db_;
  std::int64_t run_id_;
  report::RunData run_;
  mcap::Writer writer_;
  std::uint16_t scene_ = 0, transform_ = 0, figures_ = 0, tf_channel_ = 0, boxes_channel_ = 0;
  std::vector<SensorChannels> sensor_channels_;
  std::vector<std::string> frames_;
  std::uint64_t lifetime_ns_ = 0;
  bool static_written_ = false, ego_at_origin_ = false;
  McapReplayCounts counts_;
};

}  // namespace mcap_replay_internal

std::string mcap_frame_name(const std::string& sensor_id, int sensor, const std::vector<std::string>& taken) {
  std::string name;
  for (const char c : sensor_id) name += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
  if (name.empty() || name == "world" || name == "ego" || name == "boxes" ||
      std::find(taken.begin(), taken.end(), name) != taken.end()) {
    name = fmt::format("sensor_{}", sensor);
  }
  return name;
}

std::string mcap_replay_topic(const std::string& sensor_id, const std::string& what) {
  return sensor_id.empty() ? "/rcsim/" + what : "/rcsim/" + sensor_id + "/" + what;
}

McapReplayCounts write_run_mcap(ReportDatabase& db, std::int64_t run_id, std::ostream& out) {
  return mcap_replay_internal::McapReplayWriter(db, run_id, out).write();
}

}  // namespace rcsim::replay
