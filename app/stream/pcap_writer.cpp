#include "stream/pcap_writer.hpp"

#include <array>
#include <stdexcept>
#include <vector>

namespace rcsim::stream {
namespace {

// pcap's own headers are in the writer's byte order (the magic tells a reader which); we write
// little-endian. Network headers are big-endian.
void le(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void be(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// RFC 791 header checksum: one's complement of the one's-complement sum of 16-bit words.
std::uint16_t ipv4_checksum(std::span<const std::uint8_t> header) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < header.size(); i += 2) sum += static_cast<std::uint32_t>(header[i] << 8 | header[i + 1]);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum & 0xFFFF);
}

}  // namespace

PcapWriter::PcapWriter(const std::string& path) : out_(path, std::ios::binary | std::ios::trunc), path_(path) {
  if (!out_) throw std::runtime_error(path + ": cannot open for writing");
  std::vector<std::uint8_t> header;
  le(header, 0xa1b2c3d4, 4);  // microsecond timestamps
  le(header, 2, 2);
  le(header, 4, 2);
  le(header, 0, 4);       // GMT offset
  le(header, 0, 4);       // timestamp accuracy
  le(header, 65535, 4);   // snapshot length
  le(header, 1, 4);       // LINKTYPE_ETHERNET
  out_.write(reinterpret_cast<const char*>(header.data()), static_cast<std::streamsize>(header.size()));
}

void PcapWriter::write(std::int64_t unix_time_ns, const udp::endpoint& from, const udp::endpoint& to,
                       std::span<const std::uint8_t> payload) {
  if (!from.address().is_v4() || !to.address().is_v4() || payload.size() > 65507) {
    ++skipped_;
    return;
  }
  std::vector<std::uint8_t> frame;
  frame.reserve(42 + payload.size());
  // Ethernet II: locally administered addresses, EtherType IPv4.
  constexpr std::array<std::uint8_t, 12> kMacs = {0x02, 0, 0, 0, 0, 2, 0x02, 0, 0, 0, 0, 1};
  frame.insert(frame.end(), kMacs.begin(), kMacs.end());
  be(frame, 0x0800, 2);
  const std::size_t ip_start = frame.size();
  be(frame, 0x45, 1);  // version 4, 5 words
  be(frame, 0, 1);
  be(frame, 20 + 8 + payload.size(), 2);
  be(frame, ip_id_++, 2);
  be(frame, 0x4000, 2);  // don't fragment
  be(frame, 64, 1);
  be(frame, 17, 1);  // UDP
  be(frame, 0, 2);   // checksum, below
  be(frame, from.address().to_v4().to_uint(), 4);
  be(frame, to.address().to_v4().to_uint(), 4);
  const std::uint16_t checksum = ipv4_checksum({frame.data() + ip_start, 20});
  frame[ip_start + 10] = static_cast<std::uint8_t>(checksum >> 8);
  frame[ip_start + 11] = static_cast<std::uint8_t>(checksum & 0xFF);
  be(frame, from.port(), 2);
  be(frame, to.port(), 2);
  be(frame, 8 + payload.size(), 2);
  be(frame, 0, 2);
  frame.insert(frame.end(), payload.begin(), payload.end());

  std::vector<std::uint8_t> record;
  le(record, static_cast<std::uint64_t>(unix_time_ns / 1'000'000'000), 4);
  le(record, static_cast<std::uint64_t>(unix_time_ns % 1'000'000'000 / 1000), 4);
  le(record, frame.size(), 4);
  le(record, frame.size(), 4);
  out_.write(reinterpret_cast<const char*>(record.data()), static_cast<std::streamsize>(record.size()));
  out_.write(reinterpret_cast<const char*>(frame.data()), static_cast<std::streamsize>(frame.size()));
  if (!out_) throw std::runtime_error(path_ + ": write failed");
  ++written_;
}

}  // namespace rcsim::stream
