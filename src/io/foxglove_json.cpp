#include "io/foxglove_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/target_colours.hpp"

namespace rcsim::foxglove {

// JSON Schemas of the messages (Foxglove knows its own by name; the schema lets a client list
// the fields). Kept to the fields written.
namespace {

constexpr int kViewFieldSegments = 32;

const char* const kTimeSchema = R"({"type": "object", "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}}})";
std::string vector3_schema() { return R"({"type": "object", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}}})"; }
std::string quaternion_schema() {
  return R"({"type": "object", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}, "w": {"type": "number"}}})";
}
}  // namespace

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

std::uint64_t time_ns(double t_s) { return static_cast<std::uint64_t>(std::llround(std::max(0.0, t_s) * 1e9)); }
Json time_json(std::uint64_t ns) { return {{"sec", ns / 1000000000}, {"nsec", ns % 1000000000}}; }
Json vec3(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
Json yaw_quaternion(double yaw_rad) { return {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(0.5 * yaw_rad)}, {"w", std::cos(0.5 * yaw_rad)}}; }
Json pose_json(double x_m, double y_m, double z_m, double yaw_rad) { return {{"position", vec3(x_m, y_m, z_m)}, {"orientation", yaw_quaternion(yaw_rad)}}; }

Json colour(const char* hex, double alpha) {
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

Json frame_transform(std::uint64_t ns, const std::string& parent, const std::string& child, const Pose2& X_PC) {
  return {{"timestamp", time_json(ns)}, {"parent_frame_id", parent}, {"child_frame_id", child},
          {"translation", vec3(X_PC.x_m, X_PC.y_m, 0.0)}, {"rotation", yaw_quaternion(X_PC.yaw_rad)}};
}


Json view_field_entity(const std::string& frame, double azimuth_half_rad, double max_range_m, std::uint64_t ns) {
  Json points = Json::array({vec3(0, 0, 0)});
  for (int i = 0; i <= kViewFieldSegments; ++i) {
    const double a = -azimuth_half_rad + 2.0 * azimuth_half_rad * i / kViewFieldSegments;
    const Vec2 p = point_from_polar(max_range_m, a);
    points.push_back(vec3(p.x(), p.y(), 0.0));
  }
  points.push_back(vec3(0, 0, 0));
  Json e = entity(ns, frame, "view_field", 0);
  e["frame_locked"] = true;
  e["lines"].push_back({{"type", 0}, {"pose", pose_json(0, 0, 0, 0)}, {"thickness", 2.0}, {"scale_invariant", true},
                        {"points", points}, {"color", colour(colours::kViewField, 0.8)}, {"colors", Json::array()}, {"indices", Json::array()}});
  return e;
}

std::string frame_name(const std::string& sensor_id, int sensor, const std::vector<std::string>& taken) {
  std::string name;
  for (const char c : sensor_id) name += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
  if (name.empty() || name == "world" || name == "ego" || name == "boxes" ||
      std::find(taken.begin(), taken.end(), name) != taken.end()) {
    name = fmt::format("sensor_{}", sensor);
  }
  return name;
}

}  // namespace rcsim::foxglove
