// A ROS 2 bag's metadata.yaml and SQLite storage (src/io/rosbag2_reader.hpp), written here by hand
// in Humble's layout: the files in order, the messages in the order recorded with their topic's
// type and format, and what is no bag refused naming the file and the field or table.
#include "io/rosbag2_reader.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::rosbag2::rosbag2_reader_test {
namespace {

namespace fs = std::filesystem;
using testing::refusal_of;

class Rosbag2Reader : public rcsim::testing::ScratchDirTest {
 protected:
  Rosbag2Reader() : ScratchDirTest("rosbag2_reader") {}
  // metadata.yaml naming `files`, with `extra` lines inside rosbag2_bagfile_information.
  void metadata(const std::vector<std::string>& files, const std::string& storage = "sqlite3", const std::string& extra = "") {
    std::string yaml = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: " + storage + "\n" + extra +
                       "  relative_file_paths:\n";
    for (const std::string& f : files) yaml += "    - " + f + "\n";
    write_file("bag/metadata.yaml", yaml);
  }
  // A storage file in Humble's layout: two topics, messages (topic id, timestamp, data) in order.
  fs::path db3(const std::string& name, const std::vector<std::tuple<int, std::int64_t, std::string>>& messages) {
    const fs::path path = dir_ / "bag" / name;
    SQLite::Database db(path.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db.exec("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL, "
            "offered_qos_profiles TEXT NOT NULL)");
    db.exec("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL)");
    db.exec("INSERT INTO topics VALUES (1, '/odom', 'nav_msgs/msg/Odometry', 'cdr', ''), (2, '/tf', 'tf2_msgs/msg/TFMessage', 'cdr', '')");
    SQLite::Statement insert(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)");
    for (const auto& [topic, t_ns, data] : messages) {
      insert.bind(1, topic), insert.bind(2, static_cast<std::int64_t>(t_ns)), insert.bind(3, data.data(), static_cast<int>(data.size()));
      insert.exec(), insert.reset();
    }
    return path;
  }
};

TEST_F(Rosbag2Reader, TheFilesInOrderAndTheMessagesAsRecorded) {
  fs::create_directories(dir_ / "bag");
  db3("b_0.db3", {{1, 300, std::string("a\0b", 3)}, {2, 100, "tf"}});
  db3("b_1.db3", {{1, 400, "c"}});
  // Older rosbag2 wrote the bag's own directory in front of each file's name.
  metadata({"b_0.db3", "bag/b_1.db3"});
  EXPECT_TRUE(is_bag_directory(dir_ / "bag"));
  EXPECT_FALSE(is_bag_directory(dir_ / "bag" / "b_0.db3"));
  const BagMetadata bag = read_bag_metadata(dir_ / "bag");
  EXPECT_EQ(bag.storage, "sqlite3");
  EXPECT_EQ(bag.version, 5);
  ASSERT_EQ(bag.files.size(), 2u);
  EXPECT_EQ(bag.files[1], dir_ / "bag" / "b_1.db3");
  std::vector<std::string> seen, topics;
  for (const fs::path& f : bag.files) {
    for_each_sqlite_message(
        f, [&](const SqliteMessage& m) { seen.push_back(std::string(m.topic) + " " + std::string(m.type) + " " + std::string(m.serialization_format) + " " + std::to_string(m.timestamp_ns) + " " + std::string(m.data)); },
        &topics);
  }
  // The rows' order, not the stamps': the reorder window of the importer puts them in order.
  EXPECT_EQ(seen, (std::vector<std::string>{"/odom nav_msgs/msg/Odometry cdr 300 " + std::string("a\0b", 3), "/tf tf2_msgs/msg/TFMessage cdr 100 tf",
                                            "/odom nav_msgs/msg/Odometry cdr 400 c"}));
  EXPECT_EQ(topics, (std::vector<std::string>{"/odom", "/tf", "/odom", "/tf"}));
}

TEST_F(Rosbag2Reader, WhatIsNoBagIsRefusedNamingTheFieldOrTable) {
  fs::create_directories(dir_ / "bag");
  db3("b_0.db3", {});
  const auto refused = [&] { return refusal_of([&] { read_bag_metadata(dir_ / "bag"); }); };
  metadata({"b_0.db3"}, "sqlite3", "  compression_mode: FILE\n  compression_format: zstd\n");
  EXPECT_NE(refused().find("rosbag2_bagfile_information.compression_mode: 'FILE': a compressed bag"), std::string::npos) << refused();
  metadata({"b_0.db3"}, "rosbag_v2");
  EXPECT_NE(refused().find("storage_identifier: 'rosbag_v2': rcsim reads bags stored as sqlite3 or mcap"), std::string::npos);
  metadata({"/etc/passwd"});
  EXPECT_NE(refused().find("relative_file_paths[0]: '/etc/passwd' is no path inside the bag"), std::string::npos) << refused();
  metadata({"b_1.db3"});
  EXPECT_NE(refused().find("relative_file_paths[0]: 'b_1.db3' is not a file in"), std::string::npos) << refused();
  metadata({});
  EXPECT_NE(refused().find("relative_file_paths: missing or empty"), std::string::npos) << refused();
  write_file("bag/metadata.yaml", "rosbag2_bagfile_information: [\n");
  EXPECT_NE(refused().find("metadata.yaml: line "), std::string::npos) << refused();
  write_file("bag/metadata.yaml", "something_else: 1\n");
  EXPECT_NE(refused().find("rosbag2_bagfile_information: missing: not a rosbag2 bag's metadata"), std::string::npos) << refused();
  // A storage file that is no SQLite database, and one without a messages table.
  const fs::path text = write_file("bag/text.db3", "SQLite format 2, not quite");
  EXPECT_NE(refusal_of([&] { for_each_sqlite_message(text, [](const SqliteMessage&) {}); }).find("text.db3: table topics: not a rosbag2 SQLite storage file"),
            std::string::npos);
  {
    SQLite::Database db((dir_ / "bag" / "topics_only.db3").string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db.exec("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, serialization_format TEXT)");
  }
  EXPECT_NE(refusal_of([&] { for_each_sqlite_message(dir_ / "bag" / "topics_only.db3", [](const SqliteMessage&) {}); })
                .find("topics_only.db3: table messages: not a rosbag2 SQLite storage file"),
            std::string::npos);
}

}  // namespace
}  // namespace rcsim::rosbag2::rosbag2_reader_test
