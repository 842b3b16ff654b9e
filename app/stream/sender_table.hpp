#pragma once
// A receiver's state per sender: sequence numbers and partial messages (reassembly.hpp), for a
// bounded number of senders in bounded memory. Every source port is a sender, so a flood from
// many ports (or streamers coming and going for hours) would otherwise grow the listener without
// bound: each sender may hold up to 16 MiB of partial messages and 4 MiB of missing ranges.
//
// At most kMaxSenders are tracked, holding at most kMaxStateBytes in all. Beyond either, the
// least recently heard sender is forgotten, preferring one that never delivered a whole message
// (a real stream delivers one every cycle; a flood of fragments never does): its partial messages
// count as incomplete and its loss, duplicate and reordering counts are kept. A sender heard
// again after that starts afresh, from the first sequence number it is then seen with.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <list>
#include <map>
#include <optional>

#include "stream/reassembly.hpp"

namespace rcsim::stream {

struct SenderState {
  SequenceTracker sequence{};
  Reassembler reassembler{};
  bool delivered = false;  // has completed a message
};

struct SenderCounts {
  std::uint64_t lost = 0, duplicates = 0, reordered = 0, incomplete = 0;
};

template <class Key>
class SenderTable {
 public:
  // A listener hears one streamer, or a few on a multicast group; 64 leave room for many
  // streamers and bound the table's own overhead (about 200 bytes a sender) to nothing.
  static constexpr std::size_t kMaxSenders = 64;
  // Four senders' worth of partial messages at their own cap (Reassembler::kMaxPendingBytes):
  // a real stream holds a few kB at a time (100,000 targets in flight are 3.6 MB).
  static constexpr std::size_t kMaxStateBytes = 64u << 20;

  // `key` is never forgotten (the streamer a listener subscribed at: its count starts at 0).
  void pin(const Key& key) { pinned_ = key; }

  // The state of the sender of a datagram, now the most recently heard; `fresh` when it was not
  // tracked (new, or forgotten since). A new sender that finds the table full forgets another.
  SenderState& hear(const Key& key, bool& fresh) {
    const auto found = index_.find(key);
    fresh = found == index_.end();
    if (!fresh) {
      order_.splice(order_.begin(), order_, found->second);
      return found->second->state;
    }
    if (order_.size() >= kMaxSenders) forget_one(nullptr);
    order_.push_front(Entry{key});
    order_.front().bytes = bytes_of(order_.front());
    total_bytes_ += order_.front().bytes;
    index_.emplace(key, order_.begin());
    ++admitted_;
    peak_senders_ = std::max(peak_senders_, order_.size());
    return order_.front().state;
  }

  // After `key`'s datagram changed its state: others are forgotten until all fit the budget.
  void account(const Key& key) {
    const auto found = index_.find(key);
    if (found == index_.end()) return;
    Entry& entry = *found->second;
    total_bytes_ -= entry.bytes;
    entry.bytes = bytes_of(entry);
    total_bytes_ += entry.bytes;
    while (total_bytes_ > kMaxStateBytes && forget_one(&key)) {
    }
    peak_bytes_ = std::max(peak_bytes_, total_bytes_);
  }

  // Gives up every partial message; the counts of every sender, tracked and forgotten.
  SenderCounts finish() {
    SenderCounts counts = forgotten_counts_;
    for (Entry& entry : order_) {
      entry.state.reassembler.flush();
      add_counts(entry.state, counts);
    }
    return counts;
  }

  std::size_t size() const { return order_.size(); }
  std::size_t state_bytes() const { return total_bytes_; }
  std::size_t peak_senders() const { return peak_senders_; }
  std::size_t peak_state_bytes() const { return peak_bytes_; }
  std::uint64_t admitted() const { return admitted_; }    // fresh senders, counting returns
  std::uint64_t forgotten() const { return forgotten_; }  // senders forgotten to keep the bounds

 private:
  struct Entry {
    Key key;
    SenderState state{};
    std::size_t bytes = 0;  // counted in total_bytes_
  };
  using Iterator = typename std::list<Entry>::iterator;

  static std::size_t bytes_of(const Entry& entry) {
    constexpr std::size_t kNodeBytes = sizeof(Entry) + sizeof(Key) + sizeof(Iterator) + 64;  // list and map nodes
    return kNodeBytes + entry.state.sequence.state_bytes() + entry.state.reassembler.state_bytes();
  }

  static void add_counts(const SenderState& state, SenderCounts& counts) {
    counts.lost += state.sequence.lost();
    counts.duplicates += state.sequence.duplicates();
    counts.reordered += state.sequence.reordered();
    counts.incomplete += state.reassembler.incomplete();
  }

  // Forgets the least recently heard sender that never delivered a message, else the least
  // recently heard; never the pinned one nor `keep`. False when there is none to forget.
  bool forget_one(const Key* keep) {
    std::optional<Iterator> victim;
    for (auto it = order_.end(); it != order_.begin();) {
      --it;
      if ((pinned_ && it->key == *pinned_) || (keep && it->key == *keep)) continue;
      if (!victim) victim = it;
      if (!it->state.delivered) {
        victim = it;
        break;
      }
    }
    if (!victim) return false;
    Entry& entry = **victim;
    entry.state.reassembler.flush();
    add_counts(entry.state, forgotten_counts_);
    total_bytes_ -= entry.bytes;
    index_.erase(entry.key);
    order_.erase(*victim);
    ++forgotten_;
    return true;
  }

  std::list<Entry> order_;  // most recently heard first
  std::map<Key, Iterator> index_;
  std::optional<Key> pinned_;
  SenderCounts forgotten_counts_;
  std::size_t total_bytes_ = 0, peak_bytes_ = 0, peak_senders_ = 0;
  std::uint64_t admitted_ = 0, forgotten_ = 0;
};

}  // namespace rcsim::stream
