#pragma once
// Fuzz entry points of the UDP stream (schemas/udp-stream.md, docs/fuzzing.md): what `rcsim
// listen` does with the datagrams it receives, and what `rcsim stream` does with a datagram on
// its control port. Both check, beyond "no crash", that what was decoded survives encoding again.
#include <fmt/format.h>

#include <array>
#include <map>
#include <utility>

#include "fuzz/fuzz_support.hpp"
#include "io/csv_reader.hpp"
#include "stream/listener.hpp"
#include "stream/reassembly.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::fuzz {

namespace udp {

using stream::Bytes;

// A stream of datagrams in one input: each is [source: u8][length: u16 LE][bytes]; a length
// beyond the input's end takes what is left.
inline std::vector<std::pair<std::uint8_t, Input>> split_datagrams(Input data) {
  std::vector<std::pair<std::uint8_t, Input>> out;
  while (data.size() >= 3) {
    const std::uint8_t source = data[0];
    const std::size_t length = std::min<std::size_t>(data[1] | (std::size_t{data[2]} << 8), data.size() - 3);
    out.emplace_back(source, data.subspan(3, length));
    data = data.subspan(3 + length);
  }
  return out;
}

inline void append_framed(Bytes& out, std::uint8_t source, const Bytes& datagram) {
  out.push_back(source);
  out.push_back(static_cast<std::uint8_t>(datagram.size() & 0xFF));
  out.push_back(static_cast<std::uint8_t>(datagram.size() >> 8));
  out.insert(out.end(), datagram.begin(), datagram.end());
}

inline void check(bool condition, const char* what) {
  if (!condition) throw Finding(what);
}

// Small enough to split a few targets into fragments, large enough for every header and id
// (wire_format.cpp, payload_capacity).
inline constexpr std::size_t kSmallDatagramBytes = 600;

// A complete target list, encoded again (in fragments of every size) and decoded, is itself.
inline void check_round_trip(const stream::TargetListMessage& list) {
  for (const std::size_t max_datagram_bytes : {stream::kMaxDatagramBytes, kSmallDatagramBytes}) {
    std::vector<stream::WireTarget> targets;
    for (const Bytes& payload : stream::encode_target_list(list, max_datagram_bytes)) {
      stream::TargetListFragment fragment;
      check(stream::decode_target_list(payload, fragment) == stream::DecodeError::none, "a re-encoded target list does not decode");
      check(fragment.message.cycle == list.cycle && fragment.message.sensor_id == list.sensor_id &&
                fragment.message.level == list.level && fragment.message.sensor_index == list.sensor_index &&
                fragment.message.elevation == list.elevation && fragment.total_count == list.targets.size() && fragment.first_index == targets.size(),
            "a re-encoded target list decodes to another list");
      targets.insert(targets.end(), fragment.message.targets.begin(), fragment.message.targets.end());
    }
    check(targets.size() == list.targets.size(), "a re-encoded target list has another target count");
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const auto& a = targets[i];
      const auto& b = list.targets[i];
      check(a.id == b.id && a.range_m == b.range_m && a.azimuth_rad == b.azimuth_rad && a.range_rate_mps == b.range_rate_mps &&
                a.amplitude_db == b.amplitude_db && a.elevation_rad == b.elevation_rad,
            "a re-encoded target differs");
    }
  }
}

// What the listener (app/stream/listener.cpp, Listener::Impl::process and handle_message) does
// with one datagram from one sender; the socket, the pcap file and the subscription are left out.
struct ListenerState {
  struct Source {
    stream::SequenceTracker sequence;
    stream::Reassembler reassembler;
  };
  std::map<std::uint8_t, Source> sources;
  std::string output, truth_output;
  std::uint64_t malformed = 0;

  void process(Input datagram, std::uint8_t from) {
    const stream::HeaderResult decoded = stream::decode_header(datagram);
    if (decoded.error != stream::DecodeError::none) return refuse();
    const stream::Header& header = decoded.header;
    const Input payload = datagram.subspan(stream::kHeaderBytes);
    if (stream::is_control_request(header.type)) return refuse();
    if (header.type == stream::MessageType::control_reply) {
      stream::ControlReply reply;
      if (stream::decode_control_reply(payload, reply) != stream::DecodeError::none) return refuse();
      const Bytes again = stream::encode_control_reply(reply);
      stream::ControlReply twice;
      check(stream::decode_control_reply(again, twice) == stream::DecodeError::none && again == stream::encode_control_reply(twice),
            "a re-encoded control reply differs");
      return;
    }
    Source& source = sources[from];
    if (source.sequence.observe(header.sequence) == stream::Arrival::duplicate) return;
    if (header.type == stream::MessageType::end_of_stream) {
      stream::EndOfStream end;
      if (stream::decode_end_of_stream(payload, end) != stream::DecodeError::none) return refuse();
      return;
    }
    const stream::Reassembler::Result result = source.reassembler.add(header, payload);
    if (result.status == stream::Reassembler::Status::malformed) return refuse();
    if (result.message) handle_message(*result.message);
  }

  void handle_message(const stream::CompleteMessage& complete) {
    if (const auto* list = std::get_if<stream::TargetListMessage>(&complete.message)) {
      stream::append_target_rows(output, TargetListFormat::Csv, complete.header.timestamp_ns, *list);
      stream::append_target_rows(output, TargetListFormat::Jsonl, complete.header.timestamp_ns, *list);
      check_round_trip(*list);
      return;
    }
    const auto& gt = std::get<stream::GroundTruthMessage>(complete.message);
    const double t_s = static_cast<double>(complete.header.timestamp_ns) / 1e9;
    const auto row = [&](std::string_view kind, const std::string& id, const stream::WirePose& p, double length_m, double width_m) {
      fmt::format_to(std::back_inserter(truth_output), "{:.6f},{},{},{},{:.4f},{:.4f},{:.6f},{:.4f},{:.4f},{:.4f}\n", t_s, gt.cycle,
                     kind, csv_field(id), p.x_m, p.y_m, p.yaw_rad, p.speed_mps, length_m, width_m);
    };
    row("ego", "ego", gt.ego, 0.0, 0.0);
    for (const stream::WireObject& o : gt.objects) row("object", o.object_id, o.pose, o.length_m, o.width_m);
  }

  void refuse() { ++malformed; }
};

}  // namespace udp

// Input: datagrams as a listener receives them from up to four senders (udp::split_datagrams).
inline void fuzz_udp_datagrams(Input data) {
  udp::ListenerState listener;
  for (const auto& [source, datagram] : udp::split_datagrams(data)) listener.process(datagram, source & 3);
  for (auto& [from, source] : listener.sources) source.reassembler.flush();
}

// Input: one datagram on the streamer's control port (app/stream/streamer.cpp, handle_control).
// A request it decodes, encoded again, decodes to the same request.
inline void fuzz_udp_control(Input data) {
  stream::ControlRequest request;
  if (stream::decode_control_request(data, request) != stream::DecodeError::none) return;
  const stream::Bytes again = stream::make_datagram(
      request.header,
      stream::encode_control_payload(request.header.type, request.argument, request.sensor_mask, request.token));
  stream::ControlRequest twice;
  udp::check(stream::decode_control_request(again, twice) == stream::DecodeError::none, "a re-encoded control request does not decode");
  udp::check(twice.header.type == request.header.type && twice.header.sequence == request.header.sequence &&
                 twice.header.timestamp_ns == request.header.timestamp_ns && twice.header.flags == request.header.flags &&
                 twice.argument == request.argument && twice.sensor_mask == request.sensor_mask &&
                 twice.token == request.token,
             "a re-encoded control request differs");
}

// Seeds made by the encoders (scripts/fuzz.sh writes them through the harnesses): name -> bytes.
inline std::vector<std::pair<std::string, stream::Bytes>> udp_datagram_seeds() {
  using namespace stream;
  std::vector<std::pair<std::string, Bytes>> seeds;
  TargetListMessage list;
  list.cycle = 7;
  list.sensor_index = 1;
  list.level = WireLevel::tracks;
  list.sensor_id = "front_left";
  for (int i = 0; i < 60; ++i) list.targets.push_back({i, 5.0 + i, 0.01 * i - 0.3, -1.5, 12.0 + 0.1 * i});
  GroundTruthMessage truth;
  truth.cycle = 7;
  truth.ego = {1.0, 2.0, 0.1, 10.0};
  for (std::uint32_t i = 0; i < 12; ++i) truth.objects.push_back({i, {20.0 + i, -3.0, 3.14, 5.0}, 4.6, 1.8, fmt::format("car_{}", i)});
  std::uint64_t sequence = 0;
  std::uint32_t message = 0;
  const auto datagrams = [&](MessageType type, const std::vector<Bytes>& payloads) {
    std::vector<Bytes> out;
    for (std::size_t f = 0; f < payloads.size(); ++f) {
      Header h;
      h.type = type;
      h.sequence = sequence++;
      h.timestamp_ns = 280'000'000;
      h.message_number = message;
      h.fragment_index = static_cast<std::uint16_t>(f);
      h.fragment_count = static_cast<std::uint16_t>(payloads.size());
      out.push_back(make_datagram(h, payloads[f]));
    }
    ++message;
    return out;
  };
  const auto bundle = [](const std::vector<Bytes>& list_of_datagrams, std::uint8_t source = 0) {
    Bytes out;
    for (const Bytes& d : list_of_datagrams) udp::append_framed(out, source, d);
    return out;
  };
  const std::vector<Bytes> whole = datagrams(MessageType::simulated_targets, encode_target_list(list));
  const std::vector<Bytes> fragments = datagrams(MessageType::recorded_targets, encode_target_list(list, udp::kSmallDatagramBytes));
  const std::vector<Bytes> gt = datagrams(MessageType::ground_truth, encode_ground_truth(truth, udp::kSmallDatagramBytes));
  const std::vector<Bytes> end = datagrams(MessageType::end_of_stream, {encode_end_of_stream({40, 12, 3, 1})});
  ControlReply reply;
  reply.request_type = MessageType::subscribe;
  reply.cycle_count = 100;
  const std::vector<Bytes> replies = datagrams(MessageType::control_reply, {encode_control_reply(reply)});
  seeds.emplace_back("target_list", bundle(whole));
  TargetListMessage elevated = list;  // a radar that measures elevation: 44-byte targets (issue 49)
  elevated.elevation = true;
  for (std::size_t i = 0; i < elevated.targets.size(); ++i) elevated.targets[i].elevation_rad = 0.002 * static_cast<double>(i) - 0.05;
  seeds.emplace_back("target_list_elevation",
                     bundle(datagrams(MessageType::simulated_targets, encode_target_list(elevated, udp::kSmallDatagramBytes))));
  seeds.emplace_back("target_list_fragments", bundle(fragments));
  seeds.emplace_back("ground_truth_fragments", bundle(gt));
  seeds.emplace_back("end_of_stream", bundle(end));
  seeds.emplace_back("control_reply", bundle(replies));
  std::vector<Bytes> shuffled = fragments;  // reordered, one duplicated, a second sender
  std::swap(shuffled[1], shuffled[2]);
  shuffled.push_back(shuffled[1]);
  Bytes mixed = bundle(shuffled);
  const Bytes other = bundle(gt, 1);
  mixed.insert(mixed.end(), other.begin(), other.end());
  const Bytes last = bundle(end);
  mixed.insert(mixed.end(), last.begin(), last.end());
  seeds.emplace_back("target_fragments_reordered_and_ground_truth_from_a_second_sender", mixed);
  return seeds;
}

inline std::vector<std::pair<std::string, stream::Bytes>> udp_control_seeds() {
  using namespace stream;
  std::vector<std::pair<std::string, Bytes>> seeds;
  const std::pair<const char*, MessageType> types[] = {{"subscribe", MessageType::subscribe}, {"unsubscribe", MessageType::unsubscribe},
                                                       {"pause", MessageType::pause},         {"resume", MessageType::resume},
                                                       {"step", MessageType::step},           {"seek", MessageType::seek},
                                                       {"keepalive", MessageType::keepalive}};
  std::uint64_t sequence = 0;
  for (const auto& [name, type] : types) {
    Header h;
    h.type = type;
    h.sequence = sequence++;
    const std::uint32_t argument = type == MessageType::subscribe ? (kSimulatedBit | kTruthBit) : type == MessageType::seek ? 50 : 3;
    seeds.emplace_back(name, make_datagram(h, encode_control_payload(type, argument, 0b101)));
  }
  // A subscribe that presents a control token (docs/stream.md: who can do what).
  Header h;
  h.type = MessageType::subscribe;
  h.sequence = sequence;
  seeds.emplace_back("subscribe_with_token",
                     make_datagram(h, encode_control_payload(MessageType::subscribe, kSimulatedBit, 0, "0123456789abcdef-token")));
  return seeds;
}

}  // namespace rcsim::fuzz
