// Every writer of the command line refuses an output path that is a device, a pipe or a symbolic
// link before it writes anything, and leaves the node as it was (docs/hardening.md: an output is
// replaced by rename, which would replace the node itself; as root, -o /dev/null destroyed it).
// A FIFO stands in for a device node: it needs no privilege, and a rename replaces it the same way.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kPathsSource = RCSIM_SOURCE_DIR;
const std::string kPathsScene = kPathsSource + "/docs/examples/standstill_1m.json";  // 2 s: synth is quick
const std::string kPathsRecording = kPathsSource + "/recordings_synthetic/close_front";

class OutputPaths : public rcsim::testing::ScratchDirTest {
 protected:
  OutputPaths() : ScratchDirTest("output_paths") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    fifo_ = dir_ / "node";
    ASSERT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
    target_ = dir_ / "precious.txt";
    std::ofstream(target_) << "keep me\n";
    link_ = dir_ / "link";
    fs::create_symlink(target_, link_);
  }
  // Runs `rcsim ARGS` with NODE replaced by the FIFO, then by the symbolic link: refused, exit
  // status 2, the message naming the path, and both nodes as they were.
  void expect_refused(const std::string& args) {
    for (const fs::path& node : {fifo_, link_}) {
      std::string command = args;
      command.replace(command.find("NODE"), 4, node.string());
      const auto r = rcsim::testing::run_rcsim(command);
      EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.output;
      EXPECT_NE(r.output.find(node.string() + ":"), std::string::npos) << command << "\n" << r.output;
      EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo_))) << command << ": the FIFO was replaced";
      EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link_))) << command << ": the link was replaced";
      EXPECT_EQ(rcsim::testing::read_file(target_), "keep me\n") << command << ": written through the link";
    }
  }
  fs::path fifo_, target_, link_;
};

TEST_F(OutputPaths, SimulateAndSynthRefuseANodeOrALink) {
  expect_refused("simulate " + kPathsScene + " -o NODE");
  expect_refused("synth " + kPathsScene + " -o NODE");
}

TEST_F(OutputPaths, ReplayReportAndMergeRefuseANodeOrALinkBeforeTheyWrite) {
  const fs::path db = dir_ / "report.sqlite";
  ASSERT_EQ(rcsim::testing::run_rcsim("replay " + kPathsRecording + " --db " + db.string()).exit_code, 0);
  expect_refused("report " + db.string() + " -o NODE");
  expect_refused("replay " + kPathsRecording + " --db " + db.string() + " --junit NODE");
  expect_refused("merge " + db.string() + " -o " + (dir_ / "merged.sqlite").string() + " --junit NODE");
  expect_refused("merge " + db.string() + " -o NODE");
  // Refused before the work: neither a second run nor a merged report was written.
  EXPECT_FALSE(fs::exists(dir_ / "merged.sqlite"));
  const auto runs = rcsim::testing::run_rcsim("report " + db.string() + " -o " + (dir_ / "r.html").string());
  EXPECT_EQ(runs.exit_code, 0) << runs.output;
}

TEST_F(OutputPaths, ADatabaseThatIsNoRegularFileIsRefusedWithoutAJournalBesideIt) {
  const auto r = rcsim::testing::run_rcsim("replay " + kPathsRecording + " --db " + fifo_.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fifo_.string() + ": not a regular file"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(fifo_.string() + "-journal"));
  EXPECT_FALSE(fs::exists(fifo_.string() + "-wal"));
}

TEST_F(OutputPaths, ListenRefusesANodeOrALinkBeforeItListens) {
  expect_refused("listen --port 0 --idle-timeout-s 0.1 -o NODE");
  expect_refused("listen --port 0 --idle-timeout-s 0.1 --truth-output NODE");
  expect_refused("listen --port 0 --idle-timeout-s 0.1 --pcap NODE");
}

TEST_F(OutputPaths, ARecordingIsNotWrittenOverAnotherDirectory) {
  // Refused before the simulation (write_recording's own test shows what is replaced).
  const fs::path other = dir_ / "photos";
  fs::create_directories(other);
  std::ofstream(other / "holiday.jpg") << "not a recording";
  const auto r = rcsim::testing::run_rcsim("synth " + kPathsScene + " -o " + other.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("without a recording.json"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(other / "holiday.jpg"));
}

TEST_F(OutputPaths, AMergeIntoASymbolicLinkLoopIsRefusedAsALink) {
  const fs::path db = dir_ / "report.sqlite";
  ASSERT_EQ(rcsim::testing::run_rcsim("replay " + kPathsRecording + " --db " + db.string() + " --store summary").exit_code, 0);
  const fs::path loop = dir_ / "loop.sqlite";
  fs::create_symlink(loop, loop);
  const auto r = rcsim::testing::run_rcsim("merge " + db.string() + " -o " + loop.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is a symbolic link"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("another process"), std::string::npos) << r.output;
}

}  // namespace
