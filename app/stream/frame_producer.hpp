#pragma once
// Simulation decoupled from sending: a thread runs the cycle source ahead of the schedule into a
// bounded queue, so that one slow cycle is absorbed by the queue instead of shifting the send
// times of the cycles after it. The sender takes frames without blocking.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "stream/cycle_source.hpp"

namespace rcsim::stream {

class FrameProducer {
 public:
  // `on_ready` is called from the producer thread when a frame (or the end) becomes available
  // after try_pop() found nothing; it must only hand the news over (post to the sender's loop).
  FrameProducer(CycleSource& source, std::size_t capacity, std::function<void()> on_ready);
  ~FrameProducer();
  FrameProducer(const FrameProducer&) = delete;
  FrameProducer& operator=(const FrameProducer&) = delete;

  void start(int first_cycle);
  // The next frame, if ready. Rethrows an error of the source (bad input found while running)
  // once the frames produced before it have been taken.
  std::optional<CycleFrame> try_pop();
  // Every cycle up to the end has been produced and taken.
  bool finished();
  // Drops what is queued; the next frame is `cycle` (re-running the simulation as needed).
  void seek(int cycle);
  void stop();

 private:
  void run();

  CycleSource& source_;
  std::size_t capacity_;
  std::function<void()> on_ready_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<CycleFrame> queue_;
  std::uint64_t generation_ = 0;
  std::optional<int> seek_to_;
  bool done_ = false;     // the current generation reached the end
  bool waiting_ = false;  // the consumer found the queue empty and wants to hear
  bool stop_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace rcsim::stream
