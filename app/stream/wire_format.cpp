#include "stream/wire_format.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/limits.hpp"

namespace rcsim::stream {
namespace {

// Little-endian writer into a byte vector, independent of the host's byte order.
class Writer {
 public:
  explicit Writer(Bytes& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { put(v, 2); }
  void u32(std::uint32_t v) { put(v, 4); }
  void u64(std::uint64_t v) { put(v, 8); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void text(std::string_view s) { out_.insert(out_.end(), s.begin(), s.end()); }

 private:
  void put(std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  Bytes& out_;
};

// Little-endian reader that never reads past the end: a short read sets `ok` false and yields 0.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) : in_(in) {}
  bool ok() const { return ok_; }
  std::size_t remaining() const { return in_.size() - pos_; }
  std::uint8_t u8() { return static_cast<std::uint8_t>(get(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(get(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(get(4)); }
  std::uint64_t u64() { return get(8); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  double f64() { return std::bit_cast<double>(u64()); }
  std::string text(std::size_t n) {
    if (remaining() < n) {
      ok_ = false;
      return {};
    }
    std::string s(reinterpret_cast<const char*>(in_.data() + pos_), n);
    pos_ += n;
    return s;
  }

 private:
  std::uint64_t get(int bytes) {
    if (remaining() < static_cast<std::size_t>(bytes)) {
      ok_ = false;
      pos_ = in_.size();
      return 0;
    }
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(in_[pos_ + static_cast<std::size_t>(i)]) << (8 * i);
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

constexpr std::size_t kTargetListFixedBytes = 20;
constexpr double kMaxElevation_rad = 1.58;  // schemas/limits.md: a target's elevation, ±π/2
constexpr std::size_t kTruthFixedBytes = 48;
constexpr std::size_t kTruthObjectFixedBytes = 53;
constexpr std::size_t kEndBytes = 24;
constexpr std::size_t kReplyBytes = 32;

void check_id(const std::string& id, const char* what) {
  if (id.empty() || id.size() > 255) throw std::invalid_argument(std::string(what) + " must have 1 to 255 bytes: '" + id + "'");
}

// Well-formed UTF-8 (Unicode 15, table 3-7: no overlong forms, no surrogates, at most U+10FFFF):
// an id is printed into JSON Lines, whose writer refuses anything else.
bool is_utf8(std::string_view text) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const auto* end = p + text.size();
  const auto in = [](unsigned char c, unsigned char lo, unsigned char hi) { return c >= lo && c <= hi; };
  while (p < end) {
    const unsigned char c = *p;
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte
    if (c <= 0x7F) {
      ++p;
      continue;
    }
    if (in(c, 0xC2, 0xDF)) n = 1;
    else if (c == 0xE0) n = 2, lo = 0xA0;
    else if (in(c, 0xE1, 0xEC) || in(c, 0xEE, 0xEF)) n = 2;
    else if (c == 0xED) n = 2, hi = 0x9F;
    else if (c == 0xF0) n = 3, lo = 0x90;
    else if (in(c, 0xF1, 0xF3)) n = 3;
    else if (c == 0xF4) n = 3, hi = 0x8F;
    else return false;
    if (static_cast<std::size_t>(end - p) <= n || !in(p[1], lo, hi)) return false;
    for (std::size_t i = 2; i <= n; ++i) {
      if (!in(p[i], 0x80, 0xBF)) return false;
    }
    p += n + 1;
  }
  return true;
}

bool finite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// Within schemas/limits.md, as the file readers check them: a range of 1e308 is no measurement.
bool plausible(const WireTarget& t) {
  return std::abs(t.range_m) <= limits::kMaxRange_m && std::abs(t.azimuth_rad) <= limits::kMaxAzimuth_rad &&
         std::abs(t.range_rate_mps) <= limits::kMaxSpeed_mps && std::abs(t.amplitude_db) <= limits::kMaxLevel_dB &&
         std::abs(t.elevation_rad) <= kMaxElevation_rad;
}

bool plausible(const WirePose& p) {
  return std::abs(p.x_m) <= limits::kMaxCoordinate_m && std::abs(p.y_m) <= limits::kMaxCoordinate_m &&
         std::abs(p.yaw_rad) <= limits::kMaxUnwrappedYaw_rad && std::abs(p.speed_mps) <= limits::kMaxSpeed_mps;
}

void write_pose(Writer& w, const WirePose& p) {
  w.f64(p.x_m);
  w.f64(p.y_m);
  w.f64(p.yaw_rad);
  w.f64(p.speed_mps);
}

WirePose read_pose(Reader& r) {
  WirePose p;
  p.x_m = r.f64();
  p.y_m = r.f64();
  p.yaw_rad = r.f64();
  p.speed_mps = r.f64();
  return p;
}

std::size_t payload_capacity(std::size_t max_datagram_bytes) {
  if (max_datagram_bytes > kMaxDatagramBytes || max_datagram_bytes < kHeaderBytes + kTruthFixedBytes + 64 + 255) {
    throw std::invalid_argument("datagram size limit out of range");
  }
  return max_datagram_bytes - kHeaderBytes;
}

}  // namespace

bool is_control_request(MessageType type) {
  return static_cast<std::uint8_t>(type) >= 0x10 && static_cast<std::uint8_t>(type) <= 0x16;
}

std::string_view message_type_name(MessageType type) {
  switch (type) {
    case MessageType::simulated_targets: return "simulated_targets";
    case MessageType::recorded_targets: return "recorded_targets";
    case MessageType::ground_truth: return "ground_truth";
    case MessageType::end_of_stream: return "end_of_stream";
    case MessageType::control_reply: return "control_reply";
    case MessageType::subscribe: return "subscribe";
    case MessageType::unsubscribe: return "unsubscribe";
    case MessageType::pause: return "pause";
    case MessageType::resume: return "resume";
    case MessageType::step: return "step";
    case MessageType::seek: return "seek";
    case MessageType::keepalive: return "keepalive";
  }
  return "unknown";
}

std::uint32_t message_bit(MessageType type) {
  switch (type) {
    case MessageType::simulated_targets: return kSimulatedBit;
    case MessageType::recorded_targets: return kRecordedBit;
    case MessageType::ground_truth: return kTruthBit;
    default: return 0;
  }
}

std::string_view decode_error_name(DecodeError error) {
  switch (error) {
    case DecodeError::none: return "none";
    case DecodeError::too_short: return "too_short";
    case DecodeError::too_long: return "too_long";
    case DecodeError::bad_magic: return "bad_magic";
    case DecodeError::bad_version: return "bad_version";
    case DecodeError::unknown_type: return "unknown_type";
    case DecodeError::bad_fragment: return "bad_fragment";
    case DecodeError::bad_length: return "bad_length";
    case DecodeError::bad_value: return "bad_value";
    case DecodeError::wrong_kind: return "wrong_kind";
  }
  return "unknown";
}

void encode_header(const Header& header, std::uint8_t* out) {
  // Written in place (no allocation): this runs once per datagram and destination.
  const auto put = [&out](std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) *out++ = static_cast<std::uint8_t>(v >> (8 * i));
  };
  for (std::uint8_t b : kMagic) *out++ = b;
  put(kWireVersion, 1);
  put(static_cast<std::uint8_t>(header.type), 1);
  put(header.flags, 2);
  put(header.sequence, 8);
  put(static_cast<std::uint64_t>(header.timestamp_ns), 8);
  put(header.message_number, 4);
  put(header.fragment_index, 2);
  put(header.fragment_count, 2);
}

Bytes make_datagram(const Header& header, std::span<const std::uint8_t> payload) {
  Bytes datagram(kHeaderBytes + payload.size());
  encode_header(header, datagram.data());
  if (!payload.empty()) std::memcpy(datagram.data() + kHeaderBytes, payload.data(), payload.size());
  return datagram;
}

std::vector<Bytes> encode_target_list(const TargetListMessage& message, std::size_t max_datagram_bytes) {
  check_id(message.sensor_id, "a sensor id");
  const std::size_t capacity = payload_capacity(max_datagram_bytes);
  const std::size_t target_bytes = message.elevation ? kElevationTargetBytes : kTargetBytes;
  const std::size_t per_fragment = (capacity - kTargetListFixedBytes - message.sensor_id.size()) / target_bytes;
  const std::size_t total = message.targets.size();
  const std::size_t fragments = std::max<std::size_t>(1, (total + per_fragment - 1) / per_fragment);
  if (fragments > 0xFFFF) throw std::invalid_argument("target list too long for one message");
  std::vector<Bytes> out(fragments);
  for (std::size_t f = 0; f < fragments; ++f) {
    const std::size_t first = f * per_fragment;
    const std::size_t n = std::min(per_fragment, total - std::min(total, first));
    Bytes& payload = out[f];
    payload.reserve(kTargetListFixedBytes + message.sensor_id.size() + n * target_bytes);
    Writer w(payload);
    w.u32(message.cycle);
    w.u16(message.sensor_index);
    w.u8(static_cast<std::uint8_t>(message.level));
    w.u8(static_cast<std::uint8_t>(message.sensor_id.size()));
    w.u32(static_cast<std::uint32_t>(total));
    w.u32(static_cast<std::uint32_t>(first));
    w.u16(static_cast<std::uint16_t>(n));
    w.u16(message.elevation ? kListFlagElevation : std::uint16_t{0});
    w.text(message.sensor_id);
    for (std::size_t i = first; i < first + n; ++i) {
      const WireTarget& t = message.targets[i];
      w.i32(t.id);
      w.f64(t.range_m);
      w.f64(t.azimuth_rad);
      w.f64(t.range_rate_mps);
      w.f64(t.amplitude_db);
      if (message.elevation) w.f64(t.elevation_rad);
    }
  }
  return out;
}

std::vector<Bytes> encode_ground_truth(const GroundTruthMessage& message, std::size_t max_datagram_bytes) {
  const std::size_t capacity = payload_capacity(max_datagram_bytes);
  // Objects have variable size (their id): fill each fragment greedily, then write the counts.
  std::vector<std::pair<std::size_t, std::size_t>> slices;  // first, count
  std::size_t first = 0, used = kTruthFixedBytes;
  for (std::size_t i = 0; i < message.objects.size(); ++i) {
    check_id(message.objects[i].object_id, "an object id");
    const std::size_t size = kTruthObjectFixedBytes + message.objects[i].object_id.size();
    if (used + size > capacity) {
      slices.emplace_back(first, i - first);
      first = i;
      used = kTruthFixedBytes;
    }
    used += size;
  }
  slices.emplace_back(first, message.objects.size() - first);
  if (slices.size() > 0xFFFF) throw std::invalid_argument("ground truth too long for one message");
  std::vector<Bytes> out;
  for (const auto& [start, n] : slices) {
    Bytes payload;
    Writer w(payload);
    w.u32(message.cycle);
    w.u32(static_cast<std::uint32_t>(message.objects.size()));
    w.u32(static_cast<std::uint32_t>(start));
    w.u16(static_cast<std::uint16_t>(n));
    w.u16(0);
    write_pose(w, message.ego);
    for (std::size_t i = start; i < start + n; ++i) {
      const WireObject& o = message.objects[i];
      w.u32(o.object_index);
      write_pose(w, o.pose);
      w.f64(o.length_m);
      w.f64(o.width_m);
      w.u8(static_cast<std::uint8_t>(o.object_id.size()));
      w.text(o.object_id);
    }
    out.push_back(std::move(payload));
  }
  return out;
}

Bytes encode_end_of_stream(const EndOfStream& end) {
  Bytes payload;
  Writer w(payload);
  w.u64(end.datagrams_sent);
  w.u32(end.messages_sent);
  w.u32(end.cycles_sent);
  w.u32(end.late_cycles);
  w.u32(0);
  return payload;
}

Bytes encode_control_reply(const ControlReply& reply) {
  Bytes payload;
  Writer w(payload);
  w.u64(reply.request_sequence);
  w.u8(static_cast<std::uint8_t>(reply.request_type));
  w.u8(static_cast<std::uint8_t>(reply.result));
  w.u8(static_cast<std::uint8_t>(reply.state));
  w.u8(0);
  w.u32(reply.next_cycle);
  w.u32(reply.cycle_count);
  w.u32(reply.subscribers);
  w.u64(reply.control_ignored);
  return payload;
}

bool is_control_token(std::string_view token) {
  if (token.size() < kMinControlTokenBytes || token.size() > kMaxControlTokenBytes) return false;
  return std::all_of(token.begin(), token.end(), [](char c) { return c > ' ' && c < 0x7f; });
}

Bytes encode_control_payload(MessageType type, std::uint32_t argument, std::uint32_t sensor_mask,
                             std::string_view token) {
  Bytes payload;
  Writer w(payload);
  if (type == MessageType::subscribe) {
    w.u32(argument);
    w.u32(sensor_mask);
    if (!token.empty()) {  // u8 length, then the token's bytes
      w.u8(static_cast<std::uint8_t>(token.size()));
      payload.insert(payload.end(), token.begin(), token.end());
    }
  } else if (type == MessageType::step || type == MessageType::seek) {
    w.u32(argument);
  }
  return payload;
}

HeaderResult decode_header(std::span<const std::uint8_t> datagram) {
  HeaderResult result;
  if (datagram.size() < kHeaderBytes) {
    result.error = DecodeError::too_short;
    return result;
  }
  if (datagram.size() > kMaxDatagramBytes) {
    result.error = DecodeError::too_long;
    return result;
  }
  if (!std::equal(kMagic.begin(), kMagic.end(), datagram.begin())) {
    result.error = DecodeError::bad_magic;
    return result;
  }
  Reader r(datagram.subspan(4));
  if (r.u8() != kWireVersion) {
    result.error = DecodeError::bad_version;
    return result;
  }
  const std::uint8_t type = r.u8();
  Header& h = result.header;
  h.type = static_cast<MessageType>(type);
  h.flags = r.u16();
  h.sequence = r.u64();
  h.timestamp_ns = r.i64();
  h.message_number = r.u32();
  h.fragment_index = r.u16();
  h.fragment_count = r.u16();
  const bool known = (type >= 0x01 && type <= 0x05) || is_control_request(h.type);
  if (!known) {
    result.error = DecodeError::unknown_type;
    return result;
  }
  const bool fragmentable = h.type == MessageType::simulated_targets || h.type == MessageType::recorded_targets ||
                            h.type == MessageType::ground_truth;
  if (h.fragment_count == 0 || h.fragment_index >= h.fragment_count || (!fragmentable && h.fragment_count != 1)) {
    result.error = DecodeError::bad_fragment;
  }
  return result;
}

DecodeError decode_target_list(std::span<const std::uint8_t> payload, TargetListFragment& out) {
  Reader r(payload);
  TargetListMessage& m = out.message;
  m.cycle = r.u32();
  m.sensor_index = r.u16();
  const std::uint8_t level = r.u8();
  const std::size_t id_length = r.u8();
  out.total_count = r.u32();
  out.first_index = r.u32();
  const std::size_t n = r.u16();
  const std::uint16_t flags = r.u16();
  if (!r.ok()) return DecodeError::bad_length;
  if ((flags & ~kListFlagElevation) != 0) return DecodeError::bad_value;
  m.elevation = (flags & kListFlagElevation) != 0;
  if (r.remaining() != id_length + n * (m.elevation ? kElevationTargetBytes : kTargetBytes)) return DecodeError::bad_length;
  if (level > static_cast<std::uint8_t>(WireLevel::recorded) || id_length == 0) return DecodeError::bad_value;
  if (static_cast<std::uint64_t>(out.first_index) + n > out.total_count) return DecodeError::bad_value;
  m.level = static_cast<WireLevel>(level);
  m.sensor_id = r.text(id_length);
  if (!is_utf8(m.sensor_id)) return DecodeError::bad_value;
  m.targets.resize(n);
  for (WireTarget& t : m.targets) {
    t.id = r.i32();
    t.range_m = r.f64();
    t.azimuth_rad = r.f64();
    t.range_rate_mps = r.f64();
    t.amplitude_db = r.f64();
    t.elevation_rad = m.elevation ? r.f64() : 0.0;
    if (!finite({t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db, t.elevation_rad}) || !plausible(t)) {
      return DecodeError::bad_value;
    }
  }
  return DecodeError::none;
}

DecodeError decode_ground_truth(std::span<const std::uint8_t> payload, GroundTruthFragment& out) {
  Reader r(payload);
  GroundTruthMessage& m = out.message;
  m.cycle = r.u32();
  out.total_count = r.u32();
  out.first_index = r.u32();
  const std::size_t n = r.u16();
  r.u16();
  m.ego = read_pose(r);
  if (!r.ok()) return DecodeError::bad_length;
  if (static_cast<std::uint64_t>(out.first_index) + n > out.total_count) return DecodeError::bad_value;
  if (!finite({m.ego.x_m, m.ego.y_m, m.ego.yaw_rad, m.ego.speed_mps}) || !plausible(m.ego)) return DecodeError::bad_value;
  if (n > r.remaining() / kTruthObjectFixedBytes) return DecodeError::bad_length;
  m.objects.resize(n);
  for (WireObject& o : m.objects) {
    o.object_index = r.u32();
    o.pose = read_pose(r);
    o.length_m = r.f64();
    o.width_m = r.f64();
    const std::size_t id_length = r.u8();
    o.object_id = r.text(id_length);
    if (!r.ok()) return DecodeError::bad_length;
    if (id_length == 0 || !is_utf8(o.object_id) ||
        !finite({o.pose.x_m, o.pose.y_m, o.pose.yaw_rad, o.pose.speed_mps, o.length_m, o.width_m}) || !plausible(o.pose) ||
        std::abs(o.length_m) > limits::kMaxSize_m || std::abs(o.width_m) > limits::kMaxSize_m) {
      return DecodeError::bad_value;
    }
  }
  return r.remaining() == 0 ? DecodeError::none : DecodeError::bad_length;
}

DecodeError decode_end_of_stream(std::span<const std::uint8_t> payload, EndOfStream& out) {
  if (payload.size() != kEndBytes) return DecodeError::bad_length;
  Reader r(payload);
  out.datagrams_sent = r.u64();
  out.messages_sent = r.u32();
  out.cycles_sent = r.u32();
  out.late_cycles = r.u32();
  return DecodeError::none;
}

DecodeError decode_control_reply(std::span<const std::uint8_t> payload, ControlReply& out) {
  if (payload.size() != kReplyBytes) return DecodeError::bad_length;
  Reader r(payload);
  out.request_sequence = r.u64();
  out.request_type = static_cast<MessageType>(r.u8());
  const std::uint8_t result = r.u8();
  const std::uint8_t state = r.u8();
  r.u8();
  out.next_cycle = r.u32();
  out.cycle_count = r.u32();
  out.subscribers = r.u32();
  out.control_ignored = r.u64();
  if (result > 4 || state > 2) return DecodeError::bad_value;
  out.result = static_cast<ReplyResult>(result);
  out.state = static_cast<PlayState>(state);
  return DecodeError::none;
}

DecodeError decode_control_request(std::span<const std::uint8_t> datagram, ControlRequest& out) {
  const HeaderResult h = decode_header(datagram);
  if (h.error != DecodeError::none) return h.error;
  if (!is_control_request(h.header.type)) return DecodeError::wrong_kind;
  out.header = h.header;
  out.argument = 0;
  out.sensor_mask = 0;
  Reader r(datagram.subspan(kHeaderBytes));
  switch (h.header.type) {
    case MessageType::subscribe: {
      if (r.remaining() < 8) return DecodeError::bad_length;
      out.argument = r.u32();
      out.sensor_mask = r.u32();
      if ((out.argument & ~(kSimulatedBit | kRecordedBit | kTruthBit)) != 0 || out.argument == 0) return DecodeError::bad_value;
      if (r.remaining() == 0) return DecodeError::none;
      // The optional control token: u8 length, then that many bytes, ending the payload.
      const std::size_t length = r.u8();
      if (r.remaining() != length) return DecodeError::bad_length;
      out.token = r.text(length);
      if (!is_control_token(out.token)) return DecodeError::bad_value;
      return DecodeError::none;
    }
    case MessageType::step:
    case MessageType::seek:
      if (r.remaining() != 4) return DecodeError::bad_length;
      out.argument = r.u32();
      if (h.header.type == MessageType::step && (out.argument == 0 || out.argument > 0xFFFF)) return DecodeError::bad_value;
      return DecodeError::none;
    default:
      return r.remaining() == 0 ? DecodeError::none : DecodeError::bad_length;
  }
}

}  // namespace rcsim::stream
