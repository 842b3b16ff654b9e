// A robot's log (src/io/robot_log.hpp): an MCAP file or a ROS 2 bag directory behind one visit,
// named and sized as the importer checks its counts against; a directory that is neither refused.
#include "io/robot_log.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/input_error.hpp"
#include "io/mcap_writer.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::robot_log::robot_log_test {
namespace {

namespace fs = std::filesystem;
using testing::refusal_of;

class RobotLog : public rcsim::testing::ScratchDirTest {
 protected:
  RobotLog() : ScratchDirTest("robot_log") {}
  // An MCAP file of `n` messages on /a.
  std::string mcap_bytes(int n) const {
    std::ostringstream out;
    mcap::Writer writer(out, "ros2");
    const auto channel = writer.add_channel("/a", "cdr", writer.add_schema("std_msgs/msg/String", "ros2msg", ""));
    for (int i = 0; i < n; ++i) writer.write_message(channel, static_cast<std::uint64_t>(100 + i), std::string("m").append(std::to_string(i)));
    writer.finish();
    return out.str();
  }
};

TEST_F(RobotLog, AnMcapFileAndABagOfMcapFilesReadAlike) {
  const fs::path file = write_file("drive.mcap", mcap_bytes(2));
  const Log log(file);
  EXPECT_EQ(log.name(), "drive");
  EXPECT_EQ(log.kind(), "MCAP log");
  EXPECT_EQ(log.bytes(), fs::file_size(file));
  std::vector<std::string> seen;
  const LogSummary summary = log.for_each_message([&](const LogMessage& m) {
    seen.push_back(std::string(m.topic) + " " + std::string(m.schema_name) + " " + std::string(m.encoding) + " " +
                   std::to_string(m.log_time_ns) + " " + std::string(m.data));
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"/a std_msgs/msg/String cdr 100 m0", "/a std_msgs/msg/String cdr 101 m1"}));
  EXPECT_EQ(summary.profile, "ros2");
  EXPECT_EQ(summary.topics, (std::set<std::string>{"/a"}));
  EXPECT_TRUE(summary.warnings.empty());
  // The same messages split over a bag's two MCAP files, the second cut short (a recorder killed).
  fs::create_directories(dir_ / "bag");
  write_file("bag/part_0.mcap", mcap_bytes(2));
  const std::string second = mcap_bytes(3);
  write_file("bag/part_1.mcap", second.substr(0, second.size() - 40));
  write_file("bag/metadata.yaml",
             "rosbag2_bagfile_information:\n  version: 8\n  storage_identifier: mcap\n  relative_file_paths:\n    - part_0.mcap\n    - part_1.mcap\n");
  const Log bag(dir_ / "bag/");
  EXPECT_EQ(bag.name(), "bag");
  EXPECT_EQ(bag.kind(), "rosbag2 bag (mcap, 2 files)");
  EXPECT_EQ(bag.bytes(), fs::file_size(dir_ / "bag/part_0.mcap") + fs::file_size(dir_ / "bag/part_1.mcap"));
  int messages = 0;
  const LogSummary parts = bag.for_each_message([&](const LogMessage&) { ++messages; });
  EXPECT_EQ(messages, 5);
  ASSERT_EQ(parts.warnings.size(), 1u);
  EXPECT_NE(parts.warnings[0].find("part_1.mcap: no footer"), std::string::npos) << parts.warnings[0];
}

TEST_F(RobotLog, ADirectoryWithoutMetadataIsNoLog) {
  fs::create_directories(dir_ / "empty");
  EXPECT_NE(refusal_of([&] { Log log(dir_ / "empty"); }).find("a directory without a metadata.yaml: neither an MCAP log nor a ROS 2 bag"),
            std::string::npos);
}

}  // namespace
}  // namespace rcsim::robot_log::robot_log_test
