#include "replay/import/foxglove_messages.hpp"

#include <cmath>
#include <algorithm>
#include <cstring>
#include <limits>
#include <fmt/format.h>
#include <simdjson.h>
#include <stdexcept>

#include "io/ros2_messages.hpp"

namespace rcsim::replay::foxglove {
namespace {

// A finite number (an integer too), else std::invalid_argument naming the field.
double finite(simdjson::ondemand::value value, const char* field) {
  const double v = value.get_double();
  if (!std::isfinite(v)) throw std::invalid_argument(fmt::format("{}: not finite", field));
  return v;
}

std::int64_t time_ns(simdjson::ondemand::object stamp) {
  const std::int64_t sec = stamp["sec"].get_int64(), nsec = stamp["nsec"].get_int64();
  if (nsec < 0 || nsec >= 1'000'000'000) throw std::invalid_argument(fmt::format("timestamp.nsec: {} is not in [0, 10^9)", nsec));
  // As builtin_interfaces/Time: seconds since the epoch that fit an int32 (until 2038).
  if (sec < 0 || sec > std::numeric_limits<std::int32_t>::max()) {
    throw std::invalid_argument(fmt::format("timestamp.sec: {} is not in [0, 2^31)", sec));
  }
  return sec * 1'000'000'000 + nsec;
}

// The value of one point's field of a numeric type (foxglove.NumericType), little-endian.
double field_value(const char* at, std::int64_t type) {
  const auto read = [at]<typename T>(T) {
    T v;
    std::memcpy(&v, at, sizeof(T));
    return static_cast<double>(v);
  };
  switch (type) {
    case 1: return read(std::uint8_t{});
    case 2: return read(std::int8_t{});
    case 3: return read(std::uint16_t{});
    case 4: return read(std::int16_t{});
    case 5: return read(std::uint32_t{});
    case 6: return read(std::int32_t{});
    case 7: return read(float{});
    case 8: return read(double{});
    default: throw std::invalid_argument(fmt::format("fields[].type: {} is no numeric type (1 to 8)", type));
  }
}

std::size_t type_bytes(std::int64_t type) {
  constexpr std::size_t kBytes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
  if (type < 1 || type > 8) throw std::invalid_argument(fmt::format("fields[].type: {} is no numeric type (1 to 8)", type));
  return kBytes[type];
}

}  // namespace

void for_each_scene_box(simdjson::ondemand::parser& parser, const std::string& json, const std::function<void(const SceneBox&)>& visit) {
  const simdjson::padded_string padded(json);
  simdjson::ondemand::document update = parser.iterate(padded);
  for (simdjson::ondemand::object e : update["entities"].get_array()) {
    SceneBox box;
    box.id = e["id"].get_string();
    const std::string id(box.id);  // the view lives only until the next field is read
    box.t_ns = time_ns(e["timestamp"].get_object());
    const std::string frame_id(std::string_view(e["frame_id"].get_string()));
    std::string log_class;
    simdjson::ondemand::array metadata;
    if (e["metadata"].get(metadata) == simdjson::SUCCESS) {
      for (simdjson::ondemand::object kv : metadata) {
        const std::string_view key = kv["key"].get_string();
        const std::string_view value = kv["value"].get_string();
        if (key == "class") log_class = value;
        if (key == "speed_mps") box.speed_mps = std::stod(std::string(value));
      }
    }
    simdjson::ondemand::array cubes;
    if (e["cubes"].get(cubes) != simdjson::SUCCESS) continue;  // not a box
    for (simdjson::ondemand::object cube : cubes) {
      simdjson::ondemand::object pose = cube["pose"].get_object();
      simdjson::ondemand::object position = pose["position"].get_object();
      box.x_m = finite(position["x"].value(), "position.x");
      box.y_m = finite(position["y"].value(), "position.y");
      simdjson::ondemand::object q = pose["orientation"].get_object();
      const double qx = finite(q["x"].value(), "orientation.x"), qy = finite(q["y"].value(), "orientation.y"),
                   qz = finite(q["z"].value(), "orientation.z"), qw = finite(q["w"].value(), "orientation.w");
      box.yaw_rad = ros2::yaw_of_quaternion(qx, qy, qz, qw);
      simdjson::ondemand::object size = cube["size"].get_object();
      box.length_m = finite(size["x"].value(), "size.x");
      box.width_m = finite(size["y"].value(), "size.y");
      box.id = id;
      box.log_class = log_class;
      box.frame_id = frame_id;
      visit(box);
      break;  // the first cube is the box
    }
  }
}

PointCloud decode_point_cloud(simdjson::ondemand::parser& parser, const std::string& json, const std::vector<std::string>& fields,
                              std::uint64_t max_points) {
  const simdjson::padded_string padded(json);
  simdjson::ondemand::document doc = parser.iterate(padded);
  simdjson::ondemand::object cloud = doc.get_object();
  PointCloud out;
  out.t_ns = time_ns(cloud["timestamp"].get_object());
  out.frame_id = std::string(std::string_view(cloud["frame_id"].get_string()));
  simdjson::ondemand::object pose = cloud["pose"].get_object();
  simdjson::ondemand::object position = pose["position"].get_object();
  out.position[0] = finite(position["x"].value(), "pose.position.x");
  out.position[1] = finite(position["y"].value(), "pose.position.y");
  out.position[2] = finite(position["z"].value(), "pose.position.z");
  simdjson::ondemand::object q = pose["orientation"].get_object();
  out.orientation[0] = finite(q["x"].value(), "pose.orientation.x");
  out.orientation[1] = finite(q["y"].value(), "pose.orientation.y");
  out.orientation[2] = finite(q["z"].value(), "pose.orientation.z");
  out.orientation[3] = finite(q["w"].value(), "pose.orientation.w");
  const std::int64_t stride = cloud["point_stride"].get_int64();
  if (stride <= 0 || stride > 65536) throw std::invalid_argument(fmt::format("point_stride: {} is not in 1..65536", stride));
  std::vector<std::int64_t> offset(fields.size(), -1), type(fields.size(), 0);
  for (simdjson::ondemand::object f : cloud["fields"].get_array()) {
    const std::string name(std::string_view(f["name"].get_string()));
    const std::int64_t at = f["offset"].get_int64(), t = f["type"].get_int64();
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (fields[i] != name) continue;
      if (offset[i] >= 0) throw std::invalid_argument(fmt::format("fields[{}]: named twice", name));
      // Compared without a sum, which overflows for an offset near 2^63.
      const auto bytes = static_cast<std::int64_t>(type_bytes(t));
      if (at < 0 || at > stride || bytes > stride - at) {
        throw std::invalid_argument(fmt::format("fields[{}]: offset {} and its {} bytes run past the stride {}", name, at, bytes, stride));
      }
      offset[i] = at, type[i] = t;
    }
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (offset[i] < 0) throw std::invalid_argument(fmt::format("fields: no field '{}'", fields[i]));
  }
  // The fields asked for lie side by side: a point costs at least their bytes, so that a stride of
  // 1 cannot make every byte of the data a point of five values.
  for (std::size_t i = 0; i < fields.size(); ++i) {
    for (std::size_t j = i + 1; j < fields.size(); ++j) {
      if (fields[i] == fields[j]) continue;  // asked for twice: one field
      const std::int64_t end_i = offset[i] + static_cast<std::int64_t>(type_bytes(type[i]));
      const std::int64_t end_j = offset[j] + static_cast<std::int64_t>(type_bytes(type[j]));
      if (offset[i] < end_j && offset[j] < end_i) {
        throw std::invalid_argument(fmt::format("fields[{}] (bytes {} to {}) and fields[{}] (bytes {} to {}) overlap", fields[i], offset[i],
                                                end_i - 1, fields[j], offset[j], end_j - 1));
      }
    }
  }
  // The points the data hold, told from the base64 text's length before it is decoded.
  const std::string_view text = cloud["data"].get_string();
  std::size_t padding = 0;
  while (padding < 2 && padding < text.size() && text[text.size() - 1 - padding] == '=') ++padding;
  const std::uint64_t data_bytes = (text.size() - padding) / 4 * 3 + ((text.size() - padding) % 4 == 0 ? 0 : (text.size() - padding) % 4 - 1);
  const std::uint64_t points = data_bytes / static_cast<std::uint64_t>(stride);
  const std::uint64_t max = std::min<std::uint64_t>(max_points, limits::kMaxReturnsPerScan);
  if (points > limits::kMaxReturnsPerScan) {
    throw std::invalid_argument(fmt::format("data: {} points in one cloud exceed the limit of {} (schemas/limits.md)", points,
                                            limits::kMaxReturnsPerScan));
  }
  if (points > max) throw std::invalid_argument(fmt::format("data: {} points exceed the {} the log has left", points, max));
  const std::string data = decode_base64(text);
  if (data.size() % static_cast<std::size_t>(stride) != 0) {
    throw std::invalid_argument(fmt::format("data: {} bytes are no whole number of {}-byte points", data.size(), stride));
  }
  out.field_count = fields.size();
  out.values.resize(data.size() / static_cast<std::size_t>(stride) * fields.size());
  double* value = out.values.data();
  for (std::size_t at = 0; at < data.size(); at += static_cast<std::size_t>(stride)) {
    for (std::size_t i = 0; i < fields.size(); ++i) *value++ = field_value(data.data() + at + static_cast<std::size_t>(offset[i]), type[i]);
  }
  return out;
}

std::string decode_base64(std::string_view text) {
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  std::string out;
  out.reserve(text.size() * 3 / 4);
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else throw std::invalid_argument(fmt::format("data: '{}' is not base64", c));
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if (++count == 4) {
      out += static_cast<char>((bits >> 16) & 0xff);
      out += static_cast<char>((bits >> 8) & 0xff);
      out += static_cast<char>(bits & 0xff);
      bits = 0, count = 0;
    }
  }
  if (count == 1) throw std::invalid_argument("data: base64 cut inside a byte");
  if (count == 2) out += static_cast<char>((bits >> 4) & 0xff);
  if (count == 3) {
    out += static_cast<char>((bits >> 10) & 0xff);
    out += static_cast<char>((bits >> 2) & 0xff);
  }
  return out;
}

}  // namespace rcsim::replay::foxglove
