#include "stream/reassembly.hpp"

#include <algorithm>

namespace rcsim::stream {

Arrival SequenceTracker::observe(std::uint64_t sequence) {
  if (!first_) first_ = next_ ? *next_ : sequence;
  if (!next_) next_ = sequence;
  if (sequence >= *next_) {
    const std::uint64_t gap = sequence - *next_;
    // Remember at most kWindow missing numbers; anything older is lost for good.
    const std::uint64_t tracked = std::min(gap, kWindow);
    given_up_ += gap - tracked;
    if (tracked > 0) {
      missing_.emplace(sequence - tracked, sequence);
      missing_count_ += tracked;
      give_up_beyond_window();
    }
    next_ = sequence + 1;
    ++received_;
    return gap == 0 ? Arrival::in_order : Arrival::after_gap;
  }
  // The range holding `sequence`, if any: split around it.
  auto it = missing_.upper_bound(sequence);
  if (it != missing_.begin() && sequence < (--it)->second) {
    const auto [from, end] = *it;
    missing_.erase(it);
    if (from < sequence) missing_.emplace(from, sequence);
    if (sequence + 1 < end) missing_.emplace(sequence + 1, end);
    --missing_count_;
    ++received_;
    ++reordered_;
    return Arrival::late;
  }
  ++duplicates_;
  return Arrival::duplicate;
}

void SequenceTracker::give_up_beyond_window() {
  while (missing_count_ > kWindow) {
    const auto oldest = missing_.begin();
    const auto [from, end] = *oldest;
    const std::uint64_t excess = missing_count_ - kWindow;
    missing_.erase(oldest);
    if (end - from > excess) missing_.emplace(from + excess, end);  // the range's newer part stays
    const std::uint64_t dropped = std::min(end - from, excess);
    given_up_ += dropped;
    missing_count_ -= dropped;
  }
}

Reassembler::Result Reassembler::add(const Header& header, std::span<const std::uint8_t> payload) {
  Result result;
  if (header.fragment_count == 1) {
    Partial single;
    single.first_header = header;
    single.have_first = true;
    single.type = header.type;
    single.fragment_count = 1;
    single.fragments.emplace(0, std::vector<std::uint8_t>(payload.begin(), payload.end()));
    expire(header.message_number);
    return assemble(single);
  }
  expire(header.message_number);
  auto [it, inserted] = partial_.try_emplace(header.message_number);
  Partial& p = it->second;
  if (inserted) {
    p.fragment_count = header.fragment_count;
    p.type = header.type;
  }
  if (p.type != header.type || p.fragment_count != header.fragment_count) {
    drop(it);
    result.status = Status::malformed;
    result.error = DecodeError::bad_fragment;
    return result;
  }
  if (p.fragments.count(header.fragment_index) != 0) {
    result.status = Status::duplicate_fragment;
    return result;
  }
  const std::size_t bytes = payload.size() + kFragmentOverheadBytes;
  make_room(bytes, header.message_number);
  if (pending_bytes_ + bytes > kMaxPendingBytes) {
    // This message alone outgrows every partial message's room: no sensor sends one so large.
    drop(it);
    ++incomplete_;
    result.status = Status::malformed;
    result.error = DecodeError::bad_length;
    return result;
  }
  p.fragments.emplace(header.fragment_index, std::vector<std::uint8_t>(payload.begin(), payload.end()));
  p.bytes += bytes;
  pending_bytes_ += bytes;
  if (header.fragment_index == 0) {
    p.first_header = header;
    p.have_first = true;
  }
  if (p.fragments.size() < p.fragment_count) return result;
  const Partial done = std::move(p);
  pending_bytes_ -= done.bytes;
  partial_.erase(it);
  result = assemble(done);
  if (result.status == Status::complete) ++fragmented_completed_;
  return result;
}

Reassembler::Result Reassembler::assemble(const Partial& partial) {
  Result result;
  result.status = Status::malformed;
  const bool targets = partial.type != MessageType::ground_truth;
  TargetListMessage list;
  GroundTruthMessage truth;
  std::uint32_t total = 0;
  std::size_t next_index = 0;
  for (const auto& [f, bytes] : partial.fragments) {
    std::uint32_t first = 0, fragment_total = 0;
    std::size_t items = 0;
    bool agrees = true;
    if (targets) {
      TargetListFragment fragment;
      result.error = decode_target_list(bytes, fragment);
      if (result.error != DecodeError::none) return result;
      first = fragment.first_index;
      fragment_total = fragment.total_count;
      items = fragment.message.targets.size();
      if (f == 0) {
        list = std::move(fragment.message);
        // The claimed total is not trusted beyond what the fragments can hold (a hostile header may
        // claim 2^32 targets): at most a full datagram of targets per fragment.
        const std::size_t most = std::size_t{partial.fragment_count} * (kMaxDatagramBytes / kTargetBytes);
        list.targets.reserve(std::min<std::size_t>(fragment_total, most));
      } else {
        const TargetListMessage& m = fragment.message;
        agrees = m.cycle == list.cycle && m.sensor_index == list.sensor_index && m.level == list.level &&
                 m.sensor_id == list.sensor_id && m.elevation == list.elevation;
        list.targets.insert(list.targets.end(), m.targets.begin(), m.targets.end());
      }
    } else {
      GroundTruthFragment fragment;
      result.error = decode_ground_truth(bytes, fragment);
      if (result.error != DecodeError::none) return result;
      first = fragment.first_index;
      fragment_total = fragment.total_count;
      items = fragment.message.objects.size();
      if (f == 0) {
        truth = std::move(fragment.message);
      } else {
        agrees = fragment.message.cycle == truth.cycle;
        truth.objects.insert(truth.objects.end(), fragment.message.objects.begin(), fragment.message.objects.end());
      }
    }
    if (f == 0) total = fragment_total;
    // Each fragment's slice must start where the previous one ended, with the same total.
    if (!agrees || fragment_total != total || first != next_index) {
      result.error = DecodeError::bad_fragment;
      return result;
    }
    next_index += items;
  }
  if (next_index != total) {
    result.error = DecodeError::bad_fragment;
    return result;
  }
  result.status = Status::complete;
  result.error = DecodeError::none;
  result.message = CompleteMessage{partial.first_header, Message{}};
  if (targets) result.message->message = std::move(list);
  else result.message->message = std::move(truth);
  return result;
}

void Reassembler::expire(std::uint32_t newest) {
  // Message numbers grow by one per message; compare modulo 2^32 so that wrap-around works.
  if (!newest_ || static_cast<std::int32_t>(newest - *newest_) > 0) newest_ = newest;
  for (auto it = partial_.begin(); it != partial_.end();) {
    if (static_cast<std::uint32_t>(*newest_ - it->first) > kMaxAge && static_cast<std::int32_t>(*newest_ - it->first) > 0) {
      give_up(it++);
    } else {
      ++it;
    }
  }
}

void Reassembler::drop(std::map<std::uint32_t, Partial>::iterator it) {
  pending_bytes_ -= it->second.bytes;
  partial_.erase(it);
}

void Reassembler::give_up(std::map<std::uint32_t, Partial>::iterator it) {
  drop(it);
  ++incomplete_;
}

void Reassembler::make_room(std::size_t more, std::uint32_t keep) {
  while (pending_bytes_ + more > kMaxPendingBytes) {
    // The oldest: the furthest behind the newest message number, modulo 2^32.
    auto oldest = partial_.end();
    for (auto it = partial_.begin(); it != partial_.end(); ++it) {
      if (it->first != keep && (oldest == partial_.end() || *newest_ - it->first > *newest_ - oldest->first)) oldest = it;
    }
    if (oldest == partial_.end()) return;  // only `keep` left
    give_up(oldest);
  }
}

std::size_t Reassembler::state_bytes() const {
  constexpr std::size_t kNodeLinkBytes = 32;  // a map node's colour and three pointers
  return pending_bytes_ + partial_.size() * (sizeof(decltype(partial_)::value_type) + kNodeLinkBytes);
}

std::uint64_t Reassembler::flush() {
  const std::uint64_t n = partial_.size();
  incomplete_ += n;
  partial_.clear();
  pending_bytes_ = 0;
  return n;
}

}  // namespace rcsim::stream
