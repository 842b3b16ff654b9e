#include "stream/streamer.hpp"

#include <fmt/format.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/multicast.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <ctime>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "stream/endpoints.hpp"
#include "stream/frame_producer.hpp"
#include "stream/pacing.hpp"
#include "stream/stop_signals.hpp"

namespace rcsim::stream {

namespace asio = boost::asio;

namespace {

constexpr int kSocketBufferBytes = 4 << 20;
constexpr int kMaxCyclesPerTurn = 32;  // at max speed: then let control and timers run
constexpr auto kHousekeepingPeriod = std::chrono::milliseconds(250);

// One stream: a fixed destination or a subscribed client.
struct Sink {
  udp::endpoint endpoint;
  udp::socket* socket = nullptr;
  std::uint32_t messages = 0;
  std::uint32_t sensor_mask = 0;  // 0: every sensor
  bool client = false;
  bool controller = false;  // a client that may steer playback (schemas/udp-stream.md)
  TimePoint last_heard{};
  std::uint64_t sequence = 0;
  std::uint32_t message_number = 0;
  std::uint32_t cycles = 0;
  std::uint32_t late_cycles = 0;
};

bool wants(const Sink& sink, const EncodedMessage& message) {
  if ((sink.messages & message_bit(message.type)) == 0) return false;
  if (message.type == MessageType::ground_truth || sink.sensor_mask == 0) return true;
  return message.sensor_index < 32 && (sink.sensor_mask >> message.sensor_index & 1u) != 0;
}

void set_buffer_sizes(udp::socket& socket) {
  boost::system::error_code ignored;
  socket.set_option(asio::socket_base::send_buffer_size(kSocketBufferBytes), ignored);
  socket.set_option(asio::socket_base::receive_buffer_size(kSocketBufferBytes), ignored);
}

}  // namespace

struct Streamer::Impl {
  Impl(CycleSource& source_in, const StreamOptions& options_in, std::ostream& log_in)
      : source(source_in),
        options(options_in),
        log(log_in),
        pacer(Pacer::Options{options_in.speed, options_in.late_tolerance, options_in.stepped}),
        producer(source_in, options_in.queue_cycles, [this] { post_pump(); }) {
    open_sockets();
  }

  void open_sockets();
  udp::socket& data_socket(const udp::endpoint& endpoint);
  void post_pump();
  void pump();
  void arm_timer(TimePoint at);
  void cancel_timer() { ++timer_token; send_timer.cancel(); }
  void send_frame(const CycleFrame& frame, std::uint16_t flags);
  void send_datagram(Sink& sink, const Header& header, std::span<const std::uint8_t> payload);
  void send_end(Sink& sink);
  void finish();
  void do_stop();
  void receive_control();
  void handle_control(std::span<const std::uint8_t> datagram, const udp::endpoint& sender);
  void reply(const udp::endpoint& to, const ControlRequest& request, ReplyResult result);
  void seek(std::uint32_t cycle);
  void housekeeping();
  std::size_t client_count() const;
  Sink* find_client(const udp::endpoint& endpoint);
  bool may_steer(const std::string& token) const;
  void evict_oldest_watcher();

  CycleSource& source;
  StreamOptions options;
  std::ostream& log;
  asio::io_context io;
  std::optional<udp::socket> control, data_v4, data_v6;
  asio::steady_timer send_timer{io}, housekeeping_timer{io};
  asio::signal_set signals{io};
  Pacer pacer;
  LatenessStats lateness;
  std::vector<Sink> sinks;
  StreamSummary summary;
  std::optional<CycleFrame> current;
  std::uint32_t next_cycle = 0;
  std::uint64_t timer_token = 0;
  bool pump_posted = false, started = false, finished = false, stopping = false;
  TimePoint last_late_report{};
  std::array<std::uint8_t, 65536> control_buffer{};
  udp::endpoint control_sender;
  // Last: its thread posts into io, so it stops (joins) before io goes.
  FrameProducer producer;
};

void Streamer::Impl::open_sockets() {
  if (options.destinations.empty() && options.control.empty()) {
    throw std::invalid_argument("nothing to stream to: give --to HOST:PORT and/or --control PORT");
  }
  if (options.destination_messages == 0 && !options.destinations.empty()) throw std::invalid_argument("--messages selects nothing");
  for (const std::string& text : options.destinations) {
    Sink sink;
    sink.endpoint = parse_endpoint(text);
    if (sink.endpoint.port() == 0) throw std::invalid_argument("'" + text + "': port 0 is not a destination");
    sink.socket = &data_socket(sink.endpoint);
    sink.messages = options.destination_messages;
    sinks.push_back(sink);
  }
  if (!options.control.empty()) {
    const udp::endpoint at = parse_endpoint(options.control, "127.0.0.1");
    control.emplace(io, at.protocol());
    control->set_option(asio::socket_base::reuse_address(false));
    control->bind(at);
    set_buffer_sizes(*control);
  }
}

udp::socket& Streamer::Impl::data_socket(const udp::endpoint& endpoint) {
  auto& socket = endpoint.address().is_v4() ? data_v4 : data_v6;
  if (!socket) {
    socket.emplace(io, endpoint.protocol());
    set_buffer_sizes(*socket);
    if (endpoint.address().is_v4()) {
      socket->set_option(asio::ip::multicast::hops(options.multicast_ttl));
      socket->set_option(asio::ip::multicast::enable_loopback(true));
      if (!options.multicast_interface.empty()) {
        socket->set_option(asio::ip::multicast::outbound_interface(asio::ip::make_address_v4(options.multicast_interface)));
      }
    }
  }
  return *socket;
}

std::size_t Streamer::Impl::client_count() const {
  return static_cast<std::size_t>(std::count_if(sinks.begin(), sinks.end(), [](const Sink& s) { return s.client; }));
}

Sink* Streamer::Impl::find_client(const udp::endpoint& endpoint) {
  for (Sink& s : sinks) {
    if (s.client && s.endpoint == endpoint) return &s;
  }
  return nullptr;
}

void Streamer::Impl::post_pump() {
  asio::post(io, [this] {
    pump_posted = false;
    pump();
  });
}

void Streamer::Impl::arm_timer(TimePoint at) {
  const std::uint64_t token = ++timer_token;
  send_timer.expires_at(at);
  send_timer.async_wait([this, token](const boost::system::error_code& ec) {
    if (ec || token != timer_token) return;
    pump();
  });
}

void Streamer::Impl::pump() {
  for (int sent = 0; !stopping && !finished;) {
    if (!started) {
      if (client_count() < static_cast<std::size_t>(std::max(0, options.wait_clients))) return;
      started = true;
    }
    if (!current) {
      current = producer.try_pop();
      if (!current) {
        if (producer.finished()) finish();
        return;  // the producer posts a pump when the next frame is ready
      }
    }
    const Pacer::Decision decision = pacer.decide(SteadyClock::now(), current->t_s);
    if (decision.action == Pacer::Action::hold) return;
    if (decision.action == Pacer::Action::wait) {
      arm_timer(decision.at);
      return;
    }
    const Pacer::SendRecord record = pacer.on_sent(SteadyClock::now(), current->t_s);
    lateness.add(record);
    send_frame(*current, record.late ? kFlagLate : std::uint16_t{0});
    ++summary.cycles;
    if (record.late) {
      const TimePoint now = SteadyClock::now();
      if (lateness.late() == 1 || now - last_late_report >= std::chrono::seconds(1)) {
        log << fmt::format("rcsim stream: cycle {} left {:.3f} ms after its deadline ({} late cycles so far)\n",
                           current->cycle, std::chrono::duration<double, std::milli>(record.lateness).count(),
                           lateness.late());
        last_late_report = now;
      }
    }
    next_cycle = current->cycle + 1;
    current.reset();
    if (++sent >= kMaxCyclesPerTurn) {
      if (!pump_posted) {
        pump_posted = true;
        post_pump();
      }
      return;
    }
  }
}

void Streamer::Impl::send_datagram(Sink& sink, const Header& header, std::span<const std::uint8_t> payload) {
  std::array<std::uint8_t, kHeaderBytes> head{};
  encode_header(header, head.data());
  const std::array<asio::const_buffer, 2> buffers{asio::buffer(head), asio::buffer(payload.data(), payload.size())};
  boost::system::error_code ec;
  sink.socket->send_to(buffers, sink.endpoint, 0, ec);
  if (ec) {
    ++summary.send_errors;
    return;
  }
  ++summary.datagrams;
  summary.bytes += kHeaderBytes + payload.size();
}

void Streamer::Impl::send_frame(const CycleFrame& frame, std::uint16_t flags) {
  for (Sink& sink : sinks) {
    bool any = false;
    for (const EncodedMessage& message : frame.messages) {
      if (!wants(sink, message)) continue;
      any = true;
      Header header;
      header.type = message.type;
      header.flags = flags;
      header.timestamp_ns = frame.timestamp_ns;
      header.message_number = sink.message_number++;
      header.fragment_count = static_cast<std::uint16_t>(message.fragments.size());
      for (std::size_t f = 0; f < message.fragments.size(); ++f) {
        header.sequence = sink.sequence++;
        header.fragment_index = static_cast<std::uint16_t>(f);
        send_datagram(sink, header, message.fragments[f]);
      }
    }
    if (any) {
      ++sink.cycles;
      if (flags & kFlagLate) ++sink.late_cycles;
    }
  }
}

void Streamer::Impl::send_end(Sink& sink) {
  Header header;
  header.type = MessageType::end_of_stream;
  header.sequence = sink.sequence;
  header.message_number = sink.message_number;
  const Bytes payload = encode_end_of_stream({sink.sequence, sink.message_number, sink.cycles, sink.late_cycles});
  ++sink.sequence;
  ++sink.message_number;
  send_datagram(sink, header, payload);
}

void Streamer::Impl::finish() {
  for (Sink& sink : sinks) send_end(sink);
  if (options.hold_at_end && control) {
    finished = true;
    return;
  }
  stopping = true;
  io.stop();
}

void Streamer::Impl::do_stop() {
  if (stopping) return;
  if (!finished) {
    for (Sink& sink : sinks) send_end(sink);
  }
  stopping = true;
  io.stop();
}

void Streamer::Impl::receive_control() {
  control->async_receive_from(asio::buffer(control_buffer), control_sender,
                              [this](const boost::system::error_code& ec, std::size_t bytes) {
                                if (ec == asio::error::operation_aborted || stopping) return;
                                // Other errors (an ICMP report on a previous send) concern no
                                // datagram: receive on.
                                if (!ec) handle_control({control_buffer.data(), bytes}, control_sender);
                                receive_control();
                              });
}

void Streamer::Impl::handle_control(std::span<const std::uint8_t> datagram, const udp::endpoint& sender) {
  ++summary.control_received;
  ControlRequest request;
  const DecodeError error = decode_control_request(datagram, request);
  if (error != DecodeError::none) {
    // Never answered: a reply to garbage would make the streamer a reflector.
    ++summary.control_ignored;
    ++summary.ignored_by_reason[static_cast<std::size_t>(error)];
    return;
  }
  Sink* client = find_client(sender);
  if (client) client->last_heard = SteadyClock::now();
  ReplyResult result = ReplyResult::ok;
  const bool playback = request.header.type == MessageType::pause || request.header.type == MessageType::resume ||
                        request.header.type == MessageType::step || request.header.type == MessageType::seek;
  if (playback && !client) {
    result = ReplyResult::not_subscribed;
  } else if (playback && !client->controller) {
    result = ReplyResult::not_allowed;  // a watcher: it receives, it does not steer
  } else {
    switch (request.header.type) {
      case MessageType::subscribe: {
        const bool controller = may_steer(request.token);
        if (client) {
          client->messages = request.argument;
          client->sensor_mask = request.sensor_mask;
          client->controller = controller;
          break;
        }
        // A full table makes room for a controller: the watcher subscribed longest ago goes.
        if (client_count() >= options.max_clients && controller) evict_oldest_watcher();
        if (client_count() >= options.max_clients) {
          result = ReplyResult::refused_full;
        } else {
          Sink sink;
          sink.endpoint = sender;
          sink.socket = &*control;
          sink.messages = request.argument;
          sink.sensor_mask = request.sensor_mask;
          sink.client = true;
          sink.controller = controller;
          sink.last_heard = SteadyClock::now();
          sinks.push_back(sink);
          summary.clients_peak = std::max<std::uint64_t>(summary.clients_peak, client_count());
          log << "rcsim stream: client " << to_string(sender) << " subscribed"
              << (controller ? ", may steer\n" : ", watching\n");
        }
        break;
      }
      case MessageType::unsubscribe:
        if (!client) {
          result = ReplyResult::not_subscribed;
          break;
        }
        send_end(*client);
        sinks.erase(sinks.begin() + (client - sinks.data()));
        client = nullptr;
        log << "rcsim stream: client " << to_string(sender) << " unsubscribed\n";
        break;
      case MessageType::keepalive:
        if (!client) result = ReplyResult::not_subscribed;
        break;
      case MessageType::pause:
        pacer.pause();
        cancel_timer();
        break;
      case MessageType::resume:
        pacer.resume();
        break;
      case MessageType::step:
        if (!pacer.paused()) pacer.pause();
        cancel_timer();
        pacer.step(request.argument);
        break;
      case MessageType::seek:
        if (request.argument >= static_cast<std::uint32_t>(source.cycle_count())) result = ReplyResult::out_of_range;
        else seek(request.argument);
        break;
      default:
        break;
    }
  }
  if (result != ReplyResult::ok) ++summary.control_refused;
  reply(sender, request, result);
  if (result == ReplyResult::ok && request.header.type != MessageType::keepalive) pump();
}

bool Streamer::Impl::may_steer(const std::string& token) const {
  if (options.open_control) return true;
  if (options.control_token.empty() || token.size() != options.control_token.size()) return false;
  // Compared in time independent of where the first difference is.
  unsigned char difference = 0;
  for (std::size_t i = 0; i < token.size(); ++i) {
    difference |= static_cast<unsigned char>(token[i] ^ options.control_token[i]);
  }
  return difference == 0;
}

void Streamer::Impl::evict_oldest_watcher() {
  // Sinks are kept in the order they subscribed in.
  const auto watcher = std::find_if(sinks.begin(), sinks.end(), [](const Sink& s) { return s.client && !s.controller; });
  if (watcher == sinks.end()) return;
  log << "rcsim stream: client " << to_string(watcher->endpoint) << " (watching) ended to make room for a controller\n";
  send_end(*watcher);
  sinks.erase(watcher);
  ++summary.watchers_evicted;
}

void Streamer::Impl::reply(const udp::endpoint& to, const ControlRequest& request, ReplyResult result) {
  ControlReply r;
  r.request_sequence = request.header.sequence;
  r.request_type = request.header.type;
  r.result = result;
  r.state = finished ? PlayState::finished : pacer.paused() ? PlayState::paused : PlayState::running;
  r.next_cycle = current ? current->cycle : next_cycle;
  r.cycle_count = static_cast<std::uint32_t>(source.cycle_count());
  r.subscribers = static_cast<std::uint32_t>(client_count());
  r.control_ignored = summary.control_ignored;
  Header header;  // replies are outside every stream: sequence and message number 0
  header.type = MessageType::control_reply;
  header.timestamp_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(SteadyClock::now().time_since_epoch()).count();
  const Bytes datagram = make_datagram(header, encode_control_reply(r));
  boost::system::error_code ignored;
  control->send_to(asio::buffer(datagram), to, 0, ignored);
}

void Streamer::Impl::seek(std::uint32_t cycle) {
  producer.seek(static_cast<int>(cycle));
  current.reset();
  next_cycle = cycle;
  finished = false;
  pacer.reanchor();
  cancel_timer();
  log << "rcsim stream: seek to cycle " << cycle << '\n';
}

void Streamer::Impl::housekeeping() {
  const TimePoint now = SteadyClock::now();
  const auto timeout = std::chrono::duration<double>(options.client_timeout_s);
  for (auto it = sinks.begin(); it != sinks.end();) {
    if (it->client && now - it->last_heard > timeout) {
      log << "rcsim stream: client " << to_string(it->endpoint) << " dropped (silent for more than "
          << options.client_timeout_s << " s)\n";
      ++summary.clients_timed_out;
      it = sinks.erase(it);
    } else {
      ++it;
    }
  }
  housekeeping_timer.expires_after(kHousekeepingPeriod);
  housekeeping_timer.async_wait([this](const boost::system::error_code& ec) {
    if (!ec && !stopping) housekeeping();
  });
}

Streamer::Streamer(CycleSource& source, const StreamOptions& options, std::ostream& log)
    : impl_(std::make_unique<Impl>(source, options, log)) {}

Streamer::~Streamer() = default;

std::uint16_t Streamer::control_port() const {
  return impl_->control ? impl_->control->local_endpoint().port() : std::uint16_t{0};
}

void Streamer::stop() {
  asio::post(impl_->io, [impl = impl_.get()] { impl->do_stop(); });
}

StreamSummary Streamer::run() {
  Impl& s = *impl_;
  const TimePoint wall_start = SteadyClock::now();
  const std::clock_t cpu_start = std::clock();
  if (s.options.first_cycle < 0 || s.options.first_cycle >= s.source.cycle_count()) {
    throw std::invalid_argument(fmt::format("first cycle {} is not in 0..{}", s.options.first_cycle, s.source.cycle_count() - 1));
  }
  s.next_cycle = static_cast<std::uint32_t>(s.options.first_cycle);
  s.producer.start(s.options.first_cycle);  // before the policy change: the producer keeps the normal one
  std::optional<std::pair<int, sched_param>> normal_policy;
  if (s.options.realtime_priority > 0) {
    int policy = 0;
    sched_param previous{};
    pthread_getschedparam(pthread_self(), &policy, &previous);
    sched_param realtime{};
    realtime.sched_priority = std::clamp(s.options.realtime_priority, 1, 99);
    if (const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &realtime); error != 0) {
      s.log << "rcsim stream: warning: no real-time priority for the sending thread (" << std::strerror(error)
            << "); streaming at the normal priority\n";
    } else {
      normal_policy.emplace(policy, previous);
    }
  }
  if (s.control) s.receive_control();
  s.housekeeping();
  if (s.options.handle_signals) {
    stop_on_signals(s.signals, [&s] {
      s.summary.interrupted = true;
      s.do_stop();
    });
  }
  s.post_pump();
  try {
    s.io.run();
  } catch (...) {
    // An error of the source (a recording's bad row, found when the stream reaches it): the
    // receivers hear the end of the stream, so that they end and keep what came before it.
    if (!s.finished && !s.stopping) {
      for (Sink& sink : s.sinks) s.send_end(sink);
    }
    if (normal_policy) pthread_setschedparam(pthread_self(), normal_policy->first, &normal_policy->second);
    throw;
  }
  if (normal_policy) pthread_setschedparam(pthread_self(), normal_policy->first, &normal_policy->second);
  s.producer.stop();
  StreamSummary summary = s.summary;
  summary.late_cycles = s.lateness.late();
  summary.paced_cycles = s.lateness.paced();
  summary.lateness_p50_ms = s.lateness.quantile_ms(0.5);
  summary.lateness_p99_ms = s.lateness.quantile_ms(0.99);
  summary.lateness_max_ms = s.lateness.max_ms();
  summary.wall_s = std::chrono::duration<double>(SteadyClock::now() - wall_start).count();
  summary.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return summary;
}

std::string StreamSummary::line() const {
  std::string text = fmt::format("rcsim stream: {}{} cycles, {} datagrams, {} bytes, {} late cycles", interrupted ? "stopped, " : "",
                                 cycles, datagrams, bytes, late_cycles);
  if (paced_cycles > 0) {
    text += fmt::format(" (send lateness p50 {:.3f} ms, p99 {:.3f} ms, max {:.3f} ms)", lateness_p50_ms, lateness_p99_ms,
                        lateness_max_ms);
  }
  text += fmt::format("; control: {} received, {} ignored, {} refused; clients: {} peak, {} timed out", control_received,
                      control_ignored, control_refused, clients_peak, clients_timed_out);
  if (watchers_evicted > 0) text += fmt::format(", {} watchers ended for a controller", watchers_evicted);
  if (send_errors > 0) text += fmt::format("; {} send errors", send_errors);
  text += fmt::format("; {:.2f} s, CPU {:.0f}%", wall_s, wall_s > 0.0 ? 100.0 * cpu_s / wall_s : 0.0);
  return text;
}

double parse_speed(const std::string& text) {
  if (text == "max") return 0.0;
  std::size_t used = 0;
  double speed = 0.0;
  try {
    speed = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(speed) || speed <= 0.0 || speed > 1e6) {
    throw std::invalid_argument("--speed '" + text + "': expected a positive number (1 real time, 10 ten times) or 'max'");
  }
  return speed;
}

std::uint32_t parse_message_mask(const std::string& text) {
  std::uint32_t mask = 0;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item == "simulated") mask |= kSimulatedBit;
    else if (item == "recorded") mask |= kRecordedBit;
    else if (item == "truth") mask |= kTruthBit;
    else throw std::invalid_argument("message type '" + item + "': expected simulated, recorded or truth");
  }
  if (mask == 0) throw std::invalid_argument("no message type selected");
  return mask;
}

}  // namespace rcsim::stream
