// A long fit's progress line and its Ctrl-C (app/cli/fit_progress.cpp): the line is drawn on a
// terminal only (a pseudo-terminal here), never into a pipe or file; SIGINT sets the fit's stop flag
// while a FitInterrupt lives, and the previous handler is back after it.
#include "app/cli/fit_progress.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <string>

namespace rcsim::fit_progress_test {

// Standard error redirected to `fd` for the life of the object, then restored.
class StderrTo {
 public:
  explicit StderrTo(int fd) : saved_(::dup(STDERR_FILENO)) { ::dup2(fd, STDERR_FILENO); }
  ~StderrTo() {
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
  }
  StderrTo(const StderrTo&) = delete;
  StderrTo& operator=(const StderrTo&) = delete;

 private:
  int saved_;
};

std::string read_available(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) return text;
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

replay::SearchProgress progress_of(int evaluations, int max_evaluations, double best_objective) {
  replay::SearchProgress progress;
  progress.evaluations = evaluations;
  progress.max_evaluations = max_evaluations;
  progress.best_objective = best_objective;
  return progress;
}

TEST(FitProgress, OnATerminalTheLineShowsEvaluationsBestObjectiveAndIsClearedAtTheEnd) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const int terminal = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  ASSERT_GE(terminal, 0);
  {
    StderrTo redirect(terminal);
    cli::FitProgress progress("calibrate");
    progress.update(progress_of(3, 10, 0.12345));
  }
  ::close(terminal);
  ::fcntl(master, F_SETFL, O_NONBLOCK);
  const std::string shown = read_available(master);
  ::close(master);
  EXPECT_NE(shown.find("calibrate: 3 of at most 10 evaluations, best objective 0.1235"), std::string::npos) << shown;
  EXPECT_NE(shown.find("(Ctrl-C: stop, keep the best)"), std::string::npos) << shown;
  // Each drawing starts by clearing the line; the last one clears it for what follows.
  EXPECT_EQ(shown.substr(0, 4), "\r\033[K");
  EXPECT_EQ(shown.substr(shown.size() - 4), "\r\033[K");
}

TEST(FitProgress, IntoAPipeNothingIsDrawn) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  {
    StderrTo redirect(pipe_fds[1]);
    cli::FitProgress progress("calibrate");
    progress.update(progress_of(1, 5, 2.0));
  }
  ::close(pipe_fds[1]);
  EXPECT_EQ(read_available(pipe_fds[0]), "");
  ::close(pipe_fds[0]);
}

int g_previous_handler_calls = 0;
extern "C" void count_previous_handler(int) { ++g_previous_handler_calls; }

TEST(FitProgress, SigintSetsTheStopFlagWhileTheInterruptLivesThenThePreviousHandlerIsBack) {
  const auto before = std::signal(SIGINT, count_previous_handler);
  {
    cli::FitInterrupt interrupt;
    EXPECT_FALSE(interrupt.interrupted());
    EXPECT_FALSE(interrupt.flag()->load());
    std::raise(SIGINT);
    EXPECT_TRUE(interrupt.interrupted());
    EXPECT_TRUE(interrupt.flag()->load());
    EXPECT_EQ(g_previous_handler_calls, 0);
  }
  {
    cli::FitInterrupt again;  // a new fit starts uninterrupted
    EXPECT_FALSE(again.interrupted());
  }
  std::raise(SIGINT);
  EXPECT_EQ(g_previous_handler_calls, 1);
  std::signal(SIGINT, before);
}

}  // namespace rcsim::fit_progress_test
