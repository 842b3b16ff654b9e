// FrameProducer of app/stream/frame_producer.hpp on a scripted cycle source: every cycle once and
// in order, at most `capacity` frames ahead of the consumer, a seek dropping what is queued, and
// the source's error handed over after the frames produced before it. No timing is asserted: the
// test waits for the producer's on_ready news (or for the source to be called), with a long
// deadline only against a hang.
#include "stream/frame_producer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "stream/cycle_source.hpp"

namespace rcsim::frame_producer_test {

using stream::CycleFrame;
using stream::FrameProducer;

constexpr std::chrono::seconds kHangGuard{30};

// A counter one thread bumps and another waits on.
class Signal {
 public:
  void bump() {
    {
      std::lock_guard lock(mutex_);
      ++count_;
    }
    changed_.notify_all();
  }
  std::uint64_t value() {
    std::lock_guard lock(mutex_);
    return count_;
  }
  // Until the count is past `seen`; false on the hang guard.
  bool wait_past(std::uint64_t seen) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, kHangGuard, [&] { return count_ > seen; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t count_ = 0;
};

// Cycles 0..cycle_count-1 with t_s = cycle / 10; throws at `fail_at` if given. Every produce()
// bumps `produced`.
class ScriptedSource : public stream::CycleSource {
 public:
  ScriptedSource(int cycle_count, std::optional<int> fail_at = std::nullopt)
      : cycle_count_(cycle_count), fail_at_(fail_at) {}
  int cycle_count() const override { return cycle_count_; }
  std::uint32_t available_messages() const override { return 0; }
  const std::vector<std::string>& sensor_ids() const override { return ids_; }
  void seek(int cycle) override { next_ = cycle; }
  int next_cycle() const override { return next_; }
  CycleFrame produce() override {
    if (fail_at_ && next_ == *fail_at_) throw std::runtime_error("cycle " + std::to_string(next_) + ": bad input");
    CycleFrame frame;
    frame.cycle = static_cast<std::uint32_t>(next_);
    frame.t_s = 0.1 * next_;
    ++next_;
    produced.bump();
    return frame;
  }
  Signal produced;

 private:
  int cycle_count_;
  std::optional<int> fail_at_;
  std::vector<std::string> ids_;
  int next_ = 0;
};

// Takes frames into `frames` until the producer has finished or `limit` frames are taken,
// waiting for the on_ready news when none is ready (the count is read before try_pop, so no news
// is missed). What try_pop throws goes to the caller, the frames taken before it kept.
void take_into(std::vector<CycleFrame>& frames, FrameProducer& producer, Signal& ready, std::size_t limit = 1000) {
  while (frames.size() < limit) {
    const std::uint64_t seen = ready.value();
    if (std::optional<CycleFrame> frame = producer.try_pop()) {
      frames.push_back(std::move(*frame));
      continue;
    }
    if (producer.finished()) break;
    if (!ready.wait_past(seen)) {
      ADD_FAILURE() << "no frame and no end within " << kHangGuard.count() << " s";
      break;
    }
  }
}

std::vector<CycleFrame> take(FrameProducer& producer, Signal& ready, std::size_t limit = 1000) {
  std::vector<CycleFrame> frames;
  take_into(frames, producer, ready, limit);
  return frames;
}

TEST(StreamFrameProducer, EveryCycleOnceInOrderThenFinished) {
  ScriptedSource source(6);
  Signal ready;
  FrameProducer producer(source, 2, [&ready] { ready.bump(); });
  producer.start(1);  // from cycle 1
  const std::vector<CycleFrame> frames = take(producer, ready);
  ASSERT_EQ(frames.size(), 5u);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].cycle, k + 1);
    EXPECT_DOUBLE_EQ(frames[k].t_s, 0.1 * static_cast<double>(k + 1));
    EXPECT_EQ(frames[k].generation, 0u);
  }
  EXPECT_TRUE(producer.finished());
  EXPECT_FALSE(producer.try_pop().has_value());
}

TEST(StreamFrameProducer, RunsAtMostCapacityFramesAhead) {
  for (const std::size_t capacity : {std::size_t{0}, std::size_t{3}}) {
    const std::uint64_t expected = capacity == 0 ? 1 : capacity;  // a capacity of 0 counts as 1
    ScriptedSource source(10);
    FrameProducer producer(source, capacity, [] {});
    producer.start(0);
    // Once the queue is full nothing is taken, so the producer must wait: after stop() (which
    // joins its thread) the source has made exactly `capacity` frames.
    ASSERT_TRUE(source.produced.wait_past(expected - 1)) << capacity;
    producer.stop();
    EXPECT_EQ(source.produced.value(), expected) << capacity;
    for (std::uint64_t k = 0; k < expected; ++k) EXPECT_EQ(producer.try_pop()->cycle, k) << capacity;
    EXPECT_FALSE(producer.finished());
  }
}

TEST(StreamFrameProducer, SeekDropsTheQueueAndRestartsThere) {
  ScriptedSource source(10);
  Signal ready;
  FrameProducer producer(source, 3, [&ready] { ready.bump(); });
  producer.start(0);
  const std::vector<CycleFrame> before = take(producer, ready, 1);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].cycle, 0u);
  producer.seek(7);
  EXPECT_FALSE(producer.finished());  // the seek is pending
  const std::vector<CycleFrame> after = take(producer, ready);
  ASSERT_EQ(after.size(), 3u);
  for (std::size_t k = 0; k < after.size(); ++k) {
    EXPECT_EQ(after[k].cycle, 7 + k);
    EXPECT_EQ(after[k].generation, 1u);  // nothing of before the seek
  }
  // Back to the start: all ten again, generation 2.
  producer.seek(0);
  const std::vector<CycleFrame> again = take(producer, ready);
  ASSERT_EQ(again.size(), 10u);
  EXPECT_EQ(again.front().cycle, 0u);
  EXPECT_EQ(again.back().cycle, 9u);
  EXPECT_EQ(again.back().generation, 2u);
}

TEST(StreamFrameProducer, SourceErrorComesAfterTheFramesBeforeIt) {
  ScriptedSource source(10, 3);
  Signal ready;
  FrameProducer producer(source, 8, [&ready] { ready.bump(); });
  producer.start(0);
  std::vector<CycleFrame> frames;
  std::string error;
  try {
    take_into(frames, producer, ready);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  EXPECT_EQ(error, "cycle 3: bad input");
  ASSERT_EQ(frames.size(), 3u);
  for (std::size_t k = 0; k < frames.size(); ++k) EXPECT_EQ(frames[k].cycle, k);
  // The error stays: asked again, it is thrown again.
  EXPECT_THROW(producer.try_pop(), std::runtime_error);
}

}  // namespace rcsim::frame_producer_test
