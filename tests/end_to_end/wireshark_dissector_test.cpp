// tools/wireshark/rcsim.lua, run by tshark on captures of a loopback stream: a live capture on
// the loopback interface when this machine allows one, and always the pcap that `rcsim listen
// --pcap` writes of the datagrams it received. What tshark decodes must be what the listener
// decoded. Needs tshark (Debian package `tshark`); fails without it unless RCSIM_NO_TSHARK=1.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <future>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "stream/cycle_source.hpp"
#include "stream/listener.hpp"
#include "stream/pcap_writer.hpp"
#include "stream/streamer.hpp"
#include "app/stream/stream_test_support.hpp"
#include "test_support.hpp"

namespace rcsim::stream {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;
using boost::asio::ip::udp;

const std::string kDissector = std::string(RCSIM_SOURCE_DIR) + "/tools/wireshark/rcsim.lua";

struct Packet {
  std::uint64_t sequence = 0;
  int type = 0;
  int fragment_count = 0;
  std::vector<double> ranges_m;
  std::vector<std::string> objects;
  std::string end_cycles;
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::string item;
  std::stringstream s(text);
  while (std::getline(s, item, separator)) out.push_back(item);
  if (!text.empty() && text.back() == separator) out.emplace_back();
  return out;
}

// tshark's reading of a capture, one Packet per rcsim datagram (display filter: rcsim, and to
// the given UDP port if one is given).
std::vector<Packet> dissect(const fs::path& capture, const fs::path& dir, std::uint16_t port = 0) {
  const fs::path out = dir / "tshark.out", err = dir / "tshark.err";
  testing::Child tshark = testing::spawn(
      {"tshark", "-r", capture.string(), "-X", "lua_script:" + kDissector, "-Y",
       port == 0 ? std::string("rcsim") : fmt::format("rcsim && udp.dstport == {}", port), "-T", "fields", "-E", "separator=/t",
       "-E", "aggregator=;", "-e", "rcsim.sequence", "-e", "rcsim.type", "-e", "rcsim.fragment_count", "-e",
       "rcsim.target.range_m", "-e", "rcsim.object.id", "-e", "rcsim.end.cycles_sent"},
      out, err);
  EXPECT_EQ(tshark.wait(30s), 0) << testing::read_file(err);
  std::vector<Packet> packets;
  for (const std::string& line : split(testing::read_file(out), '\n')) {
    if (line.empty()) continue;
    const auto f = split(line, '\t');
    if (f.size() < 6) {
      ADD_FAILURE() << "tshark line: " << line;
      continue;
    }
    Packet p;
    p.sequence = std::stoull(f[0]);
    p.type = std::stoi(f[1], nullptr, 16);
    p.fragment_count = std::stoi(f[2]);
    for (const auto& r : split(f[3], ';')) {
      if (!r.empty()) p.ranges_m.push_back(std::stod(r));
    }
    for (const auto& o : split(f[4], ';')) {
      if (!o.empty()) p.objects.push_back(o);
    }
    p.end_cycles = f[5];
    packets.push_back(p);
  }
  return packets;
}

// The range column of the listener's CSV output.
std::vector<double> printed_ranges_m(const std::string& csv) {
  std::vector<double> out;
  const auto lines = split(csv, '\n');
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    out.push_back(std::stod(split(lines[i], ',')[4]));
  }
  return out;
}

void check(const std::vector<Packet>& packets, const ListenSummary& summary, const std::string& printed, int cycles,
           const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(packets.size(), summary.datagrams);
  std::vector<double> ranges;
  int lists = 0, truth = 0, ends = 0, fragmented = 0;
  bool pole59 = false;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    const Packet& p = packets[i];
    EXPECT_EQ(p.sequence, i);
    fragmented += p.fragment_count > 1;
    if (p.type == 0x01) {
      ++lists;
      ranges.insert(ranges.end(), p.ranges_m.begin(), p.ranges_m.end());
    } else if (p.type == 0x03) {
      ++truth;
      for (const auto& o : p.objects) pole59 |= o == "pole59";
    } else if (p.type == 0x04) {
      ++ends;
      EXPECT_EQ(p.end_cycles, std::to_string(cycles));
    }
  }
  EXPECT_EQ(ends, 1);
  EXPECT_GT(lists, cycles);  // fragments
  EXPECT_GT(truth, cycles);
  EXPECT_GT(fragmented, 0);
  EXPECT_TRUE(pole59);
  const std::vector<double> expected = printed_ranges_m(printed);
  ASSERT_EQ(ranges.size(), expected.size());
  ASSERT_GT(ranges.size(), 50u);
  for (std::size_t i = 0; i < ranges.size(); ++i) EXPECT_NEAR(ranges[i], expected[i], 5.1e-5) << i;
}

TEST(StreamDissector, TsharkDecodesTheLoopbackStreamAsTheListenerDoes) {
  if (const char* skip = std::getenv("RCSIM_NO_TSHARK"); skip && std::string(skip) == "1") GTEST_SKIP() << "RCSIM_NO_TSHARK=1";
  ASSERT_EQ(std::system("command -v tshark > /dev/null 2>&1"), 0)
      << "tshark not found: install the Debian package 'tshark' (or set RCSIM_NO_TSHARK=1 to skip this test)";
  const fs::path dir = testing::temp_dir("dissector");

  Scene scene = rcsim::testing::single_sensor_scene(0.2);
  for (int i = 0; i < 60; ++i) {
    rcsim::testing::add_object(scene, fmt::format("pole{}", i), "pole", {rcsim::testing::sample(0.0, 4.0 + 0.7 * i, 0.0, 0.0, 0.0)});
  }
  SourceOptions source_options;
  source_options.simulation.level = ListLevel::detections;
  source_options.simulation.noise = false;
  source_options.max_datagram_bytes = 400;
  auto source = make_scene_source(scene, source_options);

  ListenOptions listen;
  listen.pcap_output = (dir / "listener.pcap").string();
  std::ostringstream out, log;
  Listener listener(listen, out, log);
  auto listened = std::async(std::launch::async, [&listener] { return listener.run(); });

  // A live capture on the loopback interface, if this machine lets us capture. tshark prints a
  // line per packet (-P) while it writes the file: warm-up datagrams show when the capture really
  // runs, and the line count when it has seen everything. The warm-ups go to a socket of our own
  // that never reads them: other tests running in parallel send to fixed ports (9), which must
  // not enter the capture.
  const fs::path live = dir / "live.pcapng";
  boost::asio::io_context io;
  udp::socket warm_up(io, udp::v4());
  udp::socket warm_up_sink(io, udp::endpoint(boost::asio::ip::make_address("127.0.0.1"), 0));
  const udp::endpoint warm_up_to = warm_up_sink.local_endpoint();
  const std::string capture_filter = fmt::format("udp dst port {} or udp dst port {}", listener.port(), warm_up_to.port());
  testing::Child capture = testing::spawn(
      {"tshark", "-l", "-P", "-i", "lo", "-f", capture_filter, "-w", live.string()},
      dir / "capture.out", dir / "capture.err");
  const auto capture_lines = [&dir] {
    const std::string text = testing::read_file(dir / "capture.out");
    return static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n'));
  };
  bool capturing = false;
  for (int i = 0; i < 100 && !capturing; ++i) {
    warm_up.send_to(boost::asio::buffer("warm-up", 7), warm_up_to);
    std::this_thread::sleep_for(50ms);
    capturing = capture_lines() > 0;
  }
  const std::uint64_t warm_ups = capture_lines();

  StreamOptions options;
  options.destinations = {fmt::format("127.0.0.1:{}", listener.port())};
  options.destination_messages = kSimulatedBit | kTruthBit;
  options.speed = testing::kLosslessSpeed;
  std::ostringstream stream_log;
  Streamer streamer(*source, options, stream_log);
  streamer.run();
  const ListenSummary summary = listened.get();
  ASSERT_EQ(summary.lost, 0u);
  for (int i = 0; i < 100 && capturing && capture_lines() < warm_ups + summary.datagrams; ++i) std::this_thread::sleep_for(50ms);
  ::kill(capture.pid, SIGINT);
  capture.wait(10s);

  check(dissect(listen.pcap_output, dir), summary, out.str(), scene.cycle_count(), "pcap written by the listener");
  if (capturing) {
    check(dissect(live, dir, listener.port()), summary, out.str(), scene.cycle_count(), "live capture on lo");
  } else {
    std::cerr << "[ note ] no live capture on lo here (" << testing::read_file(dir / "capture.err")
              << "); checked the listener's pcap only\n";
  }
  fs::remove_all(dir);
}

// A list of a sensor that measures elevation (flag bit 0, 44-byte targets) beside a planar one:
// tshark reads the elevation where there is one, and the planar list as before.
TEST(StreamDissector, TsharkReadsTheElevationOfAListThatCarriesIt) {
  if (const char* skip = std::getenv("RCSIM_NO_TSHARK"); skip && std::string(skip) == "1") GTEST_SKIP() << "RCSIM_NO_TSHARK=1";
  ASSERT_EQ(std::system("command -v tshark > /dev/null 2>&1"), 0) << "tshark not found";
  const fs::path dir = testing::temp_dir("dissector_elevation");
  const fs::path capture = dir / "elevation.pcap";
  {
    PcapWriter pcap(capture.string());
    const udp::endpoint from(boost::asio::ip::make_address("127.0.0.1"), 40000), to(from.address(), 5005);
    TargetListMessage list;
    list.sensor_id = "imaging";
    list.elevation = true;
    list.targets = {{1, 10.0, 0.25, -1.5, 30.0, std::asin(0.1)}, {2, 20.0, -0.1, 0.0, 20.0, -0.05}};
    Header h;
    pcap.write(0, from, to, make_datagram(h, encode_target_list(list).front()));
    list.elevation = false;
    h.sequence = 1;
    h.message_number = 1;
    pcap.write(1, from, to, make_datagram(h, encode_target_list(list).front()));
  }
  const fs::path out = dir / "tshark.out", err = dir / "tshark.err";
  testing::Child tshark = testing::spawn({"tshark", "-r", capture.string(), "-X", "lua_script:" + kDissector, "-Y", "rcsim",
                                          "-T", "fields", "-E", "separator=/t", "-E", "aggregator=;", "-e",
                                          "rcsim.list_flags.elevation", "-e", "rcsim.target.range_m", "-e",
                                          "rcsim.target.elevation_rad", "-e", "_ws.expert.message"},
                                         out, err);
  ASSERT_EQ(tshark.wait(30s), 0) << testing::read_file(err);
  const auto lines = split(testing::read_file(out), '\n');
  ASSERT_GE(lines.size(), 2u) << testing::read_file(out);
  const auto elevated = split(lines[0], '\t'), planar = split(lines[1], '\t');
  ASSERT_GE(elevated.size(), 3u) << lines[0];
  ASSERT_GE(planar.size(), 3u) << lines[1];
  EXPECT_TRUE(elevated[0] == "1" || elevated[0] == "True") << elevated[0];
  EXPECT_EQ(elevated[1], "10;20");
  const auto elevations = split(elevated[2], ';');
  ASSERT_EQ(elevations.size(), 2u) << elevated[2];
  EXPECT_NEAR(std::stod(elevations[0]), std::asin(0.1), 1e-12);
  EXPECT_NEAR(std::stod(elevations[1]), -0.05, 1e-12);
  EXPECT_TRUE(planar[0] == "0" || planar[0] == "False") << planar[0];
  EXPECT_EQ(planar[1], "10;20");
  EXPECT_EQ(planar[2], "");
  if (elevated.size() > 3) {
    EXPECT_EQ(elevated[3], "");  // no expert info: well-formed
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rcsim::stream
