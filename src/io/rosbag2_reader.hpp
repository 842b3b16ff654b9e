#pragma once
// A ROS 2 bag as `ros2 bag record` writes it (rosbag2, Humble and later): a directory holding
// metadata.yaml and its storage files, one or several (`--max-bag-size` splits a bag), each an
// SQLite database (`storage_identifier: sqlite3`, Humble's default, `.db3`) or an MCAP log
// (`mcap`, the default since Iron). Read for `rcsim import --from mcap BAG_DIR`: the metadata with
// yaml-cpp, the SQLite files with Debian's SQLite (read-only), the MCAP files with io/mcap_reader.
// A bag compressed by rosbag2 (`compression_mode` FILE or MESSAGE) is refused, naming how to
// decompress it. Refusals name the file and the field or table.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rcsim::rosbag2 {

// What metadata.yaml says: the storage and its files in order (paths checked to lie in the bag).
struct BagMetadata {
  std::filesystem::path dir;
  std::string storage;  // "sqlite3" or "mcap"
  std::vector<std::filesystem::path> files;
  int version = 0;
};

// True where `path` is a directory holding a metadata.yaml.
bool is_bag_directory(const std::filesystem::path& path);

// metadata.yaml read and checked: at most 100,000 files, each a relative path without "..", that
// exists as a regular file in the bag's directory.
BagMetadata read_bag_metadata(const std::filesystem::path& dir);

// One message of an SQLite storage file: its topic's name, type (e.g. "radar_msgs/msg/RadarScan")
// and serialization format ("cdr"), the time it was received, its bytes (valid during the visit).
struct SqliteMessage {
  std::string_view topic, type, serialization_format;
  std::uint64_t timestamp_ns = 0;
  std::string_view data;
};

// Visits every message of one SQLite storage file in the order it was recorded (its rows' order),
// one row in memory at a time. `topics` receives every topic the file announces, with messages or
// not. A file that is no rosbag2 SQLite storage (no `topics` or `messages` table, a message on a
// topic not announced) is refused naming the file and the table.
void for_each_sqlite_message(const std::filesystem::path& db3, const std::function<void(const SqliteMessage&)>& visit,
                             std::vector<std::string>* topics = nullptr);

}  // namespace rcsim::rosbag2
