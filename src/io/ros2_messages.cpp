#include "io/ros2_messages.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

namespace rcsim::ros2 {
namespace {

// OMG CDR (XCDR1) as ROS 2 writes it: a 4-byte encapsulation header (0x00 0x01: little-endian,
// 0x00 0x00: big-endian, then 2 option bytes), then every primitive aligned to its own size
// from the end of that header; strings and sequences as a uint32 count first.
class CdrReader {
 public:
  explicit CdrReader(std::string_view bytes) : bytes_(bytes) {
    if (bytes.size() < 4) throw CdrError("shorter than CDR's 4-byte encapsulation header");
    if (bytes[0] != 0 || (bytes[1] != 0 && bytes[1] != 1)) {
      throw CdrError(fmt::format("encapsulation 0x{:02x}{:02x} is not plain CDR (0x0000 or 0x0001)",
                                 static_cast<unsigned char>(bytes[0]), static_cast<unsigned char>(bytes[1])));
    }
    little_ = bytes[1] == 1;
    at_ = 4;
  }
  template <typename T>
  T read(const char* field) {
    align(sizeof(T), field);
    need(sizeof(T), field);
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + at_, sizeof(T));
    if (little_ != (std::endian::native == std::endian::little)) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    at_ += sizeof(T);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }
  std::string string(const char* field) {
    const auto n = read<std::uint32_t>(field);
    need(n, field);
    std::string text(bytes_.substr(at_, n));
    at_ += n;
    if (!text.empty() && text.back() == '\0') text.pop_back();  // the count includes the terminator
    return text;
  }
  // A sequence's count, checked against what is left (each element at least `min_bytes`).
  std::uint32_t count(const char* field, std::size_t min_bytes) {
    const auto n = read<std::uint32_t>(field);
    if (static_cast<std::uint64_t>(n) * min_bytes > bytes_.size() - at_) {
      throw CdrError(fmt::format("{}: {} element(s) of {} bytes or more, but {} bytes are left", field, n, min_bytes,
                                 bytes_.size() - at_));
    }
    return n;
  }
  Header header() {
    Header h;
    h.stamp.sec = read<std::int32_t>("header.stamp.sec");
    h.stamp.nanosec = read<std::uint32_t>("header.stamp.nanosec");
    if (h.stamp.nanosec >= 1'000'000'000u) throw CdrError(fmt::format("header.stamp.nanosec: {} is not below 10^9", h.stamp.nanosec));
    h.frame_id = string("header.frame_id");
    return h;
  }
  void skip_doubles(std::size_t n, const char* field) {
    for (std::size_t i = 0; i < n; ++i) read<double>(field);
  }

 private:
  void align(std::size_t n, const char* field) {
    const std::size_t offset = (at_ - 4) % n;
    if (offset != 0) {
      need(n - offset, field);
      at_ += n - offset;
    }
  }
  void need(std::size_t n, const char* field) const {
    if (n > bytes_.size() - at_) {
      throw CdrError(fmt::format("{}: the message ends {} bytes short", field, n - (bytes_.size() - at_)));
    }
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
  bool little_ = true;
};

}  // namespace

RadarScan decode_radar_scan(std::string_view cdr, std::uint64_t max_returns) {
  CdrReader r(cdr);
  RadarScan scan;
  scan.header = r.header();
  const std::uint32_t n = r.count("returns", 5 * sizeof(float));
  if (n > limits::kMaxReturnsPerScan) {
    throw CdrError(fmt::format("returns: {} in one scan exceed the limit of {} (schemas/limits.md)", n, limits::kMaxReturnsPerScan));
  }
  if (n > max_returns) throw CdrError(fmt::format("returns: {} exceed the {} the log has left", n, max_returns));
  scan.returns.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    RadarReturn d;
    d.range = r.read<float>("returns[].range");
    d.azimuth = r.read<float>("returns[].azimuth");
    d.elevation = r.read<float>("returns[].elevation");
    d.doppler_velocity = r.read<float>("returns[].doppler_velocity");
    d.amplitude = r.read<float>("returns[].amplitude");
    scan.returns.push_back(d);
  }
  return scan;
}

Odometry decode_odometry(std::string_view cdr) {
  CdrReader r(cdr);
  Odometry o;
  o.header = r.header();
  o.child_frame_id = r.string("child_frame_id");
  o.x_m = r.read<double>("pose.pose.position.x");
  o.y_m = r.read<double>("pose.pose.position.y");
  o.z_m = r.read<double>("pose.pose.position.z");
  o.qx = r.read<double>("pose.pose.orientation.x");
  o.qy = r.read<double>("pose.pose.orientation.y");
  o.qz = r.read<double>("pose.pose.orientation.z");
  o.qw = r.read<double>("pose.pose.orientation.w");
  r.skip_doubles(36, "pose.covariance");
  o.vx_mps = r.read<double>("twist.twist.linear.x");
  o.vy_mps = r.read<double>("twist.twist.linear.y");
  r.read<double>("twist.twist.linear.z");
  r.read<double>("twist.twist.angular.x");
  r.read<double>("twist.twist.angular.y");
  o.wz_radps = r.read<double>("twist.twist.angular.z");
  r.skip_doubles(36, "twist.covariance");
  return o;
}

std::vector<TransformStamped> decode_tf_message(std::string_view cdr) {
  CdrReader r(cdr);
  // A transform is at least a header (8 + 4), a child frame's count (4) and 7 doubles.
  const std::uint32_t n = r.count("transforms", 16 + 7 * sizeof(double));
  std::vector<TransformStamped> transforms(n);
  for (TransformStamped& t : transforms) {
    t.header = r.header();
    t.child_frame_id = r.string("transforms[].child_frame_id");
    t.x_m = r.read<double>("transforms[].transform.translation.x");
    t.y_m = r.read<double>("transforms[].transform.translation.y");
    t.z_m = r.read<double>("transforms[].transform.translation.z");
    t.qx = r.read<double>("transforms[].transform.rotation.x");
    t.qy = r.read<double>("transforms[].transform.rotation.y");
    t.qz = r.read<double>("transforms[].transform.rotation.z");
    t.qw = r.read<double>("transforms[].transform.rotation.w");
  }
  return transforms;
}

double yaw_of_quaternion(double qx, double qy, double qz, double qw) {
  return std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
}

}  // namespace rcsim::ros2
