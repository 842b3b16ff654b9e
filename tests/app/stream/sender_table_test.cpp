// The listener's per-sender state is bounded in senders and in bytes (issue 21): a flood from
// many source ports forgets the least recently heard senders, preferring those that never
// delivered a message, and keeps their counts.
#include "stream/sender_table.hpp"

#include <gtest/gtest.h>

namespace rcsim::stream {
namespace {

using Table = SenderTable<int>;

// A datagram as the listener hands it on: the sender's tracker, then its reassembler.
void receive(Table& table, int sender, const Header& header, const Bytes& payload) {
  bool fresh = false;
  SenderState& state = table.hear(sender, fresh);
  if (state.sequence.observe(header.sequence) != Arrival::duplicate) {
    if (state.reassembler.add(header, payload).message) state.delivered = true;
  }
  table.account(sender);
}

// Fragment `index` of a message of `count` fragments that never completes (full payloads).
Header fragment_header(std::uint64_t sequence, std::uint32_t message, std::uint16_t index, std::uint16_t count) {
  Header h;
  h.sequence = sequence;
  h.message_number = message;
  h.fragment_index = index;
  h.fragment_count = count;
  return h;
}

const Bytes kFullPayload(kMaxDatagramBytes - kHeaderBytes, 0);

// One whole single-fragment target list.
Bytes whole_list(std::uint32_t cycle) {
  TargetListMessage m;
  m.cycle = cycle;
  m.sensor_id = "front";
  m.targets.resize(3);
  return encode_target_list(m).front();
}

TEST(SenderTable, MoreSendersThanTheCapForgetTheLeastRecentlyHeard) {
  Table table;
  constexpr int kSenders = 1000;
  for (int s = 0; s < kSenders; ++s) {
    receive(table, s, fragment_header(0, 0, 0, 2), kFullPayload);  // half a message each
    ASSERT_LE(table.size(), Table::kMaxSenders);
  }
  EXPECT_EQ(table.size(), Table::kMaxSenders);
  EXPECT_EQ(table.peak_senders(), Table::kMaxSenders);
  EXPECT_EQ(table.admitted(), static_cast<std::uint64_t>(kSenders));
  EXPECT_EQ(table.forgotten(), static_cast<std::uint64_t>(kSenders) - Table::kMaxSenders);
  // The newest 64 are tracked: sender 999 is known, sender 0 (forgotten) comes back fresh.
  bool fresh = true;
  table.hear(kSenders - 1, fresh);
  EXPECT_FALSE(fresh);
  table.hear(0, fresh);
  EXPECT_TRUE(fresh);
  EXPECT_EQ(table.forgotten(), static_cast<std::uint64_t>(kSenders) - Table::kMaxSenders + 1);
  // Every half message is counted incomplete once: when forgotten, or at the end.
  EXPECT_EQ(table.finish().incomplete, static_cast<std::uint64_t>(kSenders));
  EXPECT_LT(table.peak_state_bytes(), (Table::kMaxSenders + 1) * 2 * kMaxDatagramBytes + (64u << 10));
}

TEST(SenderTable, TheStateOfAllSendersStaysWithinItsByteBudget) {
  Table table;
  // 20 senders with 12 MiB of partial messages each (within each one's own 16 MiB): 240 MiB
  // unbounded, at most 64 MiB here.
  constexpr int kSenders = 20;
  constexpr std::uint16_t kFragments = 200;  // of each message, which claims one more
  constexpr std::uint32_t kMessages = 12 * 1024 * 1024 / (kMaxDatagramBytes - kHeaderBytes + 64) / kFragments;
  std::uint64_t partial_messages = 0;
  for (int s = 0; s < kSenders; ++s) {
    std::uint64_t sequence = 0;
    for (std::uint32_t m = 0; m < kMessages; ++m, ++partial_messages) {
      for (std::uint16_t f = 0; f < kFragments; ++f) {
        receive(table, s, fragment_header(sequence++, m, f, kFragments + 1), kFullPayload);
        ASSERT_LE(table.state_bytes(), Table::kMaxStateBytes);
      }
    }
  }
  EXPECT_LE(table.peak_state_bytes(), Table::kMaxStateBytes);
  EXPECT_GT(table.peak_state_bytes(), Table::kMaxStateBytes - (16u << 20));
  EXPECT_GE(table.forgotten(), static_cast<std::uint64_t>(kSenders) - 6);  // 12 MiB each: 5 fit in 64
  EXPECT_LE(table.size(), 6u);
  EXPECT_EQ(table.finish().incomplete, partial_messages);
}

TEST(SenderTable, ASenderThatDeliveredOutlastsAFloodOfSendersThatNeverDid) {
  Table table;
  constexpr int kStream = -1;
  std::uint64_t stream_sequence = 0;
  for (std::uint32_t cycle = 0; cycle < 50; ++cycle) {
    receive(table, kStream, fragment_header(stream_sequence++, cycle, 0, 1), whole_list(cycle));
    // 100 new senders between two of the stream's datagrams, each with half a message.
    for (int s = 0; s < 100; ++s) receive(table, static_cast<int>(cycle) * 100 + s, fragment_header(0, 0, 0, 2), kFullPayload);
  }
  bool fresh = true;
  const SenderState& stream = table.hear(kStream, fresh);
  EXPECT_FALSE(fresh) << "the stream's sender was never forgotten";
  EXPECT_EQ(stream.sequence.received(), 50u);
  EXPECT_EQ(stream.sequence.lost(), 0u);
  EXPECT_EQ(table.forgotten(), 5000u - (Table::kMaxSenders - 1));
}

TEST(SenderTable, ThePinnedSenderIsNeverForgottenAndForgottenCountsAreKept) {
  Table table;
  table.pin(7);
  receive(table, 7, fragment_header(0, 0, 0, 2), kFullPayload);  // pinned, never delivered
  receive(table, 8, fragment_header(0, 0, 0, 1), whole_list(0));
  receive(table, 8, fragment_header(10, 1, 0, 1), whole_list(1));  // 9 lost
  receive(table, 8, fragment_header(10, 1, 0, 1), whole_list(1));  // a duplicate
  for (int s = 100; s < 300; ++s) receive(table, s, fragment_header(0, 0, 0, 1), whole_list(0));  // all delivered
  bool fresh = true;
  table.hear(7, fresh);
  EXPECT_FALSE(fresh);
  table.hear(8, fresh);
  EXPECT_TRUE(fresh) << "sender 8, the least recently heard, was forgotten";
  const SenderCounts counts = table.finish();
  EXPECT_EQ(counts.lost, 9u);
  EXPECT_EQ(counts.duplicates, 1u);
  EXPECT_EQ(counts.incomplete, 1u);  // the pinned sender's half message, given up at the end
}

}  // namespace
}  // namespace rcsim::stream
