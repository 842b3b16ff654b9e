// The stream under hostile load (issue 21), on loopback: 100,000 malformed datagrams flood a
// listener before and while a stream reaches it, and 100,000 control requests with absurd values
// flood the streamer's control port while it streams. Nothing is fatal: the stream goes on, the
// capture is complete (identical to rcsim simulate's rows), and every hostile datagram is counted.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <fstream>
#include <future>
#include <sstream>
#include <random>
#include <thread>
#include <vector>

#include "stream/listener.hpp"
#include "stream/sender_table.hpp"
#include "stream/streamer.hpp"
#include "app/stream/stream_test_support.hpp"
#include "test_support.hpp"

namespace rcsim::stream {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

constexpr int kFlood = 100'000;

Scene flood_scene() {
  Scene scene = rcsim::testing::single_sensor_scene(3.0);
  rcsim::testing::add_object(scene, "car", "passenger_car", {rcsim::testing::sample(0.0, 20.0, 0.5, 3.14159, 3.0)});
  return scene;
}

void put_u32(Bytes& d, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) d[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Datagrams every reader must refuse (schemas/udp-stream.md, Refusals), in eight kinds.
std::vector<Bytes> malformed_datagrams(std::size_t kinds_each) {
  std::mt19937 rng(21);
  TargetListMessage m;
  m.sensor_id = "front";
  m.targets.resize(2);
  const Bytes valid = encode_target_list(m).front();
  std::vector<Bytes> out;
  for (std::size_t i = 0; i < kinds_each; ++i) {
    Bytes random(1 + rng() % 1400);
    for (auto& x : random) x = static_cast<std::uint8_t>(rng());
    random[0] = 'X';  // never the magic
    out.push_back(random);
    Bytes version = valid;
    version[4] = 9;  // right magic, unknown version
    out.push_back(version);
    out.push_back(Bytes(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(1 + rng() % (kHeaderBytes - 1))));
    Bytes truncated = valid;  // a target list cut inside its targets
    truncated.resize(valid.size() - 1 - rng() % 30);
    out.push_back(truncated);
    Bytes huge_total = valid;  // total_count 0xFFFFFFFF: what once ended a capture with bad_alloc
    put_u32(huge_total, kHeaderBytes + 8, 0xFFFFFFFFu);
    out.push_back(huge_total);
    Bytes huge_count = valid;  // count 0xFFFF beside 2 targets
    huge_count[kHeaderBytes + 16] = 0xFF;
    huge_count[kHeaderBytes + 17] = 0xFF;
    out.push_back(huge_count);
    Bytes bad_fragment = valid;  // fragment 7 of 1
    bad_fragment[28] = 7;
    out.push_back(bad_fragment);
    Bytes oversized(kMaxDatagramBytes + 1 + rng() % 2000, 0);  // beyond the largest datagram
    std::copy(valid.begin(), valid.begin() + kHeaderBytes, oversized.begin());
    out.push_back(oversized);
  }
  return out;
}

// Sends paced, `per_ms` datagrams a millisecond (a listener's socket buffer holds a few thousand;
// while a stream plays, the flood must leave it room, also under the sanitizers).
void flood(const std::vector<Bytes>& datagrams, std::uint16_t port, std::size_t per_ms = 25) {
  asio::io_context io;
  udp::socket socket(io, udp::v4());
  const udp::endpoint to(asio::ip::make_address("127.0.0.1"), port);
  for (std::size_t i = 0; i < datagrams.size(); ++i) {
    socket.send_to(asio::buffer(datagrams[i]), to);
    if (i % per_ms == per_ms - 1) std::this_thread::sleep_for(1ms);
  }
}

// The row of /proc/net/udp for the socket bound to 127.0.0.1:port, split into its columns
// (sl, local_address, rem_address, st, tx_queue:rx_queue, ..., drops); empty if there is none.
std::vector<std::string> udp_socket_row(std::uint16_t port) {
  std::ifstream table("/proc/net/udp");
  const std::string local = fmt::format("0100007F:{:04X}", port);
  std::string line;
  std::getline(table, line);  // header
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    std::vector<std::string> row;
    for (std::string token; fields >> token;) row.push_back(token);
    if (row.size() > 4 && row[1] == local) return row;
  }
  return {};
}

// What the kernel dropped for the socket because its buffer was full (the last column):
// datagrams the listener never saw and so cannot count.
std::uint64_t kernel_drops(std::uint16_t port) {
  const auto row = udp_socket_row(port);
  return row.empty() ? 0 : std::stoull(row.back());
}

// Waits until the socket's receive queue is empty (rx_queue, hex bytes), at most 20 s: the
// listener has then taken every datagram the kernel kept, however slow a loaded machine made it.
void wait_until_drained(std::uint16_t port) {
  for (int i = 0; i < 2000; ++i) {
    const auto row = udp_socket_row(port);
    if (row.empty() || std::stoull(row[4].substr(row[4].find(':') + 1), nullptr, 16) == 0) return;
    std::this_thread::sleep_for(10ms);
  }
}

TEST(HostileLoad, AListenerFloodedWithAHundredThousandMalformedDatagramsKeepsTheStreamAndCountsThemAll) {
  const Scene scene = flood_scene();
  SourceOptions source_options;
  source_options.simulation.seed = 8;
  ListenOptions listen;  // passive, on a free port; ends when stopped, after the kernel's count is read
  listen.stop_at_end = false;
  std::ostringstream out, log;
  Listener listener(listen, out, log);
  auto listened = std::async(std::launch::async, [&] { return listener.run(); });
  const std::vector<Bytes> garbage = malformed_datagrams(kFlood / 8);
  ASSERT_EQ(garbage.size(), static_cast<std::size_t>(kFlood));
  // Half before the stream, half while it plays.
  flood(std::vector<Bytes>(garbage.begin(), garbage.begin() + kFlood / 2), listener.port());
  auto source = make_scene_source(scene, source_options);
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", listener.port())};
  options.speed = testing::kLosslessSpeed / 4;  // 0.75 s of stream, under the second half's flood
  std::ostringstream stream_log;
  Streamer streamer(*source, options, stream_log);
  auto streamed = std::async(std::launch::async, [&] { return streamer.run(); });
  flood(std::vector<Bytes>(garbage.begin() + kFlood / 2, garbage.end()), listener.port(), 8);
  const StreamSummary sent = streamed.get();
  wait_until_drained(listener.port());  // the listener has taken what the kernel kept
  const std::uint64_t dropped = kernel_drops(listener.port());
  listener.stop();
  const ListenSummary s = listened.get();
  EXPECT_EQ(out.str(), testing::simulate_rows(scene, source_options.simulation)) << "the capture is complete";
  EXPECT_TRUE(s.end_received);
  // Every hostile datagram is counted: by the listener, or by the kernel when the flood outran it.
  EXPECT_EQ(s.malformed + dropped, static_cast<std::uint64_t>(kFlood)) << log.str();
  EXPECT_GT(s.malformed, static_cast<std::uint64_t>(kFlood / 2));
  std::uint64_t by_reason = 0;
  for (const auto n : s.malformed_by_reason) by_reason += n;
  EXPECT_EQ(by_reason, s.malformed);
  EXPECT_EQ(s.datagrams + dropped, static_cast<std::uint64_t>(kFlood) + sent.datagrams);
  std::cout << "[ figures  ] " << kFlood << " malformed datagrams: " << s.malformed << " counted by the listener, "
            << dropped << " dropped by the kernel (socket buffer full); the stream's " << sent.datagrams
            << " datagrams all arrived\n";
  EXPECT_EQ(s.target_lists, static_cast<std::uint64_t>(scene.cycle_count()));
}

// Half a message (fragment 0 of 2, a full datagram) from each of `senders` source ports, one
// fresh socket after the other (the kernel picks each port), paced `per_ms` a millisecond.
void flood_from_many_ports(std::uint16_t port, int senders, int per_ms) {
  asio::io_context io;
  const udp::endpoint to(asio::ip::make_address("127.0.0.1"), port);
  Header h;
  h.fragment_count = 2;
  const Bytes datagram = make_datagram(h, Bytes(kMaxDatagramBytes - kHeaderBytes, 0));
  for (int i = 0; i < senders; ++i) {
    udp::socket socket(io, udp::endpoint(udp::v4(), 0));
    socket.send_to(asio::buffer(datagram), to);
    if (i % per_ms == per_ms - 1) std::this_thread::sleep_for(1ms);
  }
}

TEST(HostileLoad, HalfMessagesFromThousandsOfSourcePortsKeepTheListenerBoundedAndTheStreamComplete) {
  constexpr int kPorts = 4000;
  const Scene scene = flood_scene();
  SourceOptions source_options;
  source_options.simulation.seed = 10;
  ListenOptions listen;
  listen.stop_at_end = false;
  std::ostringstream out, log;
  Listener listener(listen, out, log);
  auto listened = std::async(std::launch::async, [&] { return listener.run(); });
  flood_from_many_ports(listener.port(), kPorts / 2, 25);  // half before the stream, half while it plays
  auto source = make_scene_source(scene, source_options);
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", listener.port())};
  options.speed = testing::kLosslessSpeed / 4;
  std::ostringstream stream_log;
  Streamer streamer(*source, options, stream_log);
  auto streamed = std::async(std::launch::async, [&] { return streamer.run(); });
  flood_from_many_ports(listener.port(), kPorts / 2, 8);
  const StreamSummary sent = streamed.get();
  wait_until_drained(listener.port());
  const std::uint64_t dropped = kernel_drops(listener.port());
  listener.stop();
  const ListenSummary s = listened.get();
  EXPECT_EQ(out.str(), testing::simulate_rows(scene, source_options.simulation)) << "the capture is complete";
  EXPECT_TRUE(s.end_received);
  EXPECT_EQ(s.lost, 0u) << "the stream's sender, which delivers, was never forgotten";
  // Each hostile datagram is a fresh sender with half a message, or (a port the kernel handed out
  // again while still tracked) a duplicate; each half message is counted incomplete once.
  const std::uint64_t hostile = s.datagrams - sent.datagrams;
  EXPECT_EQ(hostile + dropped, static_cast<std::uint64_t>(kPorts));
  EXPECT_EQ(hostile, s.sources - 1 + s.duplicates);
  EXPECT_EQ(s.incomplete, s.sources - 1);
  EXPECT_EQ(s.malformed, 0u);
  using Table = SenderTable<udp::endpoint>;
  EXPECT_EQ(s.senders_peak, Table::kMaxSenders);
  EXPECT_EQ(s.senders_forgotten, s.sources - Table::kMaxSenders);
  EXPECT_LE(s.sender_state_peak_bytes, Table::kMaxSenders * 2 * kMaxDatagramBytes + (64u << 10));
  EXPECT_NE(s.line().find(fmt::format("{} senders forgotten", s.senders_forgotten)), std::string::npos) << s.line();
  std::cout << "[ figures  ] " << kPorts << " source ports with half a message each: " << s.sources << " senders heard, "
            << s.senders_forgotten << " forgotten, at most " << s.senders_peak << " tracked holding at most "
            << s.sender_state_peak_bytes << " bytes; " << dropped << " dropped by the kernel; the stream's "
            << sent.datagrams << " datagrams all arrived\n";
}

TEST(HostileLoad, AStreamerFloodedWithAbsurdControlRequestsStreamsOnUnchanged) {
  const Scene scene = flood_scene();
  SourceOptions source_options;
  source_options.simulation.seed = 9;
  ListenOptions listen;
  std::ostringstream out, log;
  Listener listener(listen, out, log);
  auto listened = std::async(std::launch::async, [&] { return listener.run(); });
  auto source = make_scene_source(scene, source_options);
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", listener.port())};
  options.control = "127.0.0.1:0";
  options.speed = testing::kLosslessSpeed / 4;
  std::ostringstream stream_log;
  Streamer streamer(*source, options, stream_log);
  const std::uint16_t control = streamer.control_port();
  // Absurd values from a stranger: seek far beyond the end, step 2^32 - 1, pause/resume without a
  // subscription, subscribe to every message and sensor bit, unknown types.
  std::vector<Bytes> requests;
  std::mt19937 rng(22);
  for (int i = 0; i < kFlood; ++i) {
    Header h;
    h.sequence = static_cast<std::uint64_t>(i);
    switch (i % 5) {
      case 0: h.type = MessageType::seek; requests.push_back(make_datagram(h, encode_control_payload(h.type, 0xFFFFFFFFu, 0))); break;
      case 1: h.type = MessageType::step; requests.push_back(make_datagram(h, encode_control_payload(h.type, 0xFFFFFFFFu, 0))); break;
      case 2: h.type = MessageType::pause; requests.push_back(make_datagram(h, encode_control_payload(h.type, 0, 0))); break;
      case 3: h.type = MessageType::resume; requests.push_back(make_datagram(h, encode_control_payload(h.type, 0, 0))); break;
      default: {
        Bytes d = make_datagram(h, encode_control_payload(MessageType::pause, static_cast<std::uint32_t>(rng()), static_cast<std::uint32_t>(rng())));
        d[5] = static_cast<std::uint8_t>(0x40 + rng() % 0x30);  // a type nobody defined
        requests.push_back(std::move(d));
      }
    }
  }
  auto streamed = std::async(std::launch::async, [&] { return streamer.run(); });
  flood(requests, control);
  const StreamSummary summary = streamed.get();
  listened.get();
  EXPECT_EQ(out.str(), testing::simulate_rows(scene, source_options.simulation)) << "the stream went on unchanged";
  EXPECT_EQ(summary.cycles, static_cast<std::uint64_t>(scene.cycle_count()));
  EXPECT_GT(summary.control_received + summary.control_ignored, 0u);
  EXPECT_LE(summary.control_received + summary.control_ignored, static_cast<std::uint64_t>(kFlood));
  EXPECT_EQ(summary.clients_peak, 0u) << "no stranger became a client";
}

}  // namespace
}  // namespace rcsim::stream
