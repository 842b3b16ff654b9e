// The listener's closing line (app/stream/listener.cpp, ListenSummary::line): a stream that began
// before the listener did says how many of its datagrams came before the first one received,
// apart from the lost ones; a listener that saw it from the start says nothing of the kind.
#include "stream/listener.hpp"

#include <gtest/gtest.h>

#include <string>

#include "stream/reassembly.hpp"

namespace rcsim::stream::listener_summary_test {

ListenSummary ended_after(std::uint64_t datagrams_sent, std::uint64_t before_first) {
  ListenSummary s;
  s.datagrams = datagrams_sent - before_first;
  s.end_received = true;
  s.end.datagrams_sent = datagrams_sent - 1;  // the END's own sequence: those before it
  s.end.cycles_sent = 101;
  s.sent_before_first = before_first;
  return s;
}

TEST(ListenerSummary, DatagramsSentBeforeTheListenerStartedAreNamedApartFromLoss) {
  // 203 sent, the first two before the listener listened: 201 received, 0 lost.
  const std::string late = ended_after(203, 2).line();
  EXPECT_NE(late.find("0 lost"), std::string::npos) << late;
  EXPECT_NE(late.find("; end of stream: the sender sent 203 datagrams, 101 cycles, 2 of the datagrams before the first one "
                      "received (the listener started after the stream)"),
            std::string::npos)
      << late;
  const std::string whole = ended_after(203, 0).line();
  EXPECT_EQ(whole.find("before the first one received"), std::string::npos) << whole;
}

TEST(ListenerSummary, APassiveTrackerCountsFromTheFirstNumberItSeesASubscriptionFromZero) {
  // What sent_before_first is read from: the first number seen by a listener that joined (2), or
  // 0 for a subscription, whose stream is known to start there.
  SequenceTracker joined;
  joined.observe(2);
  joined.observe(3);
  EXPECT_EQ(joined.first(), 2u);
  EXPECT_EQ(joined.lost(), 0u);
  SequenceTracker subscribed(std::uint64_t{0});
  subscribed.observe(2);
  EXPECT_EQ(subscribed.first(), 0u);
  EXPECT_EQ(subscribed.lost(), 2u);  // 0 and 1 missing: lost, not before the start
}

}  // namespace rcsim::stream::listener_summary_test
