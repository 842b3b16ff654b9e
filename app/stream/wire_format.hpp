#pragma once
// The rcsim UDP stream, format `rcsim-udp` version 1 (schemas/udp-stream.md): every datagram is a
// 32-byte little-endian header followed by a payload that depends on the message type. Target
// lists and ground truth that do not fit into one datagram of at most 1472 bytes (an Ethernet MTU
// of 1500 minus IPv4 and UDP headers) are split into fragments, each of which carries a
// self-contained slice of the items, so that a decoder can read every fragment on its own.
//
// Encoding never fails for valid input; decoding reports why a datagram was refused, so that the
// streamer and the listener can count hostile or broken datagrams instead of trusting them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rcsim::stream {

inline constexpr std::array<std::uint8_t, 4> kMagic = {'R', 'C', 'S', 'M'};
inline constexpr std::uint8_t kWireVersion = 1;
inline constexpr std::size_t kHeaderBytes = 32;
inline constexpr std::size_t kMaxDatagramBytes = 1472;
inline constexpr std::size_t kTargetBytes = 36;  // i32 id + 4 × f64
// A target list whose flags have kListFlagElevation: each target carries elevation_rad as a fifth f64.
inline constexpr std::size_t kElevationTargetBytes = 44;
inline constexpr std::uint16_t kListFlagElevation = 1u << 0;

enum class MessageType : std::uint8_t {
  simulated_targets = 0x01,
  recorded_targets = 0x02,
  ground_truth = 0x03,
  end_of_stream = 0x04,
  control_reply = 0x05,
  subscribe = 0x10,
  unsubscribe = 0x11,
  pause = 0x12,
  resume = 0x13,
  step = 0x14,
  seek = 0x15,
  keepalive = 0x16,
};
bool is_control_request(MessageType type);
std::string_view message_type_name(MessageType type);

// Bits of a subscription's message mask (and of the streamer's --messages).
enum MessageBits : std::uint32_t {
  kSimulatedBit = 1u << 0,
  kRecordedBit = 1u << 1,
  kTruthBit = 1u << 2,
};
std::uint32_t message_bit(MessageType type);  // 0 for types that are not selectable

// Header flags.
inline constexpr std::uint16_t kFlagLate = 1u << 0;  // the cycle left after its deadline + tolerance

struct Header {
  MessageType type = MessageType::simulated_targets;
  std::uint16_t flags = 0;
  std::uint64_t sequence = 0;        // per stream, +1 per datagram
  std::int64_t timestamp_ns = 0;     // source time of the cycle (scene or recording time)
  std::uint32_t message_number = 0;  // per stream, +1 per message; shared by its fragments
  std::uint16_t fragment_index = 0;
  std::uint16_t fragment_count = 1;
};

// Level byte of a target list: which stage of the sensor cycle it is.
enum class WireLevel : std::uint8_t { ideal = 0, detections = 1, tracks = 2, recorded = 3 };

struct WireTarget {
  std::int32_t id = 0;
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
  double elevation_rad = 0.0;  // on the wire only in a list with `elevation`
};

// One sensor's target list in one cycle (one message, one or more fragments).
struct TargetListMessage {
  std::uint32_t cycle = 0;
  std::uint16_t sensor_index = 0;
  WireLevel level = WireLevel::tracks;
  std::string sensor_id;  // 1..255 bytes
  // The sensor measures elevation: the list has the flag kListFlagElevation and 44-byte targets.
  // Without it the list is byte for byte what it was before elevations (36-byte targets).
  bool elevation = false;
  std::vector<WireTarget> targets;
};

struct WirePose {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, speed_mps = 0.0;
};
struct WireObject {
  std::uint32_t object_index = 0;
  WirePose pose;  // box centre in the world frame
  double length_m = 0.0, width_m = 0.0;
  std::string object_id;  // 1..255 bytes
};
// Ego pose and every present object's box in one cycle.
struct GroundTruthMessage {
  std::uint32_t cycle = 0;
  WirePose ego;
  std::vector<WireObject> objects;
};

struct EndOfStream {
  std::uint64_t datagrams_sent = 0;  // to this stream before this datagram
  std::uint32_t messages_sent = 0;
  std::uint32_t cycles_sent = 0;
  std::uint32_t late_cycles = 0;
};

// not_allowed: steering from a subscription that does not hold the streamer's control token.
enum class ReplyResult : std::uint8_t { ok = 0, refused_full = 1, not_subscribed = 2, out_of_range = 3, not_allowed = 4 };
enum class PlayState : std::uint8_t { running = 0, paused = 1, finished = 2 };

struct ControlReply {
  std::uint64_t request_sequence = 0;
  MessageType request_type = MessageType::keepalive;
  ReplyResult result = ReplyResult::ok;
  PlayState state = PlayState::running;
  std::uint32_t next_cycle = 0;
  std::uint32_t cycle_count = 0;
  std::uint32_t subscribers = 0;
  std::uint64_t control_ignored = 0;  // malformed control datagrams counted so far
};

// A request to the control port. `argument` is the step count (STEP), the cycle (SEEK), or the
// message mask (SUBSCRIBE, with `sensor_mask`: bit i = sensor index i, 0 = every sensor).
// A control token: what a subscribe request presents to be allowed to steer (schemas/udp-stream.md).
inline constexpr std::size_t kMinControlTokenBytes = 16, kMaxControlTokenBytes = 64;
// Whether `token` is one: 16 to 64 printable ASCII characters, no space.
bool is_control_token(std::string_view token);

struct ControlRequest {
  Header header;
  std::uint32_t argument = 0;
  std::uint32_t sensor_mask = 0;
  std::string token;  // subscribe only: the control token presented, empty for none
};

// ---- encoding ----
using Bytes = std::vector<std::uint8_t>;

void encode_header(const Header& header, std::uint8_t* out);  // writes kHeaderBytes
// The payloads of the fragments, in order; at most `max_datagram_bytes` − kHeaderBytes each.
std::vector<Bytes> encode_target_list(const TargetListMessage& message, std::size_t max_datagram_bytes = kMaxDatagramBytes);
std::vector<Bytes> encode_ground_truth(const GroundTruthMessage& message, std::size_t max_datagram_bytes = kMaxDatagramBytes);
Bytes encode_end_of_stream(const EndOfStream& end);
Bytes encode_control_reply(const ControlReply& reply);
Bytes encode_control_payload(MessageType type, std::uint32_t argument, std::uint32_t sensor_mask,
                             std::string_view token = {});
// A whole datagram: header + payload.
Bytes make_datagram(const Header& header, std::span<const std::uint8_t> payload);

// ---- decoding ----
enum class DecodeError : std::uint8_t {
  none = 0,
  too_short,     // shorter than the header
  too_long,      // longer than kMaxDatagramBytes
  bad_magic,
  bad_version,
  unknown_type,
  bad_fragment,  // index ≥ count, count 0, or a fragmented type that cannot be
  bad_length,    // payload length does not match what its fields announce
  bad_value,     // a field out of range: non-finite number, empty string, count > total
  wrong_kind,    // a data message where a control request was expected, or the reverse
};
std::string_view decode_error_name(DecodeError error);
inline constexpr std::size_t kDecodeErrorCount = 10;

struct HeaderResult {
  Header header;
  DecodeError error = DecodeError::none;
};
HeaderResult decode_header(std::span<const std::uint8_t> datagram);

// One fragment's slice; `first_index` + items.size() ≤ `total_count`.
struct TargetListFragment {
  TargetListMessage message;  // targets holds this fragment's slice
  std::uint32_t total_count = 0;
  std::uint32_t first_index = 0;
};
struct GroundTruthFragment {
  GroundTruthMessage message;  // objects holds this fragment's slice
  std::uint32_t total_count = 0;
  std::uint32_t first_index = 0;
};

// Each decodes the payload after the header (span starts at byte kHeaderBytes).
DecodeError decode_target_list(std::span<const std::uint8_t> payload, TargetListFragment& out);
DecodeError decode_ground_truth(std::span<const std::uint8_t> payload, GroundTruthFragment& out);
DecodeError decode_end_of_stream(std::span<const std::uint8_t> payload, EndOfStream& out);
DecodeError decode_control_reply(std::span<const std::uint8_t> payload, ControlReply& out);
// A whole control datagram as the streamer receives it.
DecodeError decode_control_request(std::span<const std::uint8_t> datagram, ControlRequest& out);

}  // namespace rcsim::stream
