#pragma once
// Foxglove's messages as JSON (the schemas foxglove.SceneUpdate and foxglove.FrameTransform,
// docs.foxglove.dev), for the MCAP files rcsim writes (schemas/mcap-replay.md): times, poses with
// a yaw as a quaternion, colours from the report's "#rrggbb", scene entities, transforms, a view
// field, and the JSON Schemas written beside them. Frames and topics are named by frame_name.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::foxglove {

using Json = nlohmann::ordered_json;

std::uint64_t time_ns(double t_s);  // negative times: 0
Json time_json(std::uint64_t ns);   // {sec, nsec}
Json vec3(double x, double y, double z);
Json yaw_quaternion(double yaw_rad);  // (0, 0, sin(yaw/2), cos(yaw/2))
Json pose_json(double x_m, double y_m, double z_m, double yaw_rad);
Json colour(const char* hex_rrggbb, double alpha = 1.0);  // components 0..1

// An entity with every primitive list empty, to fill; lifetime 0: for ever.
Json entity(std::uint64_t ns, const std::string& frame_id, const std::string& id, std::uint64_t lifetime_ns);
Json scene_update(Json entities);
Json frame_transform(std::uint64_t ns, const std::string& parent, const std::string& child, const Pose2& X_PC);
// A sensor's view field: a line from its origin along the arc at its range and back, frame-locked.
Json view_field_entity(const std::string& frame_id, double azimuth_half_rad, double max_range_m, std::uint64_t ns);

// The JSON Schemas written with the messages (Foxglove knows its own by name; the schema lets a
// client list the fields), kept to the fields written.
std::string scene_update_schema();
std::string frame_transform_schema();

// A sensor's frame id, also the middle of its topics: its id with every character but letters,
// digits, '_' and '-' made '_'; "sensor_N" where that is empty, taken, or one of world, ego, boxes.
std::string frame_name(const std::string& sensor_id, int sensor, const std::vector<std::string>& taken);

}  // namespace rcsim::foxglove

namespace rcsim::foxglove::text {

// The messages an export writes by the million, as JSON text straight away: the same JSON as
// entity(), scene_update() and frame_transform() above build (keys in the same order), at a fifth
// of the cost (an hour's export spent 60 % of its time building and freeing nlohmann::json).
// Numbers in their shortest round-trip form, null where not finite.
void number(std::string& out, double v);
std::string quoted(const std::string& s);  // a JSON string, escaped by nlohmann's rules
void pose(std::string& out, double x_m, double y_m, double z_m, double yaw_rad);
std::string colour(const char* hex_rrggbb, double alpha = 1.0);

// One scene entity with cubes, spheres and texts, written out as a SceneUpdate of it alone.
class Entity {
 public:
  // frame_id and id as quoted() gives them.
  Entity(std::uint64_t ns, std::string frame_id_json, std::string id_json, std::uint64_t lifetime_ns);
  // A cube or sphere at (x, y, z) turned by yaw, of the size given, coloured as colour() gives it.
  void cube(double x_m, double y_m, double z_m, double yaw_rad, double sx_m, double sy_m, double sz_m, const std::string& colour_json);
  void sphere(double x_m, double y_m, double z_m, double yaw_rad, double sx_m, double sy_m, double sz_m, const std::string& colour_json);
  // A label that faces the viewer at a fixed size on screen.
  void label(double x_m, double y_m, double z_m, double font_size, const std::string& colour_json, const std::string& text_json);
  // An annotated box as the exports draw it: a translucent cube of its length and width,
  // kBoxHeight_m tall on the ground, its label (quoted()) above it.
  void box(const Pose2& X_WO, double length_m, double width_m, const std::string& label_json);
  static constexpr double kBoxHeight_m = 1.5;  // the boxes are 2-D
  std::string scene_update() const;

 private:
  std::uint64_t ns_, lifetime_ns_;
  std::string frame_id_json_, id_json_, cubes_, spheres_, texts_;
};

std::string frame_transform(std::uint64_t ns, const std::string& parent_json, const std::string& child_json, const Pose2& X_PC);

}  // namespace rcsim::foxglove::text
