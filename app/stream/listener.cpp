#include "stream/listener.hpp"

#include <sys/socket.h>

#include <fmt/format.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/multicast.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "io/csv_reader.hpp"
#include "stream/endpoints.hpp"
#include "stream/pcap_writer.hpp"
#include "stream/reassembly.hpp"
#include "stream/sender_table.hpp"
#include "stream/stop_signals.hpp"

namespace rcsim::stream {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;

std::string target_rows_csv_header(bool elevation_column) {
  return elevation_column ? "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,elevation_rad\n"
                          : "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n";
}

void append_target_rows(std::string& out, TargetListFormat format, std::int64_t timestamp_ns, const TargetListMessage& list,
                        bool elevation_column) {
  // The same text as TargetListWriter::write_row at the tracks/detections level: t_s is the
  // header's nanoseconds back in seconds (exact for times with up to 9 decimals).
  const double t_s = static_cast<double>(timestamp_ns) / 1e9;
  if (format == TargetListFormat::Csv) {
    const std::string sensor = csv_field(list.sensor_id);
    for (const WireTarget& t : list.targets) {
      fmt::format_to(std::back_inserter(out), "{:.6f},{},{},{},{:.4f},{:.6f},{:.4f},{:.3f}", t_s, list.cycle, sensor,
                     t.id, t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db);
      if (elevation_column) fmt::format_to(std::back_inserter(out), ",{:.6f}", t.elevation_rad);
      out += '\n';
    }
    return;
  }
  const std::string sensor = nlohmann::json(list.sensor_id).dump();
  for (const WireTarget& t : list.targets) {
    fmt::format_to(std::back_inserter(out),
                   "{{\"t_s\":{:.6f},\"cycle\":{},\"sensor\":{},\"id\":{},\"range_m\":{:.4f},\"azimuth_rad\":{:.6f},"
                   "\"range_rate_mps\":{:.4f},\"amplitude_db\":{:.3f}",
                   t_s, list.cycle, sensor, t.id, t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db);
    if (elevation_column) fmt::format_to(std::back_inserter(out), ",\"elevation_rad\":{:.6f}", t.elevation_rad);
    out += "}\n";
  }
}

namespace {

constexpr std::size_t kFlushBytes = 1 << 16;
constexpr int kReceiveBufferBytes = 8 << 20;
constexpr auto kResubscribePeriod = std::chrono::milliseconds(500);
constexpr int kSubscribeAttempts = 20;
// Keepalives a subscribed listener sends without any reply before it takes the streamer for gone
// (crashed or killed) and ends with an error, keeping what it received.
constexpr int kUnansweredKeepalives = 5;

std::int64_t unix_time_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

struct Listener::Impl {
  Impl(const ListenOptions& options_in, std::ostream& out_in, std::ostream& log_in);

  void receive();
  void drain();
  void process(std::span<const std::uint8_t> datagram, const udp::endpoint& sender);
  void process_from(SenderState& source, const Header& header, std::span<const std::uint8_t> payload);
  void refuse(DecodeError error);
  void handle_reply(std::span<const std::uint8_t> payload, const udp::endpoint& from);
  void handle_message(const CompleteMessage& complete);
  void send_control(MessageType type);
  void subscribe_tick();
  void keepalive_tick();
  void idle_tick();
  void finish();
  void flush_output();
  // The rows' columns, fixed by the first target list printed: with elevation_rad when it carries
  // elevations. The CSV header goes out then (or at the end, without elevation, if none came).
  void fix_columns(bool elevation);

  ListenOptions options;
  std::ostream& out;
  std::ostream& log;
  asio::io_context io;
  udp::socket socket{io};
  udp::endpoint local;
  std::optional<udp::endpoint> control;
  asio::steady_timer subscribe_timer{io}, keepalive_timer{io}, idle_timer{io};
  asio::signal_set signals{io};
  std::array<std::uint8_t, 65536> buffer{};
  udp::endpoint sender;
  SenderTable<udp::endpoint> senders;
  ListenSummary summary;
  std::string output, truth_output;  // rows not yet written
  std::optional<bool> elevation_column;
  std::optional<std::ofstream> truth;
  std::optional<PcapWriter> pcap;
  std::unordered_map<std::uint32_t, std::uint32_t> last_cycle;  // (message type, sensor) -> the last list's cycle
  std::uint64_t control_sequence = 0;
  bool subscribed = false, stopping = false;
  int subscribe_attempts = 0;
  int unanswered_keepalives = 0;
  std::string failure;
  Clock::time_point last_datagram = Clock::now();
};

Listener::Impl::Impl(const ListenOptions& options_in, std::ostream& out_in, std::ostream& log_in)
    : options(options_in), out(out_in), log(log_in) {
  std::string bind = options.bind_address;
  if (bind.empty()) bind = options.group.empty() ? "127.0.0.1" : "0.0.0.0";
  const udp::endpoint at(asio::ip::make_address(bind), options.port);
  socket.open(at.protocol());
  if (!options.group.empty()) socket.set_option(asio::socket_base::reuse_address(true));
  // A large receive buffer absorbs bursts (--speed max) while this thread is not scheduled.
  // SO_RCVBUFFORCE passes the system's rmem_max where allowed (CAP_NET_ADMIN); else ask normally.
  int buffer_bytes = kReceiveBufferBytes;
  if (::setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVBUFFORCE, &buffer_bytes, sizeof buffer_bytes) != 0) {
    boost::system::error_code ignored;
    socket.set_option(asio::socket_base::receive_buffer_size(kReceiveBufferBytes), ignored);
  }
  socket.bind(at);
  if (!options.group.empty()) {
    const auto group = asio::ip::make_address_v4(options.group);
    if (options.group_interface.empty()) socket.set_option(asio::ip::multicast::join_group(group));
    else socket.set_option(asio::ip::multicast::join_group(group, asio::ip::make_address_v4(options.group_interface)));
  }
  local = socket.local_endpoint();
  if (!options.subscribe.empty()) {
    control = parse_endpoint(options.subscribe, "127.0.0.1");
    senders.pin(*control);
  }
  if (!options.truth_output.empty()) {
    truth.emplace(options.truth_output, std::ios::trunc);
    if (!*truth) throw std::runtime_error(options.truth_output + ": cannot open for writing");
    *truth << "t_s,cycle,kind,object,x_m,y_m,yaw_rad,speed_mps,length_m,width_m\n";
  }
  if (!options.pcap_output.empty()) pcap.emplace(options.pcap_output);
}

void Listener::Impl::fix_columns(bool elevation) {
  if (elevation_column) return;
  elevation_column = elevation;
  if (options.format == TargetListFormat::Csv) output.insert(0, target_rows_csv_header(elevation));
}

void Listener::Impl::receive() {
  socket.async_receive_from(asio::buffer(buffer), sender, [this](const boost::system::error_code& ec, std::size_t bytes) {
    if (ec == asio::error::operation_aborted || stopping) return;
    if (!ec) {
      process({buffer.data(), bytes}, sender);
      drain();
    }
    flush_output();
    if (!stopping) receive();
  });
}

// Takes what else is queued without going back to the loop (much cheaper per datagram).
void Listener::Impl::drain() {
  socket.non_blocking(true);
  for (int n = 0; n < 4096 && !stopping; ++n) {
    boost::system::error_code ec;
    const std::size_t bytes = socket.receive_from(asio::buffer(buffer), sender, 0, ec);
    if (ec) break;
    process({buffer.data(), bytes}, sender);
    if (output.size() + truth_output.size() >= kFlushBytes) flush_output();
  }
}

void Listener::Impl::flush_output() {
  if (truth && !truth_output.empty()) {
    truth->write(truth_output.data(), static_cast<std::streamsize>(truth_output.size()));
    truth->flush();
    truth_output.clear();
    if (!*truth && failure.empty()) {
      failure = options.truth_output + ": cannot write the ground truth (the disk is full, or the file was closed)";
      finish();
    }
  }
  if (output.empty()) return;
  out.write(output.data(), static_cast<std::streamsize>(output.size()));
  out.flush();
  output.clear();
  // Written as it arrives: what was received before a failed write is in the output.
  if (!out && failure.empty()) {
    failure = "cannot write the target lists (the disk is full, or the output was closed)";
    finish();
  }
}

void Listener::Impl::refuse(DecodeError error) {
  ++summary.malformed;
  ++summary.malformed_by_reason[static_cast<std::size_t>(error)];
}

void Listener::Impl::process(std::span<const std::uint8_t> datagram, const udp::endpoint& from) {
  ++summary.datagrams;
  summary.bytes += datagram.size();
  last_datagram = Clock::now();
  if (pcap) pcap->write(unix_time_ns(), from, local, datagram);
  const HeaderResult decoded = decode_header(datagram);
  if (decoded.error != DecodeError::none) return refuse(decoded.error);
  const Header& header = decoded.header;
  const auto payload = datagram.subspan(kHeaderBytes);
  if (is_control_request(header.type)) return refuse(DecodeError::wrong_kind);
  if (header.type == MessageType::control_reply) return handle_reply(payload, from);  // outside every stream

  bool fresh = false;
  SenderState& source = senders.hear(from, fresh);
  if (fresh) {
    // A subscription starts its stream at sequence 0; a passive listener starts where it joins.
    if (control && from == *control) source.sequence = SequenceTracker(std::uint64_t{0});
    ++summary.sources;
  }
  process_from(source, header, payload);
  senders.account(from);  // may forget other senders to keep the bounds
}

void Listener::Impl::process_from(SenderState& source, const Header& header, std::span<const std::uint8_t> payload) {
  if (source.sequence.observe(header.sequence) == Arrival::duplicate) return;
  if (header.type == MessageType::end_of_stream) {
    EndOfStream end;
    const DecodeError error = decode_end_of_stream(payload, end);
    if (error != DecodeError::none) return refuse(error);
    summary.end_received = true;
    summary.end = end;
    summary.sent_before_first = source.sequence.first().value_or(0);  // sequences count from 0
    if (options.stop_at_end) finish();
    return;
  }
  const Reassembler::Result result = source.reassembler.add(header, payload);
  if (result.status == Reassembler::Status::malformed) return refuse(result.error);
  if (!result.message) return;
  source.delivered = true;
  handle_message(*result.message);
}

void Listener::Impl::handle_message(const CompleteMessage& complete) {
  ++summary.messages;
  if (complete.header.fragment_count > 1) ++summary.fragmented_messages;
  if (complete.header.flags & kFlagLate) ++summary.late_flagged;
  if (const auto* list = std::get_if<TargetListMessage>(&complete.message)) {
    ++summary.target_lists;
    // A stream moves forward one cycle at a time: a list of a cycle already had, or of an earlier
    // one, means someone paused and replayed or seeked the stream (docs/stream.md).
    const std::uint32_t key = (static_cast<std::uint32_t>(complete.header.type) << 16) | list->sensor_index;
    if (const auto [last, first] = last_cycle.try_emplace(key, list->cycle); !first) {
      if (list->cycle == last->second) ++summary.cycles_repeated;
      if (list->cycle < last->second) ++summary.rewinds;
      last->second = list->cycle;
    }
    if (complete.header.type != options.print) return;
    summary.rows += list->targets.size();
    fix_columns(list->elevation);
    append_target_rows(output, options.format, complete.header.timestamp_ns, *list, *elevation_column);
    return;
  }
  const auto& gt = std::get<GroundTruthMessage>(complete.message);
  ++summary.truth_messages;
  if (!truth) return;
  const double t_s = static_cast<double>(complete.header.timestamp_ns) / 1e9;
  const auto row = [&](std::string_view kind, const std::string& id, const WirePose& p, double length_m, double width_m) {
    fmt::format_to(std::back_inserter(truth_output), "{:.6f},{},{},{},{:.4f},{:.4f},{:.6f},{:.4f},{:.4f},{:.4f}\n", t_s, gt.cycle, kind, csv_field(id),
                          p.x_m, p.y_m, p.yaw_rad, p.speed_mps, length_m, width_m);
  };
  row("ego", "ego", gt.ego, 0.0, 0.0);
  for (const WireObject& o : gt.objects) row("object", o.object_id, o.pose, o.length_m, o.width_m);
}

void Listener::Impl::handle_reply(std::span<const std::uint8_t> payload, const udp::endpoint& from) {
  // Only the streamer this listener subscribed at answers it; a passive listener asked nobody.
  if (!control || from != *control) {
    ++summary.stray_replies;
    return;
  }
  ControlReply reply;
  if (decode_control_reply(payload, reply) != DecodeError::none) {
    ++summary.malformed;
    ++summary.malformed_by_reason[static_cast<std::size_t>(DecodeError::bad_length)];
    return;
  }
  ++summary.replies;
  unanswered_keepalives = 0;
  if (reply.request_type == MessageType::subscribe) {
    if (reply.result == ReplyResult::ok) {
      if (!subscribed) log << "rcsim listen: subscribed at " << to_string(*control) << '\n';
      subscribed = true;
      subscribe_timer.cancel();
    } else if (reply.result == ReplyResult::refused_full) {
      failure = "the streamer at " + to_string(*control) + " refused the subscription: it has all the clients it takes";
      finish();
    }
  } else if (reply.request_type == MessageType::keepalive && reply.result == ReplyResult::not_subscribed && subscribed) {
    // The streamer dropped us (it had not heard from us in time): ask again.
    log << "rcsim listen: the streamer dropped the subscription; subscribing again\n";
    subscribed = false;
    subscribe_attempts = 0;
    subscribe_tick();
  }
}

void Listener::Impl::send_control(MessageType type) {
  Header header;
  header.type = type;
  header.sequence = control_sequence++;
  header.timestamp_ns = unix_time_ns();
  const Bytes datagram =
      make_datagram(header, encode_control_payload(type, options.messages, options.sensor_mask,
                                                   type == MessageType::subscribe ? options.control_token : ""));
  boost::system::error_code ignored;
  socket.send_to(asio::buffer(datagram), *control, 0, ignored);
}

void Listener::Impl::subscribe_tick() {
  if (subscribed || stopping) return;
  if (++subscribe_attempts > kSubscribeAttempts) {
    failure = "no answer from the control port " + to_string(*control);
    finish();
    return;
  }
  send_control(MessageType::subscribe);
  subscribe_timer.expires_after(kResubscribePeriod);
  subscribe_timer.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) subscribe_tick();
  });
}

void Listener::Impl::keepalive_tick() {
  if (stopping) return;
  if (subscribed) {
    if (unanswered_keepalives++ >= kUnansweredKeepalives) {
      failure = fmt::format("the streamer at {} stopped answering: {} keepalives unanswered", to_string(*control),
                            kUnansweredKeepalives);
      finish();
      return;
    }
    send_control(MessageType::keepalive);
  }
  keepalive_timer.expires_after(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.keepalive_s)));
  keepalive_timer.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) keepalive_tick();
  });
}

void Listener::Impl::idle_tick() {
  if (stopping) return;
  if (Clock::now() - last_datagram > std::chrono::duration<double>(options.idle_timeout_s)) {
    summary.idle = true;
    finish();
    return;
  }
  idle_timer.expires_after(std::chrono::milliseconds(100));
  idle_timer.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) idle_tick();
  });
}

void Listener::Impl::finish() {
  if (stopping) return;
  stopping = true;
  if (control && subscribed && !summary.end_received) send_control(MessageType::unsubscribe);
  io.stop();
}

Listener::Listener(const ListenOptions& options, std::ostream& out, std::ostream& log)
    : impl_(std::make_unique<Impl>(options, out, log)) {}

Listener::~Listener() = default;

std::uint16_t Listener::port() const { return impl_->local.port(); }

void Listener::stop() {
  asio::post(impl_->io, [impl = impl_.get()] { impl->finish(); });
}

ListenSummary Listener::run() {
  Impl& s = *impl_;
  s.log << "rcsim listen: listening on " << to_string(s.local) << '\n';
  s.log.flush();
  s.receive();
  if (s.control) {
    s.subscribe_tick();
    s.keepalive_tick();
  }
  if (s.options.idle_timeout_s > 0.0) s.idle_tick();
  if (s.options.handle_signals) {
    stop_on_signals(s.signals, [&s] {
      s.summary.interrupted = true;
      s.finish();
    });
  }
  const auto flush_all = [&s] {
    s.fix_columns(false);  // the CSV header, also when nothing arrives
    s.flush_output();
    if (s.pcap) s.pcap->flush();
    if (s.truth) s.truth->flush();
  };
  try {
    s.io.run();
  } catch (...) {
    flush_all();  // what was received before the error stays written
    throw;
  }
  flush_all();
  const SenderCounts counts = s.senders.finish();
  s.summary.lost += counts.lost;
  s.summary.duplicates += counts.duplicates;
  s.summary.reordered += counts.reordered;
  s.summary.incomplete += counts.incomplete;
  s.summary.senders_forgotten = s.senders.forgotten();
  s.summary.senders_peak = s.senders.peak_senders();
  s.summary.sender_state_peak_bytes = s.senders.peak_state_bytes();
  if (!s.failure.empty()) throw std::runtime_error(s.failure);
  return s.summary;
}

std::string ListenSummary::line() const {
  std::string text = fmt::format(
      "rcsim listen: {}{} datagrams ({} bytes{}) from {} source(s), {} messages ({} reassembled from fragments), "
      "{} target lists, {} rows, {} ground truth; {} lost, {} duplicates, {} reordered, {} incomplete, {} malformed",
      interrupted ? "stopped, " : idle ? "idle, " : "", datagrams, bytes,
      replies > 0 ? fmt::format("; {} of them control replies, outside the stream", replies) : "", sources, messages,
      fragmented_messages, target_lists, rows, truth_messages, lost, duplicates, reordered, incomplete, malformed);
  // A late cycle flags each of its messages (every sensor's target list, the ground truth).
  if (late_flagged > 0) text += fmt::format(", {} late-flagged messages", late_flagged);
  if (cycles_repeated > 0 || rewinds > 0) {
    text += fmt::format(", {} target lists of a cycle already received and {} rewinds (the stream was paused and "
                        "replayed or seeked)",
                        cycles_repeated, rewinds);
  }
  if (stray_replies > 0) text += fmt::format(", {} control replies from other than the streamer subscribed at, ignored", stray_replies);
  if (senders_forgotten > 0) {
    text += fmt::format(", {} senders forgotten (at most {} tracked, {} MiB)", senders_forgotten,
                        SenderTable<int>::kMaxSenders, SenderTable<int>::kMaxStateBytes >> 20);
  }
  if (end_received) {
    text += fmt::format("; end of stream: the sender sent {} datagrams, {} cycles", end.datagrams_sent + 1, end.cycles_sent);
    if (sent_before_first > 0) {
      text += fmt::format(", {} of the datagrams before the first one received (the listener started after the stream)",
                          sent_before_first);
    }
  } else {
    text += "; no end of stream received";
  }
  return text;
}

}  // namespace rcsim::stream
