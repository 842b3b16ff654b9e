#pragma once
// rcsim listen: the reference client of the UDP stream. Receives passively (a --to destination
// of the streamer, unicast or a multicast group) or subscribes at a control port; decodes,
// reassembles fragments, tracks loss, duplicates and reordering per sender from the sequence
// numbers, and prints the target lists in exactly the format of `rcsim simulate`.
#include <array>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>

#include "sim/target_list_writer.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::stream {

struct ListenOptions {
  std::uint16_t port = 0;                 // 0: any free port (reported in the log)
  std::string bind_address;               // default 127.0.0.1, or 0.0.0.0 with a group
  std::string group;                      // multicast group to join (IPv4)
  std::string group_interface;            // IPv4 address of the interface to join on; empty: the system's choice
  std::string subscribe;                  // [HOST:]PORT of a streamer's control port
  std::string control_token;              // presented when subscribing, empty for none
  std::uint32_t messages = kSimulatedBit; // what to subscribe to
  std::uint32_t sensor_mask = 0;          // 0: every sensor
  MessageType print = MessageType::simulated_targets;  // which target lists go to the output
  TargetListFormat format = TargetListFormat::Csv;
  std::string truth_output;  // CSV of the ground truth messages, if given
  std::string pcap_output;   // every datagram received, as a pcap file, if given
  double idle_timeout_s = 0.0;  // > 0: end after this long without a datagram
  bool stop_at_end = true;      // end at the first END datagram
  bool handle_signals = false;
  double keepalive_s = 1.0;
};

struct ListenSummary {
  std::uint64_t datagrams = 0, bytes = 0, sources = 0;
  std::uint64_t malformed = 0;  // datagrams refused by the decoder, plus messages whose fragments disagree
  std::array<std::uint64_t, kDecodeErrorCount> malformed_by_reason{};
  std::uint64_t messages = 0, fragmented_messages = 0, target_lists = 0, rows = 0, truth_messages = 0;
  std::uint64_t replies = 0, late_flagged = 0;
  std::uint64_t stray_replies = 0;  // control replies not from the streamer subscribed at: ignored
  // Target lists of a (message type, sensor) whose cycle is the last one's again, or an earlier one.
  std::uint64_t cycles_repeated = 0, rewinds = 0;
  std::uint64_t lost = 0, duplicates = 0, reordered = 0, incomplete = 0;
  // Senders (source addresses and ports) whose state was forgotten to keep at most 64 tracked in
  // at most 64 MiB (sender_table.hpp); their partial messages count as incomplete. `sources`
  // counts a forgotten sender heard again once more.
  std::uint64_t senders_forgotten = 0;
  std::size_t senders_peak = 0, sender_state_peak_bytes = 0;
  bool end_received = false;
  EndOfStream end;
  // Of the stream that ended: its datagrams numbered before the first one this listener received
  // (a listener started after the stream: not lost, never seen).
  std::uint64_t sent_before_first = 0;
  bool interrupted = false, idle = false;
  std::string line() const;
};

class Listener {
 public:
  Listener(const ListenOptions& options, std::ostream& out, std::ostream& log);
  ~Listener();
  Listener(const Listener&) = delete;
  Listener& operator=(const Listener&) = delete;

  std::uint16_t port() const;  // bound port, valid after construction
  ListenSummary run();
  void stop();  // thread-safe

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Rows of one target list in the `rcsim simulate` format (schemas/target-list.md), appended.
// `elevation_column`: the rows carry elevation_rad as `rcsim simulate` writes it for a scene with a
// radar that measures elevation (0 for a list without elevations).
void append_target_rows(std::string& out, TargetListFormat format, std::int64_t timestamp_ns, const TargetListMessage& list,
                        bool elevation_column = false);
// The CSV header line of those rows.
std::string target_rows_csv_header(bool elevation_column);

}  // namespace rcsim::stream
