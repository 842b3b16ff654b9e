// The streamer and the listener together on loopback, in this process: complete streams to two
// subscribed clients, garbage on the control port, step/seek/resume, client timeout, recordings,
// fragmented cycles.
#include "stream/streamer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>

#include <boost/asio/io_context.hpp>
#include <fstream>
#include <future>
#include <random>
#include <optional>
#include <set>
#include <thread>

#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "stream/endpoints.hpp"
#include "stream/listener.hpp"
#include "stream/reassembly.hpp"
#include "app/stream/stream_test_support.hpp"
#include "test_support.hpp"

namespace rcsim::stream {
namespace {

namespace asio = boost::asio;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

constexpr std::string_view kToken = "0123456789abcdef-token";

// A stream that starts paused, at full speed when resumed, steered by whoever holds kToken.
StreamOptions stepped_with_token() {
  StreamOptions options;
  options.control = "127.0.0.1:0";
  options.speed = 0.0;
  options.stepped = true;
  options.control_token = kToken;
  return options;
}

Scene two_sensor_scene(double duration_s) {
  Scene scene = rcsim::testing::single_sensor_scene(duration_s);
  scene.sensors.front().id = "front_left";
  scene.sensors.front().X_VS = {3.7, 0.7, 0.5};
  MountedSensor right = scene.sensors.front();
  right.id = "front_right";
  right.X_VS = {3.7, -0.7, -0.5};
  scene.sensors.push_back(right);
  rcsim::testing::add_object(scene, "left", "passenger_car", {rcsim::testing::sample(0.0, 25.0, 1.6, 3.14159, 4.0)});
  rcsim::testing::add_object(scene, "right", "passenger_car", {rcsim::testing::sample(0.0, 25.0, -1.6, 3.14159, 4.0)});
  return scene;
}

// Runs a listener on its own thread; output and summary come back through the future.
struct ListenerRun {
  explicit ListenerRun(const ListenOptions& options) : listener(options, out, log) {
    result = std::async(std::launch::async, [this] { return listener.run(); });
  }
  ListenSummary get() { return result.get(); }
  std::ostringstream out, log;
  Listener listener;
  std::future<ListenSummary> result;
};

struct StreamerRun {
  StreamerRun(CycleSource& source, const StreamOptions& options) : streamer(source, options, log) {
    result = std::async(std::launch::async, [this] { return streamer.run(); });
  }
  StreamSummary get() { return result.get(); }
  std::ostringstream log;
  Streamer streamer;
  std::future<StreamSummary> result;
};

// A bare control client: sends requests and reads what comes back, with a timeout.
class ControlClient {
 public:
  explicit ControlClient(std::uint16_t port) : socket_(io_, udp::v4()), control_(asio::ip::make_address("127.0.0.1"), port) {
    socket_.bind(udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  }
  void send(MessageType type, std::uint32_t argument = 0, std::string_view token = {}) {
    Header h;
    h.type = type;
    h.sequence = sequence_++;
    const Bytes d = make_datagram(h, encode_control_payload(type, argument, 0, token));
    socket_.send_to(asio::buffer(d), control_);
  }
  std::uint16_t port() const { return socket_.local_endpoint().port(); }
  void send_raw(const Bytes& d) { socket_.send_to(asio::buffer(d), control_); }
  // The next datagram, or nothing after the timeout.
  std::optional<Bytes> receive(std::chrono::milliseconds timeout = 5s) {
    pollfd p{socket_.native_handle(), POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
    Bytes d(65536);
    udp::endpoint from;
    d.resize(socket_.receive_from(asio::buffer(d), from));
    return d;
  }
  // Reads until the reply to the last request.
  ControlReply reply() {
    while (auto d = receive()) {
      const HeaderResult h = decode_header(*d);
      if (h.error == DecodeError::none && h.header.type == MessageType::control_reply) {
        ControlReply r;
        EXPECT_EQ(decode_control_reply(std::span<const std::uint8_t>(*d).subspan(kHeaderBytes), r), DecodeError::none);
        return r;
      }
      data_.push_back(std::move(*d));
    }
    ADD_FAILURE() << "no reply";
    return {};
  }
  // Target-list cycles received (data datagrams), reading until `count` of them or a timeout.
  std::vector<std::uint32_t> cycles(std::size_t count, std::chrono::milliseconds timeout = 5s) {
    std::vector<std::uint32_t> out;
    const auto take = [&out](const Bytes& d) {
      const HeaderResult h = decode_header(d);
      if (h.error != DecodeError::none || h.header.type != MessageType::simulated_targets) return;
      TargetListFragment f;
      if (decode_target_list(std::span<const std::uint8_t>(d).subspan(kHeaderBytes), f) == DecodeError::none) {
        out.push_back(f.message.cycle);
      }
    };
    for (const Bytes& d : data_) take(d);
    data_.clear();
    while (out.size() < count) {
      auto d = receive(timeout);
      if (!d) break;
      take(*d);
    }
    return out;
  }

 private:
  asio::io_context io_;
  udp::socket socket_;
  udp::endpoint control_;
  std::uint64_t sequence_ = 0;
  std::vector<Bytes> data_;
};

TEST(StreamLoopback, TwoSubscribedClientsBothGetTheCompleteStream) {
  const Scene scene = two_sensor_scene(2.0);
  SourceOptions source_options;
  source_options.simulation.seed = 3;
  auto source = make_scene_source(scene, source_options);
  StreamOptions options;
  options.control = "127.0.0.1:0";
  options.speed = testing::kLosslessSpeed;
  options.wait_clients = 2;
  StreamerRun streamer(*source, options);
  ListenOptions listen;
  listen.subscribe = fmt::format("127.0.0.1:{}", streamer.streamer.control_port());
  ListenerRun a(listen), b(listen);
  const ListenSummary sa = a.get(), sb = b.get();
  const StreamSummary summary = streamer.get();
  const std::string expected = testing::simulate_rows(scene, source_options.simulation);
  EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 50);
  EXPECT_EQ(a.out.str(), expected);
  EXPECT_EQ(b.out.str(), expected);
  for (const ListenSummary& s : {sa, sb}) {
    EXPECT_TRUE(s.end_received);
    EXPECT_EQ(s.lost, 0u);
    EXPECT_EQ(s.duplicates, 0u);
    EXPECT_EQ(s.malformed, 0u);
    EXPECT_EQ(s.target_lists, 2u * static_cast<std::uint64_t>(scene.cycle_count()));
    EXPECT_EQ(s.end.cycles_sent, static_cast<std::uint32_t>(scene.cycle_count()));
  }
  EXPECT_EQ(summary.cycles, static_cast<std::uint64_t>(scene.cycle_count()));
  EXPECT_EQ(summary.clients_peak, 2u);
}

TEST(StreamLoopback, GarbageOnTheControlPortChangesNothingInTheStream) {
  const Scene scene = two_sensor_scene(2.0);
  SourceOptions source_options;
  source_options.simulation.seed = 4;
  auto source = make_scene_source(scene, source_options);
  StreamOptions options;
  options.control = "127.0.0.1:0";
  options.speed = testing::kLosslessSpeed;
  options.wait_clients = 1;
  StreamerRun streamer(*source, options);
  const std::uint16_t port = streamer.streamer.control_port();

  // Hostile datagrams: random bytes, oversized, right magic with a wrong version, truncated
  // requests, a subscribe with an impossible mask, data messages sent to the control port.
  std::mt19937 rng(5);
  std::vector<Bytes> garbage;
  for (int i = 0; i < 200; ++i) {
    Bytes d(rng() % 3000);
    for (auto& x : d) x = static_cast<std::uint8_t>(rng());
    if (i % 5 == 1 && d.size() > 8) std::copy(kMagic.begin(), kMagic.end(), d.begin()), d[4] = 9;
    if (i % 5 == 2) {
      Header h;
      h.type = MessageType::subscribe;
      d = make_datagram(h, encode_control_payload(MessageType::subscribe, 0xFF, 0));
    }
    if (i % 5 == 3) {
      Header h;
      h.type = MessageType::seek;
      d = make_datagram(h, {});  // seek without its cycle
    }
    if (i % 5 == 4) {
      Header h;
      TargetListMessage m;
      m.sensor_id = "x";
      d = make_datagram(h, encode_target_list(m)[0]);
    }
    if (d.size() >= kHeaderBytes && d.size() <= kMaxDatagramBytes && d[0] == 'R' && d[1] == 'C' && d[2] == 'S' && d[3] == 'M' &&
        d[4] == 1 && i % 5 == 0)
      d[0] = 'X';
    garbage.push_back(std::move(d));
  }
  ControlClient attacker(port);
  for (std::size_t i = 0; i < garbage.size() / 2; ++i) attacker.send_raw(garbage[i]);
  ListenOptions listen;
  listen.subscribe = fmt::format("127.0.0.1:{}", port);
  ListenerRun client(listen);
  for (std::size_t i = garbage.size() / 2; i < garbage.size(); ++i) attacker.send_raw(garbage[i]);
  const ListenSummary s = client.get();
  const StreamSummary summary = streamer.get();
  EXPECT_EQ(client.out.str(), testing::simulate_rows(scene, source_options.simulation));
  EXPECT_EQ(s.lost, 0u);
  EXPECT_TRUE(s.end_received);
  // Every hostile datagram that reached the socket was ignored and counted, none answered.
  EXPECT_GT(summary.control_ignored, 0u);
  EXPECT_LE(summary.control_ignored, garbage.size());
  EXPECT_EQ(summary.control_refused, 0u);
  EXPECT_EQ(summary.clients_peak, 1u);
  std::uint64_t by_reason = 0;
  for (auto n : summary.ignored_by_reason) by_reason += n;
  EXPECT_EQ(by_reason, summary.control_ignored);
  EXPECT_FALSE(attacker.receive(100ms)) << "garbage must never be answered";
}

TEST(StreamLoopback, StepSeekAndResumeFromAClient) {
  const Scene scene = two_sensor_scene(1.0);
  const int n = scene.cycle_count();
  SourceOptions source_options;
  auto source = make_scene_source(scene, source_options);
  StreamerRun streamer(*source, stepped_with_token());
  ControlClient client(streamer.streamer.control_port());
  client.send(MessageType::pause);
  EXPECT_EQ(client.reply().result, ReplyResult::not_subscribed);  // only subscribers steer
  client.send(MessageType::subscribe, kSimulatedBit, kToken);
  EXPECT_EQ(client.reply().result, ReplyResult::ok);
  client.send(MessageType::step, 3);
  client.reply();
  EXPECT_EQ(client.cycles(6), (std::vector<std::uint32_t>{0, 0, 1, 1, 2, 2}));
  EXPECT_TRUE(client.cycles(1, 200ms).empty()) << "nothing leaves without a step";
  client.send(MessageType::seek, static_cast<std::uint32_t>(n));
  EXPECT_EQ(client.reply().result, ReplyResult::out_of_range);
  client.send(MessageType::seek, 10);
  EXPECT_EQ(client.reply().result, ReplyResult::ok);
  client.send(MessageType::step, 1);
  const ControlReply r = client.reply();
  EXPECT_EQ(r.state, PlayState::paused);
  EXPECT_EQ(client.cycles(2), (std::vector<std::uint32_t>{10, 10}));
  client.send(MessageType::resume);
  client.reply();
  const auto rest = client.cycles(static_cast<std::size_t>(2 * (n - 11)));
  ASSERT_EQ(rest.size(), static_cast<std::size_t>(2 * (n - 11)));
  EXPECT_EQ(rest.front(), 11u);
  EXPECT_EQ(rest.back(), static_cast<std::uint32_t>(n - 1));
  const StreamSummary summary = streamer.get();
  EXPECT_EQ(summary.cycles, static_cast<std::uint64_t>(3 + 1 + n - 11));
}

TEST(StreamLoopback, WatchersCannotSteerAndAControllerTakesTheOldestWatchersPlace) {
  const Scene scene = two_sensor_scene(1.0);
  auto source = make_scene_source(scene, {});
  StreamOptions options = stepped_with_token();
  options.max_clients = 2;
  StreamerRun streamer(*source, options);
  const std::uint16_t port = streamer.streamer.control_port();
  ControlClient first(port), second(port), stranger(port), operator_client(port);
  first.send(MessageType::subscribe, kSimulatedBit);
  EXPECT_EQ(first.reply().result, ReplyResult::ok);
  second.send(MessageType::subscribe, kSimulatedBit, "a-wrong-token-of-20b");
  EXPECT_EQ(second.reply().result, ReplyResult::ok);  // a wrong token subscribes as a watcher
  for (const MessageType steer : {MessageType::pause, MessageType::resume, MessageType::step, MessageType::seek}) {
    for (ControlClient* watcher : {&first, &second}) {
      watcher->send(steer, 1);
      EXPECT_EQ(watcher->reply().result, ReplyResult::not_allowed) << message_type_name(steer);
    }
  }
  EXPECT_TRUE(first.cycles(1, 200ms).empty()) << "a watcher's step let a cycle out";
  stranger.send(MessageType::subscribe, kSimulatedBit);
  EXPECT_EQ(stranger.reply().result, ReplyResult::refused_full);
  // The operator gets in although two watchers fill the table: the first one goes.
  operator_client.send(MessageType::subscribe, kSimulatedBit, kToken);
  const ControlReply in = operator_client.reply();
  EXPECT_EQ(in.result, ReplyResult::ok);
  EXPECT_EQ(in.subscribers, 2u);
  operator_client.send(MessageType::step, 2);
  EXPECT_EQ(operator_client.reply().result, ReplyResult::ok);
  EXPECT_EQ(operator_client.cycles(4), (std::vector<std::uint32_t>{0, 0, 1, 1}));
  EXPECT_EQ(second.cycles(4), (std::vector<std::uint32_t>{0, 0, 1, 1}));
  first.send(MessageType::keepalive);
  EXPECT_EQ(first.reply().result, ReplyResult::not_subscribed) << "the evicted watcher still had a stream";
  streamer.streamer.stop();
  const StreamSummary summary = streamer.get();
  EXPECT_EQ(summary.watchers_evicted, 1u);
  EXPECT_EQ(summary.cycles, 2u);
}

TEST(StreamLoopback, WithoutATokenNobodySteersUnlessTheControlIsOpen) {
  const Scene scene = two_sensor_scene(1.0);
  for (const bool open : {false, true}) {
    auto source = make_scene_source(scene, {});
    StreamOptions options;
    options.control = "127.0.0.1:0";
    options.speed = 0.0;
    options.stepped = true;
    options.open_control = open;
    StreamerRun streamer(*source, options);
    ControlClient client(streamer.streamer.control_port());
    client.send(MessageType::subscribe, kSimulatedBit, kToken);  // a token the streamer does not have
    EXPECT_EQ(client.reply().result, ReplyResult::ok);
    client.send(MessageType::step, 1);
    EXPECT_EQ(client.reply().result, open ? ReplyResult::ok : ReplyResult::not_allowed);
    EXPECT_EQ(client.cycles(2, open ? 5000ms : 200ms).size(), open ? 2u : 0u);  // both sensors' lists of cycle 0
    streamer.streamer.stop();
    EXPECT_EQ(streamer.get().cycles, open ? 1u : 0u);
  }
}

TEST(StreamLoopback, AListenerCountsTheCyclesASeekSendsAgain) {
  const Scene scene = two_sensor_scene(1.0);
  auto source = make_scene_source(scene, {});
  StreamerRun streamer(*source, stepped_with_token());
  const std::uint16_t port = streamer.streamer.control_port();
  ControlClient controller(port);
  controller.send(MessageType::subscribe, kSimulatedBit, kToken);
  controller.reply();
  ListenOptions listen;
  listen.subscribe = fmt::format("127.0.0.1:{}", port);
  ListenerRun watcher(listen);
  // The watcher is in once the streamer counts two subscribers.
  for (int i = 0; i < 100; ++i) {
    controller.send(MessageType::keepalive);
    if (controller.reply().subscribers == 2) break;
    std::this_thread::sleep_for(20ms);
  }
  controller.send(MessageType::step, 3);  // cycles 0, 1, 2
  controller.reply();
  EXPECT_EQ(controller.cycles(6).size(), 6u);
  controller.send(MessageType::seek, 1);
  controller.reply();
  controller.send(MessageType::resume);  // 1 again, 2 again, then on to the end
  controller.reply();
  const ListenSummary s = watcher.get();
  streamer.get();
  EXPECT_TRUE(s.end_received);
  EXPECT_EQ(s.rewinds, 2u);           // 2 -> 1, for each of the two sensors
  EXPECT_EQ(s.cycles_repeated, 0u);
  EXPECT_EQ(s.duplicates, 0u);        // the datagrams themselves are new: only the cycles repeat
  EXPECT_NE(s.line().find("2 rewinds"), std::string::npos) << s.line();
}

TEST(StreamLoopback, AForgedControlReplyNeitherEndsNorSteersAListener) {
  const Scene scene = two_sensor_scene(1.0);
  SourceOptions source_options;
  source_options.simulation.seed = 2;
  for (const bool subscribed : {false, true}) {
    auto source = make_scene_source(scene, source_options);
    ListenOptions listen;
    std::optional<StreamerRun> streamer;
    StreamOptions options;
    options.speed = testing::kLosslessSpeed;
    if (subscribed) {
      options.control = "127.0.0.1:0";
      options.wait_clients = 1;
      streamer.emplace(*source, options);
      listen.subscribe = fmt::format("127.0.0.1:{}", streamer->streamer.control_port());
    }
    ListenerRun listener(listen);
    // "Refused: the streamer has all the clients it takes", from a socket that is not the streamer.
    ControlReply forged;
    forged.request_type = MessageType::subscribe;
    forged.result = ReplyResult::refused_full;
    Header h;
    h.type = MessageType::control_reply;
    ControlClient stranger(listener.listener.port());
    stranger.send_raw(make_datagram(h, encode_control_reply(forged)));
    if (!subscribed) {
      options.destinations = {fmt::format("127.0.0.1:{}", listener.listener.port())};
      std::this_thread::sleep_for(100ms);  // the forged reply arrives first
      streamer.emplace(*source, options);
    }
    const ListenSummary s = listener.get();
    streamer->get();
    EXPECT_TRUE(s.end_received) << (subscribed ? "subscribed" : "passive");
    EXPECT_EQ(s.stray_replies, 1u);
    EXPECT_EQ(listener.out.str(), testing::simulate_rows(scene, source_options.simulation));
  }
}

TEST(StreamLoopback, SeekingBackReplaysIdenticalCycles) {
  const Scene scene = two_sensor_scene(1.0);
  SourceOptions source_options;
  source_options.simulation.seed = 9;
  auto source = make_scene_source(scene, source_options);
  auto first = source->produce();
  for (int k = 1; k < 12; ++k) source->produce();
  const CycleFrame twelve = source->produce();
  source->seek(0);  // back: the simulation restarts, tracker state and random draws included
  const CycleFrame again = source->produce();
  source->seek(12);  // forward: the cycles between are simulated, not encoded
  const CycleFrame twelve_again = source->produce();
  ASSERT_EQ(first.messages.size(), again.messages.size());
  for (std::size_t i = 0; i < first.messages.size(); ++i) EXPECT_EQ(first.messages[i].fragments, again.messages[i].fragments);
  for (std::size_t i = 0; i < twelve.messages.size(); ++i) EXPECT_EQ(twelve.messages[i].fragments, twelve_again.messages[i].fragments);
  EXPECT_EQ(twelve_again.cycle, 12u);
}

TEST(StreamLoopback, AClientThatFallsSilentIsDropped) {
  const Scene scene = two_sensor_scene(1.0);
  auto source = make_scene_source(scene, {});
  StreamOptions options;
  options.control = "127.0.0.1:0";
  options.stepped = true;
  options.client_timeout_s = 0.2;
  StreamerRun streamer(*source, options);
  ControlClient silent(streamer.streamer.control_port());
  silent.send(MessageType::subscribe, kSimulatedBit);
  ASSERT_EQ(silent.reply().subscribers, 1u);
  // Another socket asks (KEEPALIVE from a non-subscriber: answered with the subscriber count).
  ControlClient probe(streamer.streamer.control_port());
  std::uint32_t subscribers = 1;
  for (int i = 0; i < 100 && subscribers != 0; ++i) {
    std::this_thread::sleep_for(100ms);
    probe.send(MessageType::keepalive);
    subscribers = probe.reply().subscribers;
  }
  EXPECT_EQ(subscribers, 0u);
  streamer.streamer.stop();
  const StreamSummary summary = streamer.get();
  EXPECT_EQ(summary.clients_timed_out, 1u);
  EXPECT_EQ(summary.cycles, 0u);
}

TEST(StreamLoopback, FragmentedCyclesReassembleEndToEnd) {
  // 60 poles 0.7 m apart in range along the boresight: many detections per cycle; with
  // datagrams limited to 400 bytes each list and each ground truth spans several fragments.
  Scene scene = rcsim::testing::single_sensor_scene(0.4);
  for (int i = 0; i < 60; ++i) {
    rcsim::testing::add_object(scene, fmt::format("pole{}", i), "pole",
                               {rcsim::testing::sample(0.0, 4.0 + 0.7 * i, 0.02 * (i % 7), 0.0, 0.0)});
  }
  SourceOptions source_options;
  source_options.simulation.level = ListLevel::detections;
  source_options.simulation.noise = false;
  source_options.max_datagram_bytes = 400;
  auto source = make_scene_source(scene, source_options);
  ListenOptions listen;
  listen.truth_output = (testing::temp_dir("fragments") / "truth.csv").string();
  ListenerRun client(listen);
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", client.listener.port())};
  options.destination_messages = kSimulatedBit | kTruthBit;
  options.speed = testing::kLosslessSpeed;
  StreamerRun streamer(*source, options);
  const StreamSummary summary = streamer.get();
  const ListenSummary s = client.get();
  const std::string expected = testing::simulate_rows(scene, source_options.simulation);
  EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 20 * scene.cycle_count());
  EXPECT_EQ(client.out.str(), expected);
  EXPECT_EQ(s.fragmented_messages, 2u * static_cast<std::uint64_t>(scene.cycle_count()));
  EXPECT_EQ(s.truth_messages, static_cast<std::uint64_t>(scene.cycle_count()));
  EXPECT_EQ(s.lost, 0u);
  EXPECT_EQ(s.incomplete, 0u);
  EXPECT_GT(summary.datagrams, 4u * static_cast<std::uint64_t>(scene.cycle_count()));
  const std::string truth = testing::read_file(listen.truth_output);
  EXPECT_NE(truth.find(",object,pole59,"), std::string::npos);
  EXPECT_EQ(std::count(truth.begin(), truth.end(), '\n'), 1 + 61 * scene.cycle_count());
}

TEST(StreamLoopback, RecordingStreamsRecordedSimulatedAndTruth) {
  const fs::path dir = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "two_in_one_cell";
  const Recording rec = read_recording(dir);
  ASSERT_GT(rec.targets.size(), 20u);
  SourceOptions source_options;
  source_options.simulation.seed = 5;
  auto source = open_source(dir, source_options);
  EXPECT_EQ(source->available_messages(), kSimulatedBit | kRecordedBit | kTruthBit);
  ListenOptions recorded_options;
  recorded_options.print = MessageType::recorded_targets;
  ListenerRun recorded(recorded_options);
  ListenerRun simulated(ListenOptions{});
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", recorded.listener.port()),
                          fmt::format("127.0.0.1:{}", simulated.listener.port())};
  options.destination_messages = kSimulatedBit | kRecordedBit | kTruthBit;
  options.speed = testing::kLosslessSpeed;
  StreamerRun streamer(*source, options);
  streamer.get();
  const ListenSummary sr = recorded.get(), ss = simulated.get();
  // The recorded rows are the recording's targets.csv, in the simulate format.
  std::string expected = "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n";
  for (const RecordedTarget& t : rec.targets) {
    expected += fmt::format("{:.6f},{},{},{},{:.4f},{:.6f},{:.4f},{:.3f}\n", t.t_s, t.cycle, rec.sensors[t.sensor].id, t.id,
                            t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db);
  }
  EXPECT_EQ(recorded.out.str(), expected);
  EXPECT_GT(ss.rows, 0u);
  for (const ListenSummary& s : {sr, ss}) {
    EXPECT_EQ(s.truth_messages, static_cast<std::uint64_t>(rec.cycle_count()));
    EXPECT_EQ(s.target_lists, 4u * static_cast<std::uint64_t>(rec.cycle_count()));
    EXPECT_EQ(s.lost, 0u);
  }
}

TEST(StreamLoopback, ABadRowEndsTheStreamWithItsErrorAndTheListenerKeepsTheCyclesBefore) {
  // A recording is read as it streams: a bad row in the last cycle is found there. The streamer
  // ends with the error (file, line, column), after telling its receivers the stream ended.
  const fs::path dir = testing::temp_dir("bad_row") / "rec";
  fs::copy(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "two_in_one_cell", dir);
  std::string targets = testing::read_file(dir / "targets.csv");
  const std::size_t last_row = targets.rfind('\n', targets.size() - 2) + 1;
  const std::size_t range = [&] {
    std::size_t at = last_row;
    for (int comma = 0; comma < 4; ++comma) at = targets.find(',', at) + 1;
    return at;
  }();
  targets.replace(range, targets.find(',', range) - range, "1e308");
  std::ofstream(dir / "targets.csv", std::ios::trunc) << targets;
  const int rows = static_cast<int>(std::count(targets.begin(), targets.end(), '\n'));

  SourceOptions source_options;
  auto source = open_source(dir, source_options);
  ListenerRun client(ListenOptions{});
  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", client.listener.port())};
  options.speed = testing::kLosslessSpeed * 4;
  std::ostringstream log;
  Streamer streamer(*source, options, log);
  try {
    streamer.run();
    ADD_FAILURE() << "the bad row was not found";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("targets.csv: line {}, column 'range_m'", rows)), std::string::npos)
        << e.what();
  }
  const ListenSummary s = client.get();
  EXPECT_TRUE(s.end_received) << "the listener heard the end";
  EXPECT_EQ(s.lost, 0u);
  const int cycles = source->cycle_count();
  // The bad row is the last cycle's only row; reading cycle k reads on to the first row beyond it,
  // so the error comes in place of cycle k = cycles - 2, and every cycle before it arrived.
  EXPECT_EQ(s.target_lists, 2u * static_cast<std::uint64_t>(cycles - 2));
}

TEST(StreamLoopback, MulticastGroupOnTheLoopbackInterface) {
  const Scene scene = two_sensor_scene(1.0);
  SourceOptions source_options;
  auto source = make_scene_source(scene, source_options);
  ListenOptions listen;
  listen.group = "239.255.77.77";
  listen.group_interface = "127.0.0.1";
  listen.idle_timeout_s = 5.0;  // never hang if the group delivers nothing
  std::unique_ptr<ListenerRun> client;
  try {
    client = std::make_unique<ListenerRun>(listen);
  } catch (const boost::system::system_error& e) {
    GTEST_SKIP() << "no multicast on the loopback interface here: " << e.what();
  }
  StreamOptions options;
  options.destinations = {fmt::format("239.255.77.77:{}", client->listener.port())};
  options.multicast_interface = "127.0.0.1";
  options.speed = testing::kLosslessSpeed;
  StreamerRun streamer(*source, options);
  streamer.get();
  const ListenSummary s = client->get();
  EXPECT_EQ(client->out.str(), testing::simulate_rows(scene, source_options.simulation));
  EXPECT_EQ(s.lost, 0u);
  EXPECT_TRUE(s.end_received);
}

TEST(StreamLoopback, BadOptionsAreRefused) {
  auto source = make_scene_source(two_sensor_scene(0.2), {});
  const auto refused = [&source](StreamOptions o) {
    std::ostringstream log;
    EXPECT_THROW(Streamer(*source, o, log), std::invalid_argument);
  };
  refused({});  // no destination, no control port
  StreamOptions bad_port;
  bad_port.destinations = {"127.0.0.1:notaport"};
  refused(bad_port);
  EXPECT_THROW(parse_speed("0"), std::invalid_argument);
  EXPECT_THROW(parse_speed("fast"), std::invalid_argument);
  EXPECT_EQ(parse_speed("max"), 0.0);
  EXPECT_EQ(parse_speed("10"), 10.0);
  EXPECT_EQ(parse_message_mask("simulated,truth"), kSimulatedBit | kTruthBit);
  EXPECT_THROW(parse_message_mask("tracks"), std::invalid_argument);
  SourceOptions ideal;
  ideal.simulation.level = ListLevel::ideal;
  EXPECT_THROW(make_scene_source(two_sensor_scene(0.2), ideal), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim::stream
