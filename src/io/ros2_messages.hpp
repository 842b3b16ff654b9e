#pragma once
// ROS 2 messages as MCAP logs carry them (message encoding "cdr": OMG CDR, the XCDR1 rules ROS 2's
// middlewares use), read for `rcsim import --from mcap`: radar_msgs/msg/RadarScan (a radar's
// detections of one cycle), sensor_msgs/msg/PointCloud2 (a radar driver's detections as points),
// nav_msgs/msg/Odometry (the ego) and tf2_msgs/msg/TFMessage. Little- and big-endian
// encapsulations both read; a message that ends before its fields do, or holds a count beyond
// what is left, is refused (CdrError naming the field).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/limits.hpp"

namespace rcsim::ros2 {

struct CdrError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// builtin_interfaces/Time: seconds and nanoseconds since the epoch.
struct Time {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::int64_t ns() const { return std::int64_t{sec} * 1'000'000'000 + nanosec; }
};

struct Header {
  Time stamp;
  std::string frame_id;
};

// radar_msgs/msg/RadarReturn: one detection; range the slant distance, angles in the sensor frame
// (azimuth positive to the left, elevation up), the radial speed negative when approaching.
struct RadarReturn {
  float range = 0.0f, azimuth = 0.0f, elevation = 0.0f, doppler_velocity = 0.0f, amplitude = 0.0f;
};

struct RadarScan {
  Header header;
  std::vector<RadarReturn> returns;
};

// nav_msgs/msg/Odometry, the parts rcsim reads: the pose in the header's frame, the twist in the
// child frame (the vehicle's).
struct Odometry {
  Header header;
  std::string child_frame_id;
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  double vx_mps = 0.0, vy_mps = 0.0, wz_radps = 0.0;
};

// geometry_msgs/msg/TransformStamped: the pose of `child_frame_id` in `header.frame_id` (the
// parent) at `header.stamp`: a point p in the child's frame is R p + t in the parent's.
struct TransformStamped {
  Header header;
  std::string child_frame_id;
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
};

// sensor_msgs/msg/PointField: a named value of each point, at `offset` bytes into it, of a
// `datatype` (INT8 1, UINT8 2, INT16 3, UINT16 4, INT32 5, UINT32 6, FLOAT32 7, FLOAT64 8: not
// foxglove.NumericType's numbers), `count` of them (the first is read).
struct PointField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};

// A sensor_msgs/msg/PointCloud2 read for the fields asked for: per point their values in the order
// asked (any datatype, either endianness, rows row_step apart, points point_step apart), held in
// one array. Where the cloud is not dense, points with a value that is not finite are left out and
// counted.
struct CloudPoints {
  Header header;
  std::vector<std::string> field_names;  // every field the cloud has, in its order
  bool is_dense = true;
  std::size_t field_count = 0;
  std::vector<double> values;  // point i's field k at values[i * field_count + k]
  std::size_t invalid_points = 0;
  std::size_t size() const { return field_count == 0 ? 0 : values.size() / field_count; }
};

inline constexpr std::string_view kRadarScanSchema = "radar_msgs/msg/RadarScan";
inline constexpr std::string_view kOdometrySchema = "nav_msgs/msg/Odometry";
inline constexpr std::string_view kTfMessageSchema = "tf2_msgs/msg/TFMessage";
inline constexpr std::string_view kPointCloud2Schema = "sensor_msgs/msg/PointCloud2";

// A RadarScan of at most `max_returns` returns (and at most limits::kMaxReturnsPerScan): a count
// beyond either, or beyond the bytes behind it, is refused (CdrError) before anything is allocated.
RadarScan decode_radar_scan(std::string_view cdr, std::uint64_t max_returns = limits::kMaxReturnsPerScan);
Odometry decode_odometry(std::string_view cdr);
// A PointCloud2's fields `wanted`; refused (CdrError): a field asked for that the cloud lacks
// (listing the fields it has), of no known datatype, running past point_step, or overlapping
// another asked for; points that need more bytes than the data holds; more than `max_points` (and
// limits::kMaxReturnsPerScan) points, checked before anything is allocated.
CloudPoints decode_point_cloud2(std::string_view cdr, const std::vector<std::string>& wanted,
                                std::uint64_t max_points = limits::kMaxReturnsPerScan);
std::vector<TransformStamped> decode_tf_message(std::string_view cdr);

// The yaw of a quaternion (rotation about z, ZYX convention), rad in (-pi, pi].
double yaw_of_quaternion(double qx, double qy, double qz, double qw);

}  // namespace rcsim::ros2
