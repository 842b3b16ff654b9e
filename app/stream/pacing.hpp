#pragma once
// When each cycle leaves: absolute deadlines on a steady clock, computed from one anchor
//   deadline(t_s) = anchor_wall + (t_s − anchor_t_s) / speed,
// never from the previous send, so that a slow cycle (or a slow send) does not shift the schedule
// of the cycles after it. Pausing, resuming and seeking re-anchor at the next cycle sent.
//
// The pacer is pure logic on time points handed in by the caller: the streamer passes
// steady_clock::now(), the tests pass a clock of their own.
#include <chrono>
#include <cstdint>
#include <vector>

namespace rcsim::stream {

using SteadyClock = std::chrono::steady_clock;
using TimePoint = SteadyClock::time_point;

class Pacer {
 public:
  struct Options {
    double speed = 1.0;  // scene seconds per wall second; 0 = as fast as possible ("max")
    std::chrono::nanoseconds late_tolerance{std::chrono::milliseconds(2)};
    bool start_paused = false;  // stepped mode: nothing leaves without a STEP
  };
  enum class Action : std::uint8_t { send, wait, hold };
  struct Decision {
    Action action = Action::hold;
    TimePoint at{};  // for wait: the deadline
  };
  struct SendRecord {
    bool paced = false;  // false for max speed and for stepped cycles (no deadline)
    std::chrono::nanoseconds lateness{0};
    bool late = false;
  };

  explicit Pacer(const Options& options);

  // What to do with the next cycle (source time t_s) at `now`.
  Decision decide(TimePoint now, double t_s);
  // The cycle at t_s has left at `sent`.
  SendRecord on_sent(TimePoint sent, double t_s);
  TimePoint deadline(double t_s) const;

  void pause();
  void resume();
  void step(std::uint32_t cycles);  // while paused: let this many cycles leave
  void reanchor() { anchored_ = false; }  // after a seek

  bool paused() const { return paused_; }
  bool max_speed() const { return speed_ <= 0.0; }
  std::uint32_t step_credits() const { return credits_; }

 private:
  double speed_;
  std::chrono::nanoseconds tolerance_;
  bool paused_;
  std::uint32_t credits_ = 0;
  bool anchored_ = false;
  TimePoint anchor_wall_{};
  double anchor_t_s_ = 0.0;
};

// Distribution of send lateness (send time − deadline) over the paced cycles.
class LatenessStats {
 public:
  void add(const Pacer::SendRecord& record);
  std::uint64_t paced() const { return lateness_us_.size(); }
  std::uint64_t late() const { return late_; }
  // The p-quantile (0..1) of lateness in ms (nearest rank); 0 without samples.
  double quantile_ms(double p) const;
  double max_ms() const;

 private:
  mutable std::vector<float> lateness_us_;
  mutable bool sorted_ = true;
  std::uint64_t late_ = 0;
};

}  // namespace rcsim::stream
