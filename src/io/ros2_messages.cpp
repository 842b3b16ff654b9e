#include "io/ros2_messages.hpp"

#include <algorithm>
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
  // A uint8[] sequence's bytes where they lie (no copy).
  std::string_view byte_sequence(const char* field) {
    const std::uint32_t n = count(field, 1);
    const std::string_view bytes = bytes_.substr(at_, n);
    at_ += n;
    return bytes;
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
  if (o.qx == 0.0 && o.qy == 0.0 && o.qz == 0.0 && o.qw == 0.0) throw CdrError("pose.pose.orientation: a zero quaternion is no rotation");
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

namespace {

// sensor_msgs/msg/PointField's datatype numbers (not foxglove.NumericType's) and their bytes.
std::uint32_t point_field_bytes(std::uint8_t datatype) {
  switch (datatype) {
    case 1: case 2: return 1;  // INT8, UINT8
    case 3: case 4: return 2;  // INT16, UINT16
    case 5: case 6: case 7: return 4;  // INT32, UINT32, FLOAT32
    case 8: return 8;  // FLOAT64
    default: return 0;
  }
}

template <typename T>
double value_of(const unsigned char* at, bool swap) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, at, sizeof(T));
  if (swap) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return static_cast<double>(value);
}

double point_field_value(const unsigned char* at, std::uint8_t datatype, bool swap) {
  switch (datatype) {
    case 1: return value_of<std::int8_t>(at, swap);
    case 2: return value_of<std::uint8_t>(at, swap);
    case 3: return value_of<std::int16_t>(at, swap);
    case 4: return value_of<std::uint16_t>(at, swap);
    case 5: return value_of<std::int32_t>(at, swap);
    case 6: return value_of<std::uint32_t>(at, swap);
    case 7: return value_of<float>(at, swap);
    default: return value_of<double>(at, swap);
  }
}

}  // namespace

CloudPoints decode_point_cloud2(std::string_view cdr, const std::vector<std::string>& wanted, std::uint64_t max_points) {
  CdrReader r(cdr);
  CloudPoints cloud;
  cloud.header = r.header();
  const auto height = r.read<std::uint32_t>("height");
  const auto width = r.read<std::uint32_t>("width");
  // A PointField is at least a name's count (4), an offset (4), a datatype (1, padded to 4) and a count (4).
  const std::uint32_t n_fields = r.count("fields", 16);
  std::vector<PointField> fields(n_fields);
  for (PointField& f : fields) {
    f.name = r.string("fields[].name");
    f.offset = r.read<std::uint32_t>("fields[].offset");
    f.datatype = r.read<std::uint8_t>("fields[].datatype");
    f.count = r.read<std::uint32_t>("fields[].count");
  }
  const bool big_endian = r.read<std::uint8_t>("is_bigendian") != 0;
  const auto point_step = r.read<std::uint32_t>("point_step");
  const auto row_step = r.read<std::uint32_t>("row_step");
  const std::string_view data = r.byte_sequence("data");
  cloud.is_dense = r.read<std::uint8_t>("is_dense") != 0;
  for (const PointField& f : fields) cloud.field_names.push_back(f.name);

  // The fields asked for: present, of a known type, within the point, not overlapping.
  const auto listed = [&] {
    std::string names;
    for (const PointField& f : fields) names += (names.empty() ? "" : ", ") + f.name;
    return names.empty() ? std::string("none") : names;
  };
  std::vector<const PointField*> used;
  for (const std::string& name : wanted) {
    const auto f = std::find_if(fields.begin(), fields.end(), [&](const PointField& p) { return p.name == name; });
    if (f == fields.end()) throw CdrError(fmt::format("fields: no field '{}' (the cloud's fields: {})", name, listed()));
    const std::uint32_t bytes = point_field_bytes(f->datatype);
    if (bytes == 0) throw CdrError(fmt::format("fields['{}'].datatype: {} is no PointField datatype (1 to 8)", name, f->datatype));
    if (f->offset > point_step || bytes > point_step - f->offset) {
      throw CdrError(fmt::format("fields['{}']: offset {} and {} byte(s) run past point_step {}", name, f->offset, bytes, point_step));
    }
    for (const PointField* other : used) {
      const std::uint32_t other_bytes = point_field_bytes(other->datatype);
      if (other != &*f && f->offset < other->offset + other_bytes && other->offset < f->offset + bytes) {
        throw CdrError(fmt::format("fields['{}'] and fields['{}'] overlap", name, other->name));
      }
    }
    used.push_back(&*f);
  }
  // The points: height rows of width points, each row row_step bytes apart; the count checked
  // against the bytes behind it before anything is allocated.
  const std::uint64_t points = std::uint64_t{height} * width;
  if (points > 0 && (point_step == 0 || std::uint64_t{width} * point_step > row_step || std::uint64_t{height} * row_step > data.size())) {
    throw CdrError(fmt::format("data: {} x {} points of {} bytes in rows of {} bytes need more than its {} bytes", height, width,
                               point_step, row_step, data.size()));
  }
  if (points > limits::kMaxReturnsPerScan) {
    throw CdrError(fmt::format("{} points in one cloud exceed the limit of {} (schemas/limits.md)", points, limits::kMaxReturnsPerScan));
  }
  if (points > max_points) throw CdrError(fmt::format("{} points exceed the {} the log has left", points, max_points));
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  cloud.field_count = wanted.size();
  cloud.values.reserve(static_cast<std::size_t>(points) * wanted.size());
  std::vector<double> point(wanted.size());
  for (std::uint32_t row = 0; row < height; ++row) {
    for (std::uint32_t col = 0; col < width; ++col) {
      const auto* at = reinterpret_cast<const unsigned char*>(data.data()) + std::uint64_t{row} * row_step + std::uint64_t{col} * point_step;
      bool finite = true;
      for (std::size_t k = 0; k < used.size(); ++k) {
        point[k] = point_field_value(at + used[k]->offset, used[k]->datatype, swap);
        finite = finite && std::isfinite(point[k]);
      }
      // A cloud that is not dense may hold invalid points (NaN): left out and counted.
      if (!finite && !cloud.is_dense) {
        ++cloud.invalid_points;
        continue;
      }
      cloud.values.insert(cloud.values.end(), point.begin(), point.end());
    }
  }
  return cloud;
}

double yaw_of_quaternion(double qx, double qy, double qz, double qw) {
  return std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
}

}  // namespace rcsim::ros2
