// PcapWriter of app/stream/pcap_writer.hpp: the file's global header, one record's Ethernet, IPv4
// (with its RFC 791 checksum) and UDP headers byte by byte, the datagrams it skips, and a path it
// cannot open.
#include "stream/pcap_writer.hpp"

#include <gtest/gtest.h>

#include <boost/asio/ip/address.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "scratch_dir.hpp"

namespace rcsim::pcap_writer_test {

using stream::PcapWriter;
using stream::udp;

std::vector<std::uint8_t> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

udp::endpoint endpoint(const char* address, unsigned short port) {
  return {boost::asio::ip::make_address(address), port};
}

class StreamPcapWriter : public rcsim::testing::ScratchDirTest {
 protected:
  StreamPcapWriter() : ScratchDirTest("pcap_writer") {}
};

TEST_F(StreamPcapWriter, OneDatagramByteByByte) {
  const auto path = dir_ / "one.pcap";
  PcapWriter writer(path.string());
  const std::vector<std::uint8_t> payload = {'a', 'b', 'c'};
  // 1 700 000 000.123456789 s: the record keeps whole microseconds, 123456.
  writer.write(1'700'000'000'123'456'789, endpoint("127.0.0.1", 5000), endpoint("10.0.0.2", 6000), payload);
  writer.flush();
  EXPECT_EQ(writer.written(), 1u);
  EXPECT_EQ(writer.skipped(), 0u);
  const std::vector<std::uint8_t> expected = {
      // Global header: magic a1b2c3d4 (little-endian), version 2.4, zone 0, sigfigs 0,
      // snapshot length 65535, link type 1 (Ethernet).
      0xd4, 0xc3, 0xb2, 0xa1, 2, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0, 0, 1, 0, 0, 0,
      // Record: 1700000000 = 0x6553f100 s, 123456 = 0x1e240 us, 45 bytes captured and on the wire.
      0x00, 0xf1, 0x53, 0x65, 0x40, 0xe2, 0x01, 0x00, 45, 0, 0, 0, 45, 0, 0, 0,
      // Ethernet: to 02:00:00:00:00:02 from 02:00:00:00:00:01, IPv4.
      0x02, 0, 0, 0, 0, 2, 0x02, 0, 0, 0, 0, 1, 0x08, 0x00,
      // IPv4: 45 00, length 31, id 0, don't fragment, TTL 64, UDP, checksum, 127.0.0.1 -> 10.0.0.2.
      // Checksum: 4500 + 001f + 4000 + 4011 + 7f00 + 0001 + 0a00 + 0002 = 0x14e33 -> 0x4e34,
      // complemented 0xb1cb.
      0x45, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x40, 0x00, 0x40, 0x11, 0xb1, 0xcb, 127, 0, 0, 1, 10, 0, 0, 2,
      // UDP: 5000 -> 6000, length 11, checksum 0 (not computed), then the payload.
      0x13, 0x88, 0x17, 0x70, 0x00, 0x0b, 0x00, 0x00, 'a', 'b', 'c'};
  EXPECT_EQ(file_bytes(path), expected);
}

TEST_F(StreamPcapWriter, RecordsFollowEachOtherWithTheirOwnIpIdAndValidChecksums) {
  const auto path = dir_ / "two.pcap";
  PcapWriter writer(path.string());
  const std::vector<std::uint8_t> empty;
  const std::vector<std::uint8_t> four = {1, 2, 3, 4};
  writer.write(2'000'000'000, endpoint("192.168.1.20", 40000), endpoint("192.168.1.1", 30000), empty);
  writer.write(2'000'999'999, endpoint("192.168.1.20", 40000), endpoint("192.168.1.1", 30000), four);
  writer.flush();
  const std::vector<std::uint8_t> bytes = file_bytes(path);
  ASSERT_EQ(bytes.size(), 24u + (16u + 42u) + (16u + 46u));
  const std::size_t second = 24 + 16 + 42;
  // Second record at 2.000999999 s: 2 s and 999 us (truncated, not rounded).
  EXPECT_EQ(bytes[second], 2);
  EXPECT_EQ(bytes[second + 4] | bytes[second + 5] << 8, 999);
  // The IPv4 identification counts up: 0, then 1.
  EXPECT_EQ(bytes[24 + 16 + 14 + 5], 0);
  EXPECT_EQ(bytes[second + 16 + 14 + 5], 1);
  // Each IPv4 header sums (one's complement, with its checksum) to 0xffff.
  for (const std::size_t ip : {std::size_t{24 + 16 + 14}, second + 16 + 14}) {
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < 20; i += 2) sum += static_cast<std::uint32_t>(bytes[ip + i] << 8 | bytes[ip + i + 1]);
    while (sum >> 16) sum = (sum & 0xffff) + (sum >> 16);
    EXPECT_EQ(sum, 0xffffu) << ip;
  }
  // The empty datagram's UDP length is its header's 8 bytes.
  EXPECT_EQ(bytes[24 + 16 + 14 + 20 + 5], 8);
}

TEST_F(StreamPcapWriter, SkipsIPv6AndOversizedDatagrams) {
  const auto path = dir_ / "skipped.pcap";
  PcapWriter writer(path.string());
  const std::vector<std::uint8_t> small = {7};
  writer.write(0, endpoint("::1", 1), endpoint("::1", 2), small);
  writer.write(0, endpoint("127.0.0.1", 1), endpoint("::1", 2), small);
  // 65507 bytes is the largest UDP payload over IPv4 (65535 - 20 - 8): one more is skipped.
  writer.write(0, endpoint("127.0.0.1", 1), endpoint("127.0.0.1", 2), std::vector<std::uint8_t>(65508, 0));
  EXPECT_EQ(writer.skipped(), 3u);
  EXPECT_EQ(writer.written(), 0u);
  writer.write(0, endpoint("127.0.0.1", 1), endpoint("127.0.0.1", 2), std::vector<std::uint8_t>(65507, 0));
  EXPECT_EQ(writer.written(), 1u);
  writer.flush();
  EXPECT_EQ(std::filesystem::file_size(path), 24u + 16u + 42u + 65507u);
}

TEST_F(StreamPcapWriter, RefusesAPathItCannotOpenNamingIt) {
  const std::string path = (dir_ / "missing" / "out.pcap").string();
  try {
    PcapWriter writer(path);
    FAIL() << "opened " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open for writing");
  }
}

}  // namespace rcsim::pcap_writer_test
