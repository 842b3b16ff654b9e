#pragma once
// rcsim stream: paced UDP playback of a cycle source (schemas/udp-stream.md, docs/stream.md).
//
// One thread runs a Boost.Asio loop that sends frames at their deadlines (pacing.hpp), serves
// the control port and watches the clients; a producer thread simulates ahead (frame_producer.hpp).
// Every destination and every subscribed client is its own stream with its own sequence and
// message numbers, receiving the message types (and sensors) it asked for. Playback (pause,
// resume, step, seek) is one timeline shared by all: the streamer plays one scene like one car
// on one bus, and every client sees the same cycles.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "stream/cycle_source.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::stream {

struct StreamOptions {
  std::vector<std::string> destinations;  // HOST:PORT, unicast or multicast
  std::uint32_t destination_messages = kSimulatedBit;
  std::string control;  // [HOST:]PORT of the control port, empty for none; HOST defaults to 127.0.0.1
  double speed = 1.0;   // 0 = max
  bool stepped = false;  // start paused: cycles leave on STEP (RESUME switches to paced playback)
  int wait_clients = 0;  // hold the first cycle until this many clients have subscribed
  int first_cycle = 0;
  double client_timeout_s = 5.0;
  std::size_t max_clients = 16;
  // Who may steer playback (pause, resume, step, seek): a client whose subscribe request presents
  // this token (is_control_token), or with open_control every client. Others only watch, and
  // a controller finding the clients full ends the stream of the watcher subscribed longest ago.
  std::string control_token;
  bool open_control = false;
  std::chrono::nanoseconds late_tolerance{std::chrono::milliseconds(2)};
  int multicast_ttl = 1;
  std::string multicast_interface;  // IPv4 address of the outgoing interface, empty = default
  bool hold_at_end = false;  // after the last cycle, keep serving the control port (seek back)
  bool handle_signals = false;  // SIGINT/SIGTERM stop the stream cleanly
  std::size_t queue_cycles = 64;
  // > 0: the sending thread runs under SCHED_FIFO at this priority (1..99) while it streams, so
  // that busy CPUs do not delay its wake-ups (needs CAP_SYS_NICE; without, a warning and on).
  // The simulation thread keeps the normal policy.
  int realtime_priority = 0;
};

struct StreamSummary {
  std::uint64_t cycles = 0, datagrams = 0, bytes = 0, late_cycles = 0, paced_cycles = 0;
  double lateness_p50_ms = 0.0, lateness_p99_ms = 0.0, lateness_max_ms = 0.0;
  std::uint64_t control_received = 0, control_ignored = 0, control_refused = 0;
  std::array<std::uint64_t, kDecodeErrorCount> ignored_by_reason{};
  std::uint64_t clients_peak = 0, clients_timed_out = 0, send_errors = 0, watchers_evicted = 0;
  double wall_s = 0.0, cpu_s = 0.0;
  bool interrupted = false;
  // The one line printed at the end.
  std::string line() const;
};

class Streamer {
 public:
  Streamer(CycleSource& source, const StreamOptions& options, std::ostream& log);
  ~Streamer();
  Streamer(const Streamer&) = delete;
  Streamer& operator=(const Streamer&) = delete;

  // The bound control port (0 without one); valid after construction.
  std::uint16_t control_port() const;
  // Plays until the end (or stop()); the summary of what was sent.
  StreamSummary run();
  // Thread-safe: ends the stream cleanly (END to every stream), as SIGINT does.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "1", "10", "0.5", or "max" (0).
double parse_speed(const std::string& text);
// "simulated,recorded,truth" → a message mask.
std::uint32_t parse_message_mask(const std::string& text);

}  // namespace rcsim::stream
