// Child processes of rcsim campaign (app/cli/child_process.cpp): started from argument vectors,
// never a shell, so a name with spaces or quotes reaches the child as it is; output captured or
// appended to a log; the exit status or 128 + the signal that ended the child.
#include "app/cli/child_process.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scratch_dir.hpp"

namespace rcsim::child_process_test {

class ChildProcess : public rcsim::testing::ScratchDirTest {
 protected:
  ChildProcess() : ScratchDirTest("child_process") {}
};

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(ChildProcess, ArgumentsReachTheChildAsTheyAreWithoutAShell) {
  std::string out;
  // A shell would expand $HOME and split at the spaces; printf gets one argument each.
  EXPECT_EQ(cli::run_captured({"printf", "%s|", "a b", "$HOME", "'q'; rm -rf x"}, out), 0);
  EXPECT_EQ(out, "a b|$HOME|'q'; rm -rf x|");
}

TEST_F(ChildProcess, TheExitStatusOrOneHundredTwentyEightPlusTheSignalIsReturned) {
  std::string out;
  EXPECT_EQ(cli::run_captured({"sh", "-c", "exit 3"}, out), 3);
  EXPECT_EQ(cli::run_captured({"sh", "-c", "kill -9 $$"}, out), 128 + 9);
  EXPECT_EQ(cli::wait_for(cli::spawn_logged({"true"}, dir_ / "log")), 0);
}

TEST_F(ChildProcess, BothOutputsAreAppendedToTheLog) {
  const auto log = dir_ / "shard.log";
  std::ofstream(log) << "earlier\n";
  const pid_t pid = cli::spawn_logged({"sh", "-c", "echo out; echo err >&2"}, log);
  EXPECT_EQ(cli::wait_for(pid), 0);
  EXPECT_EQ(file_text(log), "earlier\nout\nerr\n");
}

TEST_F(ChildProcess, AProgramThatDoesNotExistIsRefusedNamingIt) {
  std::string out;
  try {
    cli::run_captured({"rcsim-no-such-program-here"}, out);
    FAIL() << "started a program that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot start rcsim-no-such-program-here"), std::string::npos) << e.what();
  }
}

TEST_F(ChildProcess, ThisExecutableIsTheRunningProgram) {
  const auto self = cli::this_executable();
  EXPECT_TRUE(self.is_absolute()) << self;
  EXPECT_TRUE(std::filesystem::is_regular_file(self)) << self;
  EXPECT_NE(self.filename().string().find("test"), std::string::npos) << self;  // rcsim_tests, not rcsim
}

}  // namespace rcsim::child_process_test
