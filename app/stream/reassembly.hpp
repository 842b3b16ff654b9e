#pragma once
// The receiving side's bookkeeping: loss, duplicates and reordering from the datagram sequence
// numbers, and fragments put back together into whole messages (schemas/udp-stream.md).
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "stream/wire_format.hpp"

namespace rcsim::stream {

enum class Arrival : std::uint8_t {
  in_order,   // the next expected sequence number
  after_gap,  // newer than expected: the numbers in between are (for now) missing
  late,       // older than the newest, but missing until now: reordered, not lost
  duplicate,  // seen before (or older than the tracking window)
};

// Sequence numbers of one stream. Numbers are counted from `first`, the first one seen (or 0
// when the stream is known to start there: a fresh subscription). Loss at the end of a stream
// shows once the END datagram (which has the last number) arrives.
class SequenceTracker {
 public:
  // Missing numbers further back than this are given up on (counted lost, no longer tracked),
  // so that a hostile jump in the numbers cannot make the record grow without bound.
  static constexpr std::uint64_t kWindow = 1u << 16;

  explicit SequenceTracker(std::optional<std::uint64_t> first = std::nullopt) : next_(first) {}

  Arrival observe(std::uint64_t sequence);
  std::uint64_t received() const { return received_; }  // distinct numbers
  std::uint64_t duplicates() const { return duplicates_; }
  std::uint64_t reordered() const { return reordered_; }
  std::uint64_t lost() const { return given_up_ + missing_count_; }  // missing so far
  std::optional<std::uint64_t> first() const { return first_; }
  // Heap held for the missing ranges: a map node each (48 bytes, 64 with the allocator's header);
  // at most kWindow ranges, 4 MiB, when every other number is missing.
  std::size_t state_bytes() const { return missing_.size() * kRangeNodeBytes; }
  static constexpr std::size_t kRangeNodeBytes = 64;

 private:
  void give_up_beyond_window();

  std::optional<std::uint64_t> next_;
  std::optional<std::uint64_t> first_;
  // The missing numbers as disjoint ranges [first, end), keyed by first: a jump of any size is one
  // range, not one entry per number (a hostile jump of 2^16 cost 8 ms a datagram as a set).
  std::map<std::uint64_t, std::uint64_t> missing_;
  std::uint64_t missing_count_ = 0;  // numbers in missing_, at most kWindow
  std::uint64_t received_ = 0, duplicates_ = 0, reordered_ = 0, given_up_ = 0;
};

// A whole decoded message.
using Message = std::variant<TargetListMessage, GroundTruthMessage>;
struct CompleteMessage {
  Header header;  // of the first fragment (fragment_index 0)
  Message message;
};

// Puts fragments together by message number. Fragments that do not agree with the others of
// their message (another type, cycle, sensor, total, or a gap in the item indices) make the
// message malformed; messages that stay incomplete too long are dropped and counted.
class Reassembler {
 public:
  // A partial message is given up once this many newer message numbers have been seen.
  static constexpr std::uint32_t kMaxAge = 1024;
  // Partial messages hold at most this many bytes in all (payloads, and kFragmentOverheadBytes a
  // fragment); beyond, the oldest are given up, and a message that alone would need more is
  // malformed (bad_length; 100,000 targets are 3.6 MB). A datagram's fragment count is never a
  // size: a header claiming 65535 fragments costs what its own fragment holds.
  static constexpr std::size_t kMaxPendingBytes = 16u << 20;
  static constexpr std::size_t kFragmentOverheadBytes = 64;

  enum class Status : std::uint8_t { complete, pending, malformed, duplicate_fragment };
  struct Result {
    Status status = Status::pending;
    DecodeError error = DecodeError::none;
    std::optional<CompleteMessage> message;
  };

  // `header` decoded without error, of a target-list or ground-truth datagram; `payload` is the
  // datagram after the header.
  Result add(const Header& header, std::span<const std::uint8_t> payload);
  // Gives up every partial message (at the end of the stream); returns how many.
  std::uint64_t flush();

  std::uint64_t incomplete() const { return incomplete_; }  // given up without all fragments
  std::uint64_t fragmented_completed() const { return fragmented_completed_; }
  std::size_t pending() const { return partial_.size(); }
  std::size_t pending_bytes() const { return pending_bytes_; }
  // Heap held in all: the fragments' bytes (pending_bytes) and a map node per partial message.
  std::size_t state_bytes() const;

 private:
  struct Partial {
    Header first_header;
    bool have_first = false;
    std::uint16_t fragment_count = 0;
    std::map<std::uint16_t, std::vector<std::uint8_t>> fragments;  // by index, those received
    std::size_t bytes = 0;                                          // counted in pending_bytes_
    MessageType type{};
  };
  Result assemble(const Partial& partial);
  void expire(std::uint32_t newest);
  void drop(std::map<std::uint32_t, Partial>::iterator it);     // forgets it
  void give_up(std::map<std::uint32_t, Partial>::iterator it);  // forgets it, counted incomplete
  // Gives up the oldest partial messages (not `keep`) until `more` bytes fit in kMaxPendingBytes.
  void make_room(std::size_t more, std::uint32_t keep);

  std::map<std::uint32_t, Partial> partial_;
  std::optional<std::uint32_t> newest_;
  std::size_t pending_bytes_ = 0;
  std::uint64_t incomplete_ = 0, fragmented_completed_ = 0;
};

}  // namespace rcsim::stream
