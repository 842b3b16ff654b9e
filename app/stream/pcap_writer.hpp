#pragma once
// A classic pcap file (libpcap 2.4, Ethernet link type) of UDP datagrams, so that what a listener
// received can be opened in Wireshark or tshark with the rcsim dissector
// (tools/wireshark/rcsim.lua). Each datagram is wrapped in Ethernet, IPv4 and UDP headers built
// here (IPv4 only; the UDP checksum is 0, "not computed", which IPv4 allows).
#include <cstdint>
#include <fstream>
#include <span>
#include <string>

#include "stream/endpoints.hpp"

namespace rcsim::stream {

class PcapWriter {
 public:
  explicit PcapWriter(const std::string& path);  // throws std::runtime_error naming the file
  // `unix_time_ns`: the receive time. Datagrams over IPv6 are not written (counted as skipped).
  void write(std::int64_t unix_time_ns, const udp::endpoint& from, const udp::endpoint& to,
             std::span<const std::uint8_t> payload);
  std::uint64_t written() const { return written_; }
  std::uint64_t skipped() const { return skipped_; }
  void flush() { out_.flush(); }

 private:
  std::ofstream out_;
  std::string path_;
  std::uint16_t ip_id_ = 0;
  std::uint64_t written_ = 0, skipped_ = 0;
};

}  // namespace rcsim::stream
