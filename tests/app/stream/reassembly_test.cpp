// Loss, duplicates and reordering from sequence numbers; fragments reassembled exactly.
#include "stream/reassembly.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <set>

namespace rcsim::stream {
namespace {

struct Datagram {
  Header header;
  Bytes payload;
};

// A message as the streamer sends it: one datagram per fragment, consecutive sequence numbers.
std::vector<Datagram> datagrams_of(const TargetListMessage& m, std::uint64_t first_sequence, std::uint32_t message_number) {
  const auto payloads = encode_target_list(m);
  std::vector<Datagram> out;
  for (std::size_t f = 0; f < payloads.size(); ++f) {
    Header h;
    h.type = MessageType::simulated_targets;
    h.sequence = first_sequence + f;
    h.timestamp_ns = 40'000'000;
    h.message_number = message_number;
    h.fragment_index = static_cast<std::uint16_t>(f);
    h.fragment_count = static_cast<std::uint16_t>(payloads.size());
    out.push_back({h, payloads[f]});
  }
  return out;
}

TargetListMessage many_targets(std::size_t n, std::uint32_t cycle) {
  TargetListMessage m;
  m.cycle = cycle;
  m.sensor_index = 1;
  m.sensor_id = "front_right";
  for (std::size_t i = 0; i < n; ++i) {
    m.targets.push_back({static_cast<std::int32_t>(i), 0.1 * static_cast<double>(i), 0.001 * static_cast<double>(i % 3000), -1.0, 3.0});
  }
  return m;
}

TEST(WireSequence, InOrderGapLateAndDuplicate) {
  SequenceTracker t(std::uint64_t{0});
  EXPECT_EQ(t.observe(0), Arrival::in_order);
  EXPECT_EQ(t.observe(1), Arrival::in_order);
  EXPECT_EQ(t.observe(4), Arrival::after_gap);  // 2 and 3 missing
  EXPECT_EQ(t.lost(), 2u);
  EXPECT_EQ(t.observe(3), Arrival::late);  // reordered, not lost
  EXPECT_EQ(t.lost(), 1u);
  EXPECT_EQ(t.reordered(), 1u);
  EXPECT_EQ(t.observe(3), Arrival::duplicate);
  EXPECT_EQ(t.observe(4), Arrival::duplicate);
  EXPECT_EQ(t.observe(5), Arrival::in_order);
  EXPECT_EQ(t.received(), 5u);  // 0 1 3 4 5
  EXPECT_EQ(t.duplicates(), 2u);
  EXPECT_EQ(t.lost(), 1u);      // 2
}

TEST(WireSequence, FreshSubscriptionCountsLossFromZeroPassiveFromFirstSeen) {
  SequenceTracker subscribed(std::uint64_t{0});
  subscribed.observe(3);
  EXPECT_EQ(subscribed.lost(), 3u);
  SequenceTracker passive;
  passive.observe(1000);
  passive.observe(1001);
  EXPECT_EQ(passive.lost(), 0u);
  EXPECT_EQ(passive.first(), 1000u);
}

TEST(WireSequence, AHostileJumpDoesNotGrowMemoryWithoutBound) {
  SequenceTracker t(std::uint64_t{0});
  t.observe(0);
  t.observe(std::uint64_t{1} << 40);
  EXPECT_EQ(t.lost(), (std::uint64_t{1} << 40) - 1);  // all counted lost, only kWindow remembered
  EXPECT_EQ(t.observe((std::uint64_t{1} << 40) - 1), Arrival::late);
  EXPECT_EQ(t.observe(5), Arrival::duplicate);  // too old to tell: not a late arrival
}

// The tracker against the plain model it replaces (a set of the newest kWindow missing numbers)
// over random gaps, reorderings, duplicates and jumps beyond the window.
TEST(WireSequence, MissingRangesCountAsTheSetOfMissingNumbersWould) {
  std::mt19937_64 rng(21);
  SequenceTracker t(std::uint64_t{0});
  std::set<std::uint64_t> missing;
  std::uint64_t next = 0, given_up = 0;
  for (int i = 0; i < 10000; ++i) {
    std::uint64_t s = next + rng() % 4;  // in order or a small gap
    const auto kind = rng() % 100;
    if (kind < 30 && next > 0) {
      s = next - 1 - rng() % std::min<std::uint64_t>(next, 3 * SequenceTracker::kWindow / 2);  // late, duplicate or too old
    } else if (kind == 99) {
      s = next + SequenceTracker::kWindow / 2 + rng() % (2 * SequenceTracker::kWindow);  // a jump, maybe beyond the window
    }
    Arrival expected;
    if (s >= next) {
      const std::uint64_t gap = s - next, tracked = std::min(gap, SequenceTracker::kWindow);
      given_up += gap - tracked;
      for (std::uint64_t m = s - tracked; m < s; ++m) missing.insert(m);
      while (missing.size() > SequenceTracker::kWindow) {
        missing.erase(missing.begin());
        ++given_up;
      }
      next = s + 1;
      expected = gap == 0 ? Arrival::in_order : Arrival::after_gap;
    } else {
      expected = missing.erase(s) == 1 ? Arrival::late : Arrival::duplicate;
    }
    ASSERT_EQ(t.observe(s), expected) << "datagram " << i << ", sequence " << s;
    ASSERT_EQ(t.lost(), given_up + missing.size()) << "datagram " << i;
  }
}

TEST(WireSequence, HostileJumpsCostARangeEachNotOneEntryPerNumber) {
  // Each jump left 2^16 numbers missing; as a set that was 8 ms a datagram (Release), so a flood
  // of them stalled the listener. Fuzzing (tests/fuzz, udp_datagram) made it show.
  SequenceTracker t(std::uint64_t{0});
  std::uint64_t s = 0;
  for (int i = 0; i < 100000; ++i, s += 70000) t.observe(s);
  EXPECT_EQ(t.lost(), s - 70000 + 1 - 100000);
  EXPECT_EQ(t.received(), 100000u);
}

TEST(WireSequence, LossOverALongLossyStreamIsCountedExactly) {
  std::mt19937 rng(3);
  SequenceTracker t(std::uint64_t{0});
  std::uint64_t dropped = 0;
  for (std::uint64_t s = 0; s < 100000; ++s) {
    if (rng() % 50 == 0) {
      ++dropped;
      continue;
    }
    t.observe(s);
  }
  t.observe(100000);  // the END datagram closes the count
  EXPECT_EQ(t.lost(), dropped);
  EXPECT_EQ(t.received(), 100001 - dropped);
}

TEST(WireReassembly, ManyTargetsShuffledAndDuplicatedReassembleExactly) {
  const TargetListMessage m = many_targets(1000, 17);
  auto datagrams = datagrams_of(m, 100, 9);
  ASSERT_GE(datagrams.size(), 25u);  // 1000 targets over 39-target fragments: 26
  const std::size_t fragments = datagrams.size();
  auto copies = datagrams;
  datagrams.insert(datagrams.end(), copies.begin(), copies.begin() + 5);  // duplicates
  std::mt19937 rng(11);
  std::shuffle(datagrams.begin(), datagrams.end(), rng);

  SequenceTracker sequence(std::uint64_t{100});
  Reassembler reassembler;
  int complete = 0, duplicate_datagrams = 0;
  for (const Datagram& d : datagrams) {
    if (sequence.observe(d.header.sequence) == Arrival::duplicate) {
      ++duplicate_datagrams;
      continue;
    }
    const auto result = reassembler.add(d.header, d.payload);
    ASSERT_NE(result.status, Reassembler::Status::malformed);
    if (!result.message) continue;
    ++complete;
    const auto& list = std::get<TargetListMessage>(result.message->message);
    EXPECT_EQ(result.message->header.fragment_index, 0);
    EXPECT_EQ(list.cycle, 17u);
    EXPECT_EQ(list.sensor_id, "front_right");
    ASSERT_EQ(list.targets.size(), m.targets.size());
    for (std::size_t i = 0; i < m.targets.size(); ++i) {
      EXPECT_EQ(list.targets[i].id, m.targets[i].id);
      EXPECT_EQ(list.targets[i].range_m, m.targets[i].range_m);
      EXPECT_EQ(list.targets[i].azimuth_rad, m.targets[i].azimuth_rad);
    }
  }
  EXPECT_EQ(complete, 1);
  EXPECT_EQ(duplicate_datagrams, 5);
  EXPECT_EQ(sequence.lost(), 0u);
  EXPECT_EQ(sequence.received(), fragments);
  EXPECT_GT(sequence.reordered(), 0u);
  EXPECT_EQ(reassembler.pending(), 0u);
  EXPECT_EQ(reassembler.fragmented_completed(), 1u);
}

TEST(WireReassembly, ALostFragmentLeavesTheMessageIncompleteAndCounted) {
  auto datagrams = datagrams_of(many_targets(100, 1), 0, 0);
  ASSERT_EQ(datagrams.size(), 3u);
  Reassembler reassembler;
  EXPECT_FALSE(reassembler.add(datagrams[0].header, datagrams[0].payload).message);
  EXPECT_FALSE(reassembler.add(datagrams[2].header, datagrams[2].payload).message);
  // Newer messages push it out of the window: given up, counted.
  for (std::uint32_t n = 1; n <= Reassembler::kMaxAge + 1; ++n) {
    auto single = datagrams_of(many_targets(1, n), n + 3, n);
    EXPECT_TRUE(reassembler.add(single[0].header, single[0].payload).message);
  }
  EXPECT_EQ(reassembler.incomplete(), 1u);
  EXPECT_EQ(reassembler.pending(), 0u);
}

// Issue 49: a list with elevations is split by 44-byte targets and put back with them; a
// fragment of a planar list under its number makes it malformed.
TEST(WireReassembly, AListWithElevationsReassemblesWithThem) {
  TargetListMessage m = many_targets(60, 3);
  m.elevation = true;
  for (std::size_t i = 0; i < m.targets.size(); ++i) m.targets[i].elevation_rad = 0.01 * static_cast<double>(i);
  const auto d = datagrams_of(m, 0, 1);
  ASSERT_EQ(d.size(), 2u);  // 32 + 28 targets
  Reassembler reassembler;
  EXPECT_FALSE(reassembler.add(d[1].header, d[1].payload).message);
  const auto result = reassembler.add(d[0].header, d[0].payload);
  ASSERT_TRUE(result.message);
  const auto& list = std::get<TargetListMessage>(result.message->message);
  EXPECT_TRUE(list.elevation);
  ASSERT_EQ(list.targets.size(), 60u);
  for (std::size_t i = 0; i < 60; ++i) EXPECT_EQ(list.targets[i].elevation_rad, m.targets[i].elevation_rad) << i;

  TargetListMessage planar = m;
  planar.elevation = false;
  const auto p = datagrams_of(planar, 2, 2);
  const auto e = datagrams_of(m, 4, 2);
  ASSERT_EQ(p.size(), 2u);
  reassembler.add(e[0].header, e[0].payload);
  EXPECT_EQ(reassembler.add(p[1].header, p[1].payload).status, Reassembler::Status::malformed);
}

TEST(WireReassembly, FragmentsThatDisagreeMakeTheMessageMalformed) {
  auto a = datagrams_of(many_targets(100, 1), 0, 5);
  auto b = datagrams_of(many_targets(100, 2), 0, 5);  // same message number, another cycle
  Reassembler reassembler;
  reassembler.add(a[0].header, a[0].payload);
  reassembler.add(a[1].header, a[1].payload);
  const auto result = reassembler.add(b[2].header, b[2].payload);
  EXPECT_EQ(result.status, Reassembler::Status::malformed);
  EXPECT_EQ(result.error, DecodeError::bad_fragment);
  EXPECT_FALSE(result.message);

  // A different fragment count under the same number is refused at once.
  auto c = datagrams_of(many_targets(200, 1), 0, 6);
  reassembler.add(c[0].header, c[0].payload);
  Header other = c[1].header;
  other.fragment_count = 2;
  EXPECT_EQ(reassembler.add(other, c[1].payload).status, Reassembler::Status::malformed);
}

// Issue 21: a target-list header claiming 0xFFFFFFFF targets made the reassembly reserve room for
// them (std::bad_alloc ended the capture). The claim is not trusted: the message is malformed.
TEST(WireReassembly, AHugeClaimedTotalIsMalformedNotAnAllocation) {
  for (const std::size_t n : {std::size_t{1}, std::size_t{200}}) {  // one fragment, and several
    auto d = datagrams_of(many_targets(n, 1), 0, 9);
    for (auto& datagram : d) {
      for (int b = 8; b < 12; ++b) datagram.payload[static_cast<std::size_t>(b)] = 0xFF;  // total_count
    }
    Reassembler reassembler;
    Reassembler::Result last;
    for (const auto& datagram : d) last = reassembler.add(datagram.header, datagram.payload);
    EXPECT_EQ(last.status, Reassembler::Status::malformed) << n;
    EXPECT_FALSE(last.message);
  }
}

TEST(WireReassembly, AClaimedFragmentCountIsNoAllocation) {
  // 1100 datagrams of 35 bytes, each the first of a message claiming 65535 fragments, held 2 GB
  // of empty fragment slots (found by fuzzing: tests/fuzz/regressions/udp_datagram/). Now each
  // partial message holds what it received.
  Reassembler reassembler;
  const Bytes payload(3, 0);
  for (std::uint32_t n = 0; n < 1100; ++n) {
    Header h;
    h.message_number = n;
    h.fragment_count = 0xFFFF;
    EXPECT_EQ(reassembler.add(h, payload).status, Reassembler::Status::pending);
  }
  EXPECT_EQ(reassembler.pending(), Reassembler::kMaxAge + 1);
  EXPECT_EQ(reassembler.pending_bytes(), (Reassembler::kMaxAge + 1) * (3 + Reassembler::kFragmentOverheadBytes));
  EXPECT_EQ(reassembler.incomplete(), 1100u - (Reassembler::kMaxAge + 1));
}

TEST(WireReassembly, PartialMessagesHoldAtMostTheirByteBudget) {
  Reassembler reassembler;
  const Bytes full(kMaxDatagramBytes - kHeaderBytes, 0);
  // Full fragments of 1000 messages that never complete: the oldest are given up.
  for (std::uint32_t n = 0; n < 1000; ++n) {
    for (std::uint16_t f = 0; f < 20; ++f) {
      Header h;
      h.message_number = n;
      h.fragment_index = f;
      h.fragment_count = 0xFFFF;
      reassembler.add(h, full);
      ASSERT_LE(reassembler.pending_bytes(), Reassembler::kMaxPendingBytes);
    }
  }
  EXPECT_GT(reassembler.incomplete(), 400u);
  EXPECT_LT(reassembler.pending(), 600u);
  // One message that alone outgrows the budget is malformed, not held.
  Reassembler one;
  Reassembler::Result last;
  for (std::uint16_t f = 0; f < 0xFFFE; ++f) {
    Header h;
    h.message_number = 7;
    h.fragment_index = f;
    h.fragment_count = 0xFFFF;
    last = one.add(h, full);
    if (last.status != Reassembler::Status::pending) break;
  }
  EXPECT_EQ(last.status, Reassembler::Status::malformed);
  EXPECT_EQ(last.error, DecodeError::bad_length);
  EXPECT_EQ(one.pending_bytes(), 0u);
  // A real message of 100,000 targets (3.6 MB, 2565 fragments) still reassembles.
  const auto datagrams = datagrams_of(many_targets(100000, 3), 0, 9);
  Reassembler big;
  std::optional<CompleteMessage> message;
  for (const auto& d : datagrams) {
    auto result = big.add(d.header, d.payload);
    if (result.message) message = std::move(result.message);
  }
  ASSERT_TRUE(message);
  EXPECT_EQ(std::get<TargetListMessage>(message->message).targets.size(), 100000u);
}

TEST(WireReassembly, GroundTruthFragmentsReassemble) {
  GroundTruthMessage m;
  m.cycle = 3;
  for (std::uint32_t i = 0; i < 100; ++i) m.objects.push_back({i, {double(i), 0, 0, 0}, 4, 2, fmt::format("car_{}", i)});
  const auto payloads = encode_ground_truth(m);
  ASSERT_GT(payloads.size(), 2u);
  Reassembler reassembler;
  std::optional<CompleteMessage> done;
  for (std::size_t f = payloads.size(); f-- > 0;) {  // last fragment first
    Header h;
    h.type = MessageType::ground_truth;
    h.message_number = 1;
    h.fragment_index = static_cast<std::uint16_t>(f);
    h.fragment_count = static_cast<std::uint16_t>(payloads.size());
    auto r = reassembler.add(h, payloads[f]);
    if (r.message) done = std::move(r.message);
  }
  ASSERT_TRUE(done);
  const auto& gt = std::get<GroundTruthMessage>(done->message);
  ASSERT_EQ(gt.objects.size(), 100u);
  EXPECT_EQ(gt.objects[99].object_id, "car_99");
  EXPECT_EQ(gt.objects[42].pose.x_m, 42.0);
}

}  // namespace
}  // namespace rcsim::stream
