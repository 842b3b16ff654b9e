#include "stream/frame_producer.hpp"

#include <algorithm>
#include <utility>

namespace rcsim::stream {

FrameProducer::FrameProducer(CycleSource& source, std::size_t capacity, std::function<void()> on_ready)
    : source_(source), capacity_(std::max<std::size_t>(1, capacity)), on_ready_(std::move(on_ready)) {}

FrameProducer::~FrameProducer() { stop(); }

void FrameProducer::start(int first_cycle) {
  {
    std::lock_guard lock(mutex_);
    seek_to_ = first_cycle;
  }
  thread_ = std::thread([this] { run(); });
}

void FrameProducer::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::optional<CycleFrame> FrameProducer::try_pop() {
  std::optional<CycleFrame> frame;
  {
    std::lock_guard lock(mutex_);
    if (queue_.empty()) {
      // The source's error in its place: after the frames produced before it.
      if (error_) std::rethrow_exception(error_);
      waiting_ = true;
      return frame;
    }
    frame = std::move(queue_.front());
    queue_.pop_front();
  }
  wake_.notify_all();
  return frame;
}

bool FrameProducer::finished() {
  std::lock_guard lock(mutex_);
  return done_ && queue_.empty() && !seek_to_;
}

void FrameProducer::seek(int cycle) {
  {
    std::lock_guard lock(mutex_);
    queue_.clear();
    ++generation_;
    seek_to_ = cycle;
    done_ = false;
  }
  wake_.notify_all();
}

void FrameProducer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || seek_to_ || (!done_ && queue_.size() < capacity_); });
    if (stop_) return;
    const std::uint64_t generation = generation_;
    const std::optional<int> seek_to = std::exchange(seek_to_, std::nullopt);
    lock.unlock();
    // The source is touched by this thread only.
    std::optional<CycleFrame> frame;
    bool end = false;
    std::exception_ptr error;
    try {
      if (seek_to) source_.seek(*seek_to);
      if (source_.next_cycle() >= source_.cycle_count()) end = true;
      else frame = source_.produce();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (generation != generation_) continue;  // a seek came in meanwhile: this frame is stale
    if (error) {
      error_ = error;
      done_ = true;
    } else if (end) {
      done_ = true;
    } else {
      frame->generation = generation;
      queue_.push_back(std::move(*frame));
    }
    if (std::exchange(waiting_, false)) {
      lock.unlock();
      on_ready_();
      lock.lock();
    }
  }
}

}  // namespace rcsim::stream
