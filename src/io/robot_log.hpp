#pragma once
// A robot's log as `rcsim import --from mcap` reads it: one MCAP file, or a ROS 2 bag directory
// (io/rosbag2_reader: metadata.yaml and its storage files, sqlite3 or mcap, split bags in order).
// Each message is handed on with its topic, its schema's name (a ROS 2 type such as
// "radar_msgs/msg/RadarScan", or "foxglove.PointCloud"), its encoding ("cdr", "json") and its log
// time (an MCAP message's log_time, a bag's receive timestamp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace rcsim::robot_log {

struct LogMessage {
  std::string_view topic, schema_name, encoding;
  std::uint64_t log_time_ns = 0;
  std::string_view data;
};

// What a pass over the log found besides its messages.
struct LogSummary {
  std::string profile, library;         // an MCAP header's (the first file's, for a bag)
  std::set<std::string> topics;         // every topic announced, with messages or not
  std::vector<std::string> warnings;    // e.g. an unfinished MCAP file read up to its last record
};

class Log {
 public:
  // An MCAP file, or a directory holding a rosbag2 metadata.yaml; an InputError otherwise.
  explicit Log(std::filesystem::path path);

  // The file's stem, or the bag directory's name.
  std::string name() const;
  // "MCAP log" or "rosbag2 bag (sqlite3, 2 files)".
  std::string kind() const;
  // The bytes of its file or storage files: what the log's counts are checked against.
  std::uint64_t bytes() const { return bytes_; }

  LogSummary for_each_message(const std::function<void(const LogMessage&)>& visit) const;

 private:
  std::filesystem::path path_;
  bool bag_ = false;
  std::string storage_;
  std::vector<std::filesystem::path> files_;
  std::uint64_t bytes_ = 0;
};

}  // namespace rcsim::robot_log
