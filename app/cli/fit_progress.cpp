#include "cli/fit_progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace rcsim::cli {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) { g_interrupted.store(true); }

}  // namespace

FitInterrupt::FitInterrupt() {
  g_interrupted.store(false);
  previous_ = std::signal(SIGINT, on_interrupt);
}

FitInterrupt::~FitInterrupt() { std::signal(SIGINT, previous_ == SIG_ERR ? SIG_DFL : previous_); }

const std::atomic<bool>* FitInterrupt::flag() const { return &g_interrupted; }

bool FitInterrupt::interrupted() const { return g_interrupted.load(); }

FitProgress::FitProgress(std::string label) : label_(std::move(label)), terminal_(isatty(STDERR_FILENO) == 1) {
  if (!terminal_) return;
  ticker_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::seconds(2), [this] { return done_; })) draw();
  });
}

FitProgress::~FitProgress() {
  if (!terminal_) return;
  {
    std::lock_guard lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  ticker_.join();
  std::fputs("\r\033[K", stderr);
}

void FitProgress::update(const replay::SearchProgress& progress) {
  if (!terminal_) return;
  std::lock_guard lock(mutex_);
  last_ = progress;
  draw();
}

// Under the lock.
void FitProgress::draw() {
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string eta = "-";
  if (last_.evaluations > 0) {
    eta = fmt::format("at most {:.0f} s", elapsed_s / last_.evaluations * (last_.max_evaluations - last_.evaluations));
  }
  std::fprintf(stderr, "\r\033[K%s: %d of at most %d evaluations, best objective %.4f, %.0f s, ETA %s (Ctrl-C: stop, keep the best)",
               label_.c_str(), last_.evaluations, last_.max_evaluations, last_.best_objective, elapsed_s, eta.c_str());
  std::fflush(stderr);
}

}  // namespace rcsim::cli
