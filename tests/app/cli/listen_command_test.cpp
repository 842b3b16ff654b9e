// `rcsim listen` and `rcsim stream` as a user runs them: what listen prints over loopback is
// byte-identical to what `rcsim simulate -o` writes; SIGTERM stops cleanly; bad input refused.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <iostream>
#include <thread>

#include "app/stream/stream_test_support.hpp"
#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::stream {
namespace listen_command_test {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

const std::string kBinary = RCSIM_BINARY;
const std::string kScene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/front_approach.json";

class ListenCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::temp_dir("cli"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Runs `rcsim listen` (port 0, read back from its log), then `rcsim stream` to it, paced at
// kLosslessSpeed (a burst at `--speed max` can overflow a descheduled listener's buffer).
// Returns false when the listener itself reports a loss (UDP on a loaded loopback may drop a
// datagram; a lost end-of-stream datagram ends the listener at its idle timeout): the caller
// retries then. Every other failure is an assertion failure here.
bool stream_and_listen(const fs::path& dir, const std::string& format, const std::string& scene, int cycles = 101,
                       int datagrams = 203) {
  const fs::path out = dir / ("listen." + format), log = dir / "listen.err";
  testing::Child listener = testing::spawn(
      {kBinary, "listen", "--port", "0", "--format", format, "--idle-timeout-s", "10", "-o", out.string()}, dir / "listen.out", log);
  EXPECT_GT(listener.pid, 0);
  const std::string port = testing::listening_port(testing::wait_for_text(log, "listening on"));
  EXPECT_FALSE(port.empty()) << testing::read_file(log);
  if (port.empty()) return true;
  const std::string speed = fmt::format("{}", testing::kLosslessSpeed);
  testing::Child streamer = testing::spawn({kBinary, "stream", scene, "--to", "127.0.0.1:" + port, "--speed", speed, "--seed", "11"},
                                           dir / "stream.out", dir / "stream.err");
  EXPECT_EQ(streamer.wait(), 0) << testing::read_file(dir / "stream.err");
  EXPECT_EQ(listener.wait(), 0) << testing::read_file(log);
  const std::string stream_log = testing::read_file(dir / "stream.err");
  EXPECT_NE(stream_log.find(fmt::format("rcsim stream: {} cycles, {} datagrams", cycles, datagrams)), std::string::npos)
      << stream_log;
  const std::string listen_log = testing::read_file(log);
  if (listen_log.find(" 0 lost, ") == std::string::npos || listen_log.find("end of stream: ") == std::string::npos) {
    std::cerr << "the listener reports a loss on loopback; streaming again:\n" << listen_log;
    return false;
  }
  EXPECT_NE(listen_log.find(" 0 lost, 0 duplicates, 0 reordered, 0 incomplete, 0 malformed"), std::string::npos) << listen_log;
  EXPECT_NE(listen_log.find(fmt::format("end of stream: the sender sent {} datagrams", datagrams)), std::string::npos)
      << listen_log;
  return true;
}

TEST_F(ListenCli, PrintsExactlyWhatSimulateWritesCsvAndJsonl) {
  for (const std::string format : {"csv", "jsonl"}) {
    int attempts = 1;
    while (!stream_and_listen(dir_, format, kScene) && attempts < 3) ++attempts;
    const fs::path simulated = dir_ / ("simulate." + format);
    testing::Child simulate = testing::spawn({kBinary, "simulate", kScene, "--seed", "11", "--format", format, "-o", simulated.string()},
                                             dir_ / "simulate.out", dir_ / "simulate.err");
    ASSERT_EQ(simulate.wait(), 0);
    const std::string expected = testing::read_file(simulated);
    EXPECT_GT(expected.size(), 5000u);
    EXPECT_EQ(testing::read_file(dir_ / ("listen." + format)), expected) << format << " after " << attempts << " attempt(s)";
  }
}

// Issue 49: a scene whose radar measures elevation streams its targets' elevations, and the
// listener prints the elevation_rad column exactly as `rcsim simulate` writes it.
TEST_F(ListenCli, PrintsTheElevationColumnOfA3dSceneAsSimulateDoes) {
  const std::string scene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/road_users/pedestrian_crossing.json";
  for (const std::string format : {"csv", "jsonl"}) {
    int attempts = 1;
    while (!stream_and_listen(dir_, format, scene, 31, 106) && attempts < 3) ++attempts;
    const fs::path simulated = dir_ / ("simulate." + format);
    testing::Child simulate = testing::spawn({kBinary, "simulate", scene, "--seed", "11", "--format", format, "-o", simulated.string()},
                                             dir_ / "simulate.out", dir_ / "simulate.err");
    ASSERT_EQ(simulate.wait(), 0);
    const std::string expected = testing::read_file(simulated);
    EXPECT_NE(expected.find("elevation_rad"), std::string::npos);
    EXPECT_EQ(testing::read_file(dir_ / ("listen." + format)), expected) << format << " after " << attempts << " attempt(s)";
  }
}

TEST_F(ListenCli, StreamStopsCleanlyOnSigtermWithAOneLineSummary) {
  testing::Child streamer = testing::spawn({kBinary, "stream", kScene, "--to", "127.0.0.1:9", "--speed", "1"}, dir_ / "out", dir_ / "err");
  testing::wait_for_text(dir_ / "err", "rcsim stream: ");
  std::this_thread::sleep_for(300ms);
  ::kill(streamer.pid, SIGTERM);
  EXPECT_EQ(streamer.wait(), 0);
  const std::string log = testing::read_file(dir_ / "err");
  const std::size_t last = log.rfind("rcsim stream: stopped, ");
  ASSERT_NE(last, std::string::npos) << log;
  const std::string line = log.substr(last);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << "one line";
  for (const char* part : {" cycles, ", " datagrams, ", " bytes, ", " late cycles"}) EXPECT_NE(line.find(part), std::string::npos) << part;
}

TEST_F(ListenCli, BadArgumentsAreRefusedWithAMessage) {
  const auto run = [this](const std::vector<std::string>& args) {
    testing::Child c = testing::spawn(args, dir_ / "out", dir_ / "err");
    const int code = c.wait();
    return std::make_pair(code, testing::read_file(dir_ / "err"));
  };
  auto [code, err] = run({kBinary, "stream", kScene});
  EXPECT_NE(code, 0);
  EXPECT_NE(err.find("--to"), std::string::npos) << err;
  std::tie(code, err) = run({kBinary, "stream", kScene, "--to", "127.0.0.1:5000", "--speed", "0"});
  EXPECT_NE(code, 0);
  EXPECT_NE(err.find("--speed"), std::string::npos) << err;
  std::tie(code, err) = run({kBinary, "stream", kScene, "--to", "127.0.0.1:5000", "--messages", "recorded"});
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--messages"), std::string::npos) << err;
  std::tie(code, err) = run({kBinary, "stream", kScene, "--to", "nohost.invalid:5000"});
  EXPECT_NE(code, 0);
  EXPECT_NE(err.find("nohost.invalid"), std::string::npos) << err;
}

// Issue 21: an error must never lose a capture. The streamer is killed mid-stream; the listener
// subscribed to it hears no answer to its keepalives, ends with that error, and keeps every
// target list received before it in its output file (5 keepalives at 1 s unanswered).
TEST_F(ListenCli, AnErrorKeepsTheCaptureReceivedBeforeIt) {
  testing::Child streamer = testing::spawn({kBinary, "stream", kScene, "--control", "127.0.0.1:0", "--speed", "1"},
                                           dir_ / "stream.out", dir_ / "stream.err");
  const std::string stream_log = testing::wait_for_text(dir_ / "stream.err", "control port ");
  const std::string control = stream_log.substr(stream_log.find("control port ") + 13);
  const fs::path out = dir_ / "capture.csv", log = dir_ / "listen.err";
  testing::Child listener = testing::spawn(
      {kBinary, "listen", "--subscribe", "127.0.0.1:" + control.substr(0, control.find_first_not_of("0123456789")), "-o",
       out.string()},
      dir_ / "listen.out", log);
  std::this_thread::sleep_for(1500ms);  // about 37 of the scene's 101 cycles at real time
  ::kill(streamer.pid, SIGKILL);
  EXPECT_EQ(streamer.wait(), 128 + SIGKILL);
  EXPECT_EQ(listener.wait(30s), 1) << testing::read_file(log);
  const std::string listen_log = testing::read_file(log);
  EXPECT_NE(listen_log.find("the target lists received before the error are in " + out.string()), std::string::npos)
      << listen_log;
  EXPECT_NE(listen_log.find("stopped answering: 5 keepalives unanswered"), std::string::npos) << listen_log;
  const std::string capture = testing::read_file(out);
  const auto rows = std::count(capture.begin(), capture.end(), '\n');
  EXPECT_GT(rows, 20) << capture;  // header and the rows of the cycles streamed before the kill
}

}  // namespace listen_command_test
}  // namespace rcsim::stream

namespace rcsim::listen_command_usage_test {

namespace fs = std::filesystem;
using rcsim::testing::CommandResult;

const std::string kUsageScene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/front_approach.json";

using rcsim::testing::output_has;
CommandResult run_usage(const std::string& args) { return rcsim::testing::run_rcsim_with_timeout(args); }

class ListenCliUsage : public rcsim::testing::ScratchDirTest {
 protected:
  ListenCliUsage() : ScratchDirTest("listen_cli_usage") {}
};

TEST_F(ListenCliUsage, ListenSaysWhyTheTruthOutputHoldsOnlyItsHeader) {
  const fs::path truth = dir_ / "truth.csv";
  const auto idle = run_usage("listen --port 0 --idle-timeout-s 0.2 --truth-output " + truth.string());
  EXPECT_EQ(idle.exit_code, 0) << idle.output;
  EXPECT_TRUE(output_has(idle, "no ground truth arrived, so " + truth.string() + " holds the header only")) << idle.output;
  EXPECT_TRUE(output_has(idle, "--messages simulated,truth")) << idle.output;
  const std::string header = rcsim::testing::read_file(truth);
  EXPECT_EQ(std::count(header.begin(), header.end(), '\n'), 1) << header;

  // With the truth streamed, no hint. The listener's port is read from its log.
  const std::string bin = RCSIM_BINARY, dir = dir_.string();
  const std::string script =
      "cd " + dir + " && (timeout 60 " + bin + " listen --port 0 --idle-timeout-s 10 -o out.csv --truth-output truth.csv "
      "> listen.out 2> listen.err &) && for i in $(seq 200); do grep -q 'listening on' listen.err && break; sleep 0.05; done && "
      "port=$(sed -n 's/.*listening on 127.0.0.1:\\([0-9]*\\).*/\\1/p' listen.err) && timeout 60 " + bin + " stream " +
      kUsageScene + " --to 127.0.0.1:$port --messages simulated,truth --speed 10 2> stream.err && "
      "for i in $(seq 200); do grep -q 'rcsim listen: .*datagrams' listen.err && break; sleep 0.05; done";
  const auto streamed = rcsim::testing::run_shell_command(script);
  ASSERT_EQ(streamed.exit_code, 0) << streamed.output << rcsim::testing::read_file(dir_ / "stream.err");
  const std::string log = rcsim::testing::read_file(dir_ / "listen.err");
  EXPECT_FALSE(log.find("no ground truth arrived") != std::string::npos) << log;
  const std::string rows = rcsim::testing::read_file(truth);
  EXPECT_GT(std::count(rows.begin(), rows.end(), '\n'), 50) << log;
}

}  // namespace rcsim::listen_command_usage_test
