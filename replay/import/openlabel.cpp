#include "replay/import/openlabel.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <simdjson.h>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "io/ros2_messages.hpp"

namespace rcsim::replay::openlabel {
namespace {

namespace od = simdjson::ondemand;

constexpr std::int64_t kNsPerS = 1'000'000'000;

// ---- times ----

// The decimal number 0.d0d1d2... times 10^(point + 9), rounded to the nearest integer (halves up):
// `point` digits stand before the decimal point (it may be negative or past the end). nullopt past
// int64.
std::optional<std::int64_t> scaled_by_1e9(std::string_view digits, long point) {
  const long size = static_cast<long>(digits.size());
  const long end = point + 9;  // digits [0, end) make the integer part
  std::int64_t v = 0;
  for (long i = 0; i < end; ++i) {
    const int d = i < size ? digits[i] - '0' : 0;
    if (__builtin_mul_overflow(v, 10, &v) || __builtin_add_overflow(v, d, &v)) return std::nullopt;
  }
  if (end >= 0 && end < size && digits[end] >= '5' && __builtin_add_overflow(v, 1, &v)) return std::nullopt;
  return v;
}

// Seconds as a decimal number ("1700000000.05", "-2", "1.7e9") in ns, rounded to the nearest
// (halves away from zero) from the digits themselves: a double would lose the ns of an epoch time.
std::optional<std::int64_t> decimal_seconds_ns(std::string_view text) {
  bool negative = false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  std::string digits;
  long point = -1;
  std::size_t at = 0;
  for (; at < text.size(); ++at) {
    if (text[at] >= '0' && text[at] <= '9') digits += text[at];
    else if (text[at] == '.' && point < 0) point = static_cast<long>(digits.size());
    else break;
  }
  if (digits.empty()) return std::nullopt;
  if (point < 0) point = static_cast<long>(digits.size());
  if (at < text.size()) {
    if (text[at] != 'e' && text[at] != 'E') return std::nullopt;
    std::string_view exponent = text.substr(at + 1);
    const bool exponent_negative = !exponent.empty() && exponent[0] == '-';
    if (!exponent.empty() && (exponent[0] == '-' || exponent[0] == '+')) exponent.remove_prefix(1);
    unsigned magnitude = 0;
    const auto [end, error] = std::from_chars(exponent.data(), exponent.data() + exponent.size(), magnitude);
    if (exponent.empty() || error != std::errc() || end != exponent.data() + exponent.size() || magnitude > 9999) return std::nullopt;
    point += exponent_negative ? -static_cast<long>(magnitude) : static_cast<long>(magnitude);
  }
  const std::optional<std::int64_t> ns = scaled_by_1e9(digits, point);
  if (!ns) return std::nullopt;
  return negative ? -*ns : *ns;
}

// An ISO 8601 time with its zone ("2023-04-01T12:00:00.050Z", "2023-04-01 14:00:00+02:00") in ns
// since the epoch; nullopt for other text, a time without a zone among it.
std::optional<std::int64_t> iso8601_ns(std::string_view text) {
  std::size_t at = 0;
  const auto number = [&](std::size_t width) -> std::optional<int> {
    if (text.size() < at + width) return std::nullopt;
    int v = 0;
    for (std::size_t k = 0; k < width; ++k, ++at) {
      if (text[at] < '0' || text[at] > '9') return std::nullopt;
      v = v * 10 + (text[at] - '0');
    }
    return v;
  };
  const auto skip = [&](std::string_view any_of) {
    const bool found = at < text.size() && any_of.find(text[at]) != std::string_view::npos;
    if (found) ++at;
    return found;
  };
  const std::optional<int> year = number(4);
  if (!year || !skip("-")) return std::nullopt;
  const std::optional<int> month = number(2);
  if (!month || !skip("-")) return std::nullopt;
  const std::optional<int> day = number(2);
  if (!day || !skip("Tt ")) return std::nullopt;
  const std::optional<int> hour = number(2);
  if (!hour || !skip(":")) return std::nullopt;
  const std::optional<int> minute = number(2);
  if (!minute || !skip(":")) return std::nullopt;
  const std::optional<int> second = number(2);
  if (!second || *hour > 23 || *minute > 59 || *second > 59) return std::nullopt;
  std::int64_t fraction_ns = 0;
  if (skip(".,")) {
    const std::size_t from = at;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9') ++at;
    if (at == from) return std::nullopt;
    fraction_ns = *scaled_by_1e9(text.substr(from, at - from), 0);  // at most 10^9: no overflow
  }
  int offset_min = 0;
  if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    const int sign = text[at++] == '-' ? -1 : 1;
    const std::optional<int> zone_h = number(2);
    std::optional<int> zone_min = 0;
    if (at < text.size()) {
      skip(":");
      zone_min = number(2);
    }
    if (!zone_h || !zone_min || *zone_h > 23 || *zone_min > 59) return std::nullopt;
    offset_min = sign * (*zone_h * 60 + *zone_min);
  } else if (!skip("Zz")) {
    return std::nullopt;  // no zone: a local time of an unknown place
  }
  if (at != text.size()) return std::nullopt;
  const std::chrono::year_month_day date{std::chrono::year{*year}, std::chrono::month{static_cast<unsigned>(*month)},
                                         std::chrono::day{static_cast<unsigned>(*day)}};
  if (!date.ok()) return std::nullopt;
  const auto days = static_cast<std::int64_t>(std::chrono::sys_days{date}.time_since_epoch().count());
  const std::int64_t seconds = days * 86'400 + *hour * 3'600 + *minute * 60 + *second - offset_min * 60;
  std::int64_t ns = 0;
  if (__builtin_mul_overflow(seconds, kNsPerS, &ns) || __builtin_add_overflow(ns, fraction_ns, &ns)) return std::nullopt;
  return ns;
}

std::string_view trimmed(std::string_view text) {
  constexpr std::string_view kSpace = " \t\r\n";
  const std::size_t first = text.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(kSpace) - first + 1);
}

// ---- the document ----

std::string describe(simdjson::error_code error) {
  switch (error) {
    case simdjson::NO_SUCH_FIELD: return "missing";
    case simdjson::INCORRECT_TYPE: return "has the wrong JSON type";
    case simdjson::NUMBER_ERROR:
    case simdjson::NUMBER_OUT_OF_RANGE: return "is not a finite number";
    default: return fmt::format("is not valid JSON ({})", simdjson::error_message(error));
  }
}

// A "num" named "speed_mps" and one named "speed", of type "value".
struct Speeds {
  std::optional<double> speed_mps, speed;
  std::optional<double> best() const { return speed_mps ? speed_mps : speed; }
};

// An object_data's cuboids (without uid, type and time) and speed.
struct ObjectData {
  std::vector<LabelledBox> boxes;
  Speeds speeds;
};

// One of openlabel.objects: its type, and its static data.
struct ObjectInfo {
  std::string type, coordinate_system;
  std::vector<LabelledBox> static_boxes;
  std::optional<double> static_speed_mps;
};

struct Frame {
  std::uint64_t number = 0;
  std::vector<LabelledBox> boxes;
};

// Reads with simdjson's error codes, each turned into an InputError naming the file and the field.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  // Pass 1 reads the metadata and openlabel.objects, pass 2 the frames: a file may hold them in
  // either order.
  Labels read(std::string json) {
    file_bytes_ = json.size();
    max_boxes_ = json.size() / kFileBytesPerBox;
    json.reserve(json.size() + simdjson::SIMDJSON_PADDING);
    od::parser parser;
    od::document doc;
    if (const auto error = parser.iterate(json.data(), json.size(), json.capacity()).get(doc)) {
      fail("", fmt::format("not JSON ({})", simdjson::error_message(error)));
    }
    Labels labels;
    for_each_openlabel_field(doc, [&](std::string_view key, od::value value) {
      if (key == "metadata") {
        for_each_field(object(value, "openlabel.metadata"), "openlabel.metadata", [&](std::string_view k, od::value v) {
          if (k == "schema_version") labels.schema_version = string(v, "openlabel.metadata.schema_version");
        });
      } else if (key == "objects") {
        read_objects(value);
      }
    });
    if (labels.schema_version.empty()) fail("openlabel.metadata.schema_version", "missing: every OpenLABEL file states it");
    doc.rewind();
    std::vector<Frame> frames;
    for_each_openlabel_field(doc, [&](std::string_view key, od::value value) {
      if (key == "frames") read_frames(value, frames);
    });
    std::stable_sort(frames.begin(), frames.end(), [](const Frame& a, const Frame& b) { return a.number < b.number; });
    std::size_t count = 0;
    for (const Frame& frame : frames) count += frame.boxes.size();
    labels.boxes.reserve(count);
    for (Frame& frame : frames) std::move(frame.boxes.begin(), frame.boxes.end(), std::back_inserter(labels.boxes));
    return labels;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw InputError(file_, where, what); }

  std::size_t file_bytes_ = 0;
  std::size_t max_boxes_ = 0;  // the boxes the file's bytes allow
  std::size_t boxes_ = 0;      // the frames' boxes so far

  template <typename T>
  T take(simdjson::simdjson_result<T>&& result, const std::string& where) const {
    T value{};
    if (const simdjson::error_code error = std::move(result).get(value)) fail(where, describe(error));
    return value;
  }

  od::object object(od::value value, const std::string& where) const { return take(value.get_object(), where); }
  std::string string(od::value value, const std::string& where) const { return std::string(take(value.get_string(), where)); }

  // visit(key, value) for each field of `object` in the file's order.
  template <typename Visit>
  void for_each_field(od::object object, const std::string& where, Visit&& visit) const {
    for (auto result : object) {
      od::field field = take(std::move(result), where);
      visit(take(field.unescaped_key(), where), field.value());
    }
  }

  // visit(key, value) for each field of the root's "openlabel". The whole root is read, so that a
  // file cut short or followed by more is refused.
  template <typename Visit>
  void for_each_openlabel_field(od::document& doc, Visit&& visit) const {
    od::object root;
    if (const auto error = doc.get_object().get(root)) {
      fail("", fmt::format("not JSON, or no object at its root ({})", simdjson::error_message(error)));
    }
    bool found = false;
    for_each_field(root, "", [&](std::string_view key, od::value value) {
      if (key != "openlabel") return;
      found = true;
      for_each_field(object(value, "openlabel"), "openlabel", visit);
    });
    if (!found) fail("openlabel", "missing: not an OpenLABEL file (its root object holds no \"openlabel\")");
    if (doc.current_location().error() != simdjson::OUT_OF_BOUNDS) fail("", "not JSON: more follows its root object");
  }

  void read_objects(od::value value) {
    for_each_field(object(value, "openlabel.objects"), "openlabel.objects", [&](std::string_view key, od::value v) {
      const std::string uid(key), where = "openlabel.objects." + uid;
      ObjectInfo info;
      bool has_type = false;
      for_each_field(object(v, where), where, [&](std::string_view field, od::value f) {
        if (field == "type") {
          info.type = string(f, where + ".type");
          has_type = true;
        } else if (field == "coordinate_system") {
          info.coordinate_system = string(f, where + ".coordinate_system");
        } else if (field == "object_data") {
          ObjectData data = object_data(f, where + ".object_data");
          info.static_boxes = std::move(data.boxes);
          info.static_speed_mps = data.speeds.best();
        }
      });
      if (!has_type) fail(where + ".type", "missing: every object has a type, the class rcsim maps to an object model");
      objects_.insert_or_assign(uid, std::move(info));
    });
  }

  void read_frames(od::value value, std::vector<Frame>& frames) {
    for_each_field(object(value, "openlabel.frames"), "openlabel.frames", [&](std::string_view key, od::value v) {
      const std::string where = "openlabel.frames." + std::string(key);
      Frame& frame = frames.emplace_back();
      const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), frame.number);
      if (key.empty() || error != std::errc() || end != key.data() + key.size()) {
        fail(where, "is no frame number: the keys of openlabel.frames are digits");
      }
      std::optional<std::int64_t> t_ns;
      for_each_field(object(v, where), where, [&](std::string_view field, od::value f) {
        if (field == "frame_properties") {
          const std::string properties = where + ".frame_properties";
          for_each_field(object(f, properties), properties, [&](std::string_view k, od::value p) {
            if (k == "timestamp") t_ns = time_ns(p, properties + ".timestamp");
          });
        } else if (field == "objects") {
          read_frame_objects(f, where + ".objects", frame.boxes);
        }
      });
      if (!frame.boxes.empty() && !t_ns) fail(where + ".frame_properties.timestamp", "missing: the frame has boxes, which need its time");
      for (LabelledBox& box : frame.boxes) box.t_ns = t_ns.value_or(0);
    });
  }

  // The boxes of a frame's objects: their own cuboids there, else their static ones.
  void read_frame_objects(od::value value, const std::string& where, std::vector<LabelledBox>& boxes) {
    for_each_field(object(value, where), where, [&](std::string_view key, od::value v) {
      const std::string uid(key), at = where + "." + uid;
      const auto found = objects_.find(uid);
      if (found == objects_.end()) fail(at, fmt::format("object {} is not among openlabel.objects", uid));
      const ObjectInfo& info = found->second;
      ObjectData data;
      for_each_field(object(v, at), at, [&](std::string_view field, od::value f) {
        if (field == "object_data") data = object_data(f, at + ".object_data");
      });
      const auto add = [&](LabelledBox box) {
        box.uid = uid;
        box.type = info.type;
        if (box.coordinate_system.empty()) box.coordinate_system = info.coordinate_system;
        if (!box.speed_mps) box.speed_mps = data.speeds.best();
        if (!box.speed_mps) box.speed_mps = info.static_speed_mps;
        boxes.push_back(std::move(box));
      };
      // The boxes this listing adds, checked before a static cuboid is copied: a few bytes naming
      // an object copy all its static cuboids into the frame.
      const std::size_t adding = data.boxes.empty() ? info.static_boxes.size() : data.boxes.size();
      if (adding > kMaxBoxesPerFrame - boxes.size()) {
        fail(at, fmt::format("{} boxes in the frame with this object's {}: more than the limit of {} a frame (schemas/limits.md)",
                             boxes.size() + adding, adding, kMaxBoxesPerFrame));
      }
      if (adding > max_boxes_ - boxes_) {
        fail(at, fmt::format("{} boxes with this object's {}, where the file's {} bytes allow {} (one per {} bytes, schemas/limits.md): "
                             "static cuboids copied into every frame that lists their object?",
                             boxes_ + adding, adding, file_bytes_, max_boxes_, kFileBytesPerBox));
      }
      boxes_ += adding;
      if (data.boxes.empty()) std::for_each(info.static_boxes.begin(), info.static_boxes.end(), add);
      for (LabelledBox& box : data.boxes) add(std::move(box));
    });
  }

  ObjectData object_data(od::value value, const std::string& where) const {
    ObjectData data;
    for_each_field(object(value, where), where, [&](std::string_view key, od::value v) {
      if (key == "cuboid") {
        std::size_t i = 0;
        for (auto element : take(v.get_array(), where + ".cuboid")) {
          const std::string at = fmt::format("{}.cuboid[{}]", where, i++);
          if (std::optional<LabelledBox> box = cuboid(take(std::move(element), at), at)) data.boxes.push_back(std::move(*box));
        }
      } else if (key == "num") {
        read_speeds(v, where + ".num", data.speeds);
      }
    });
    return data;
  }

  // A cuboid's box, its speed from its attributes; nullopt for a null val.
  std::optional<LabelledBox> cuboid(od::value value, const std::string& where) const {
    LabelledBox box;
    std::vector<double> val;
    bool has_val = false, null_val = false;
    Speeds speeds;
    const std::string at = where + ".val";
    for_each_field(object(value, where), where, [&](std::string_view key, od::value v) {
      if (key == "val") {
        has_val = true;
        null_val = take(v.is_null(), at);
        if (!null_val) val = numbers(v, at);
      } else if (key == "coordinate_system") {
        box.coordinate_system = string(v, where + ".coordinate_system");
      } else if (key == "attributes") {
        const std::string attributes = where + ".attributes";
        for_each_field(object(v, attributes), attributes, [&](std::string_view k, od::value a) {
          if (k == "num") read_speeds(a, attributes + ".num", speeds);
        });
      }
    });
    if (!has_val) fail(at, "missing");
    if (null_val) return std::nullopt;
    if (val.size() != 9 && val.size() != 10) {
      fail(at, fmt::format("holds {} numbers; a cuboid holds 9 (x, y, z, rx, ry, rz, sx, sy, sz) or 10 (x, y, z, qx, qy, qz, qw, sx, sy, sz)",
                           val.size()));
    }
    box.x_m = val[0], box.y_m = val[1], box.z_m = val[2];
    if (val.size() == 10) {
      // Non-unit quaternions are allowed (ASAM OpenLABEL 7.10.1): normalised, scaled first so that
      // the squares neither overflow nor underflow.
      const double scale = std::max({std::abs(val[3]), std::abs(val[4]), std::abs(val[5]), std::abs(val[6])});
      if (scale == 0.0) fail(at, "the quaternion (qx, qy, qz, qw) is zero");
      const double qx = val[3] / scale, qy = val[4] / scale, qz = val[5] / scale, qw = val[6] / scale;
      const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
      box.yaw_rad = ros2::yaw_of_quaternion(qx / norm, qy / norm, qz / norm, qw / norm);
    } else {
      box.yaw_rad = wrap_angle_rad(val[5]);  // Euler angles applied ZYX: rz is the yaw
    }
    const std::size_t s = val.size() - 3;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!(val[s + k] > 0.0)) fail(fmt::format("{}[{}]", at, s + k), fmt::format("s{} = {} is no size: it must be > 0", "xyz"[k], val[s + k]));
    }
    box.length_m = val[s], box.width_m = val[s + 1], box.height_m = val[s + 2];
    box.speed_mps = speeds.best();
    return box;
  }

  // An array of finite numbers.
  std::vector<double> numbers(od::value value, const std::string& where) const {
    std::vector<double> out;
    for (auto element : take(value.get_array(), where)) {
      double v = 0.0;
      const simdjson::error_code error = element.get_double().get(v);
      if (error || !std::isfinite(v)) fail(fmt::format("{}[{}]", where, out.size()), describe(error ? error : simdjson::NUMBER_ERROR));
      out.push_back(v);
    }
    return out;
  }

  // Notes the speeds among an array of "num"; others are not read.
  void read_speeds(od::value value, const std::string& where, Speeds& speeds) const {
    std::size_t i = 0;
    for (auto element : take(value.get_array(), where)) {
      const std::string at = fmt::format("{}[{}]", where, i++);
      std::string name, type;
      double val = 0.0;
      simdjson::error_code val_error = simdjson::NO_SUCH_FIELD;
      for_each_field(object(take(std::move(element), at), at), at, [&](std::string_view key, od::value v) {
        if (key == "name") name = string(v, at + ".name");
        else if (key == "type") type = string(v, at + ".type");
        else if (key == "val") val_error = v.get_double().get(val);
      });
      if ((name != "speed_mps" && name != "speed") || (!type.empty() && type != "value")) continue;
      if (val_error || !std::isfinite(val)) fail(at + ".val", describe(val_error ? val_error : simdjson::NUMBER_ERROR));
      (name == "speed_mps" ? speeds.speed_mps : speeds.speed) = val;
    }
  }

  std::int64_t time_ns(od::value value, const std::string& where) const {
    const od::json_type type = take(value.type(), where);
    std::string text;
    std::optional<std::int64_t> t_ns;
    if (type == od::json_type::number) {
      text = trimmed(value.raw_json_token());
      t_ns = decimal_seconds_ns(text);
    } else if (type == od::json_type::string) {
      text = string(value, where);
      t_ns = decimal_seconds_ns(text);
      if (!t_ns) t_ns = iso8601_ns(text);
    } else {
      fail(where, "is neither a number nor a string");
    }
    if (!t_ns) {
      fail(where, fmt::format("{:?} is no time rcsim reads: give seconds since the epoch (a number, or a string of one) or an ISO 8601 "
                              "time with its zone, as 2023-04-01T12:00:00.050Z, between the years 1678 and 2261",
                              text.substr(0, 64)));
    }
    return *t_ns;
  }

  std::string file_;
  std::unordered_map<std::string, ObjectInfo> objects_;
};

}  // namespace

Labels read_openlabel(const std::filesystem::path& file) { return Reader(file.string()).read(read_text_file(file)); }

}  // namespace rcsim::replay::openlabel
