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

namespace rcsim::foxglove::text {
namespace {

void time(std::string& out, std::uint64_t ns) { fmt::format_to(std::back_inserter(out), R"({{"sec":{},"nsec":{}}})", ns / 1000000000, ns % 1000000000); }

// {"x":..,"y":..,"z":..}
void vec3(std::string& out, double x, double y, double z) {
  out += R"({"x":)";
  number(out, x);
  out += R"(,"y":)";
  number(out, y);
  out += R"(,"z":)";
  number(out, z);
  out += '}';
}

// {"x":0,"y":0,"z":sin(yaw/2),"w":cos(yaw/2)}
void yaw_quaternion(std::string& out, double yaw_rad) {
  out += R"({"x":0,"y":0,"z":)";
  number(out, std::sin(0.5 * yaw_rad));
  out += R"(,"w":)";
  number(out, std::cos(0.5 * yaw_rad));
  out += '}';
}

void shape(std::string& list, double x_m, double y_m, double z_m, double yaw_rad, double sx_m, double sy_m, double sz_m,
           const std::string& colour_json) {
  list += list.empty() ? R"({"pose":)" : R"(,{"pose":)";
  pose(list, x_m, y_m, z_m, yaw_rad);
  list += R"(,"size":)";
  vec3(list, sx_m, sy_m, sz_m);
  list += R"(,"color":)";
  list += colour_json;
  list += '}';
}

}  // namespace

void number(std::string& out, double v) {
  if (std::isfinite(v)) {
    fmt::format_to(std::back_inserter(out), "{}", v);
  } else {
    out += "null";
  }
}

std::string quoted(const std::string& s) { return Json(s).dump(); }

void pose(std::string& out, double x_m, double y_m, double z_m, double yaw_rad) {
  out += R"({"position":)";
  vec3(out, x_m, y_m, z_m);
  out += R"(,"orientation":)";
  yaw_quaternion(out, yaw_rad);
  out += '}';
}

std::string colour(const char* hex_rrggbb, double alpha) { return foxglove::colour(hex_rrggbb, alpha).dump(); }

Entity::Entity(std::uint64_t ns, std::string frame_id_json, std::string id_json, std::uint64_t lifetime_ns)
    : ns_(ns), lifetime_ns_(lifetime_ns), frame_id_json_(std::move(frame_id_json)), id_json_(std::move(id_json)) {}

void Entity::cube(double x_m, double y_m, double z_m, double yaw_rad, double sx_m, double sy_m, double sz_m, const std::string& colour_json) {
  shape(cubes_, x_m, y_m, z_m, yaw_rad, sx_m, sy_m, sz_m, colour_json);
}

void Entity::sphere(double x_m, double y_m, double z_m, double yaw_rad, double sx_m, double sy_m, double sz_m, const std::string& colour_json) {
  shape(spheres_, x_m, y_m, z_m, yaw_rad, sx_m, sy_m, sz_m, colour_json);
}

void Entity::label(double x_m, double y_m, double z_m, double font_size, const std::string& colour_json, const std::string& text_json) {
  texts_ += texts_.empty() ? R"({"pose":)" : R"(,{"pose":)";
  pose(texts_, x_m, y_m, z_m, 0.0);
  texts_ += R"(,"billboard":true,"font_size":)";
  number(texts_, font_size);
  texts_ += R"(,"scale_invariant":true,"color":)";
  texts_ += colour_json;
  texts_ += R"(,"text":)";
  texts_ += text_json;
  texts_ += '}';
}

void Entity::box(const Pose2& X_WO, double length_m, double width_m, const std::string& label_json) {
  static const std::string box_colour = colour(colours::kBackground, 0.35), label_colour = colour(colours::kLabel);
  cube(X_WO.x_m, X_WO.y_m, 0.5 * kBoxHeight_m, X_WO.yaw_rad, length_m, width_m, kBoxHeight_m, box_colour);
  label(X_WO.x_m, X_WO.y_m, kBoxHeight_m + 0.5, 14.0, label_colour, label_json);
}

std::string Entity::scene_update() const {
  std::string out;
  out.reserve(160 + cubes_.size() + spheres_.size() + texts_.size());
  out += R"({"deletions":[],"entities":[{"timestamp":)";
  time(out, ns_);
  out += R"(,"frame_id":)" + frame_id_json_ + R"(,"id":)" + id_json_ + R"(,"lifetime":)";
  time(out, lifetime_ns_);
  out += R"(,"frame_locked":false,"metadata":[],"arrows":[],"cubes":[)" + cubes_ + R"(],"spheres":[)" + spheres_ +
         R"(],"cylinders":[],"lines":[],"triangles":[],"texts":[)" + texts_ + R"(],"models":[]}]})";
  return out;
}

std::string frame_transform(std::uint64_t ns, const std::string& parent_json, const std::string& child_json, const Pose2& X_PC) {
  std::string out = R"({"timestamp":)";
  time(out, ns);
  out += R"(,"parent_frame_id":)" + parent_json + R"(,"child_frame_id":)" + child_json + R"(,"translation":)";
  vec3(out, X_PC.x_m, X_PC.y_m, 0.0);
  out += R"(,"rotation":)";
  yaw_quaternion(out, X_PC.yaw_rad);
  out += '}';
  return out;
}

}  // namespace rcsim::foxglove::text
