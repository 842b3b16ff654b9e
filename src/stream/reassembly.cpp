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
    for (std::uint64_t s = sequence - tracked; s < sequence; ++s) missing_.insert(s);
    while (missing_.size() > kWindow) {
      missing_.erase(missing_.begin());
      ++given_up_;
    }
    next_ = sequence + 1;
    ++received_;
    return gap == 0 ? Arrival::in_order : Arrival::after_gap;
  }
  if (missing_.erase(sequence) == 1) {
    ++received_;
    ++reordered_;
    return Arrival::late;
  }
  ++duplicates_;
  return Arrival::duplicate;
}

Reassembler::Result Reassembler::add(const Header& header, std::span<const std::uint8_t> payload) {
  Result result;
  if (header.fragment_count == 1) {
    Partial single;
    single.first_header = header;
    single.have_first = true;
    single.type = header.type;
    single.fragments.emplace_back(std::vector<std::uint8_t>(payload.begin(), payload.end()));
    single.received = 1;
    expire(header.message_number);
    return assemble(single);
  }
  expire(header.message_number);
  auto [it, inserted] = partial_.try_emplace(header.message_number);
  Partial& p = it->second;
  if (inserted) {
    p.fragments.resize(header.fragment_count);
    p.type = header.type;
  }
  if (p.type != header.type || p.fragments.size() != header.fragment_count) {
    partial_.erase(it);
    result.status = Status::malformed;
    result.error = DecodeError::bad_fragment;
    return result;
  }
  auto& slot = p.fragments[header.fragment_index];
  if (slot) {
    result.status = Status::duplicate_fragment;
    return result;
  }
  slot.emplace(payload.begin(), payload.end());
  ++p.received;
  if (header.fragment_index == 0) {
    p.first_header = header;
    p.have_first = true;
  }
  if (p.received < p.fragments.size()) return result;
  Partial done = std::move(p);
  partial_.erase(it);
  result = assemble(done);
  if (result.status == Status::complete) ++fragmented_completed_;
  return result;
}

Reassembler::Result Reassembler::assemble(Partial& partial) {
  Result result;
  result.status = Status::malformed;
  const bool targets = partial.type != MessageType::ground_truth;
  TargetListMessage list;
  GroundTruthMessage truth;
  std::uint32_t total = 0;
  std::size_t next_index = 0;
  for (std::size_t f = 0; f < partial.fragments.size(); ++f) {
    const auto& bytes = *partial.fragments[f];
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
        const std::size_t most = partial.fragments.size() * (kMaxDatagramBytes / kTargetBytes);
        list.targets.reserve(std::min<std::size_t>(fragment_total, most));
      } else {
        const TargetListMessage& m = fragment.message;
        agrees = m.cycle == list.cycle && m.sensor_index == list.sensor_index && m.level == list.level &&
                 m.sensor_id == list.sensor_id;
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
      it = partial_.erase(it);
      ++incomplete_;
    } else {
      ++it;
    }
  }
}

std::uint64_t Reassembler::flush() {
  const std::uint64_t n = partial_.size();
  incomplete_ += n;
  partial_.clear();
  return n;
}

}  // namespace rcsim::stream
