#pragma once
// A long fit on a terminal: a progress line with the evaluations, the best objective so far and
// an ETA, redrawn every 2 s by a ticker thread (so also while one evaluation takes longer), and an
// interrupt (Ctrl-C, SIGINT) that asks the fit to stop with its best so far instead of losing it.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "replay/calibrate/bounded_search.hpp"

namespace rcsim::cli {

// Set by SIGINT while a FitInterrupt lives; the previous handler is restored after.
// A fit stopped by SIGINT after writing its best so far, marked partial: exit status 130, as a
// shell reports a command ended by Ctrl-C.
class FitInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
inline constexpr int kExitInterrupted = 130;

class FitInterrupt {
 public:
  FitInterrupt();
  ~FitInterrupt();
  FitInterrupt(const FitInterrupt&) = delete;
  FitInterrupt& operator=(const FitInterrupt&) = delete;
  const std::atomic<bool>* flag() const;
  bool interrupted() const;

 private:
  void (*previous_)(int);
};

class FitProgress {
 public:
  // Draws nothing unless standard error is a terminal.
  explicit FitProgress(std::string label);
  ~FitProgress();
  FitProgress(const FitProgress&) = delete;
  FitProgress& operator=(const FitProgress&) = delete;
  void update(const replay::SearchProgress& progress);

 private:
  void draw();
  std::string label_;
  bool terminal_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  replay::SearchProgress last_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::thread ticker_;
};

}  // namespace rcsim::cli
