#pragma once
// Foxglove's message schemas as an MCAP log carries them in JSON (docs.foxglove.dev/docs/visualization/message-schemas),
// read for `rcsim import --from mcap` with simdjson (an hour of boxes is hundreds of megabytes of
// JSON): a foxglove.SceneUpdate's boxes (each entity's first cube) and a foxglove.PointCloud's
// points (its base64 data through its fields). A message that is not what its schema says throws
// std::invalid_argument or simdjson::simdjson_error naming the field.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <simdjson.h>
#include <vector>

#include "common/limits.hpp"

namespace rcsim::replay::foxglove {

// One entity's box: its first cube, at the entity's time; `log_class` and `speed_mps` from the
// entity's metadata keys "class" and "speed_mps" where given.
struct SceneBox {
  std::string_view id, log_class, frame_id;  // frame_id: the entity's, the frame its cube's pose is in
  std::int64_t t_ns = 0;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, length_m = 0.0, width_m = 0.0;
  std::optional<double> speed_mps;
};

void for_each_scene_box(simdjson::ondemand::parser& parser, const std::string& json, const std::function<void(const SceneBox&)>& visit);

// A point cloud: its time, its pose in its frame (position, quaternion x y z w), and per point the
// values of the fields asked for, in their order (any numeric type, little-endian), held in one
// array (`field_count` values a point), never an allocation a point.
struct PointCloud {
  std::int64_t t_ns = 0;
  std::string frame_id;
  double position[3] = {0.0, 0.0, 0.0};
  double orientation[4] = {0.0, 0.0, 0.0, 1.0};
  std::size_t field_count = 0;
  std::vector<double> values;  // point i's field f at values[i * field_count + f]
  std::size_t size() const { return field_count == 0 ? 0 : values.size() / field_count; }
  std::span<const double> point(std::size_t i) const { return {values.data() + i * field_count, field_count}; }
};

// Throws std::invalid_argument naming: a field asked for that the cloud lacks or names twice, a
// field whose offset and bytes run past the stride (checked without overflow), two fields asked
// for that overlap (so the stride holds them all: a point costs its fields' bytes), data that is
// no whole number of points, or more points than `max_points` (and limits::kMaxReturnsPerScan),
// told from the base64 text's length before it is decoded.
PointCloud decode_point_cloud(simdjson::ondemand::parser& parser, const std::string& json, const std::vector<std::string>& fields,
                              std::uint64_t max_points = limits::kMaxReturnsPerScan);

// Standard base64 (RFC 4648, padding optional); std::invalid_argument on any other character.
std::string decode_base64(std::string_view text);

}  // namespace rcsim::replay::foxglove
