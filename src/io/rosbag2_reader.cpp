#include "io/rosbag2_reader.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <map>
#include <yaml-cpp/yaml.h>

#include "common/input_error.hpp"
#include "common/text_file.hpp"

namespace rcsim::rosbag2 {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxBagFiles = 100'000;

// A scalar of the metadata, refused naming its key path and line where it is missing or no scalar.
std::string scalar(const YAML::Node& node, const std::string& file, const std::string& key) {
  if (!node || !node.IsScalar()) throw InputError(file, key, "missing or not a single value");
  return node.as<std::string>();
}

// A storage file's path as metadata.yaml gives it: relative to the bag (older rosbag2 wrote it
// with the bag's own directory name in front); never absolute, never up through "..".
fs::path bag_file(const fs::path& dir, const std::string& file, const std::string& key, const std::string& name) {
  const fs::path relative(name);
  if (name.empty() || relative.is_absolute()) throw InputError(file, key, fmt::format("'{}' is no path inside the bag", name));
  for (const fs::path& part : relative) {
    if (part == "..") throw InputError(file, key, fmt::format("'{}' leads out of the bag through '..'", name));
  }
  for (const fs::path& candidate : {dir / relative, dir / relative.filename()}) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(candidate, ec))) return candidate;
  }
  throw InputError(file, key, fmt::format("'{}' is not a file in {}", name, dir.string()));
}

}  // namespace

bool is_bag_directory(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_regular_file(path / "metadata.yaml", ec);
}

BagMetadata read_bag_metadata(const fs::path& dir) {
  const fs::path path = dir / "metadata.yaml";
  const std::string file = path.string();
  BagMetadata bag;
  bag.dir = dir;
  try {
    const YAML::Node root = YAML::Load(read_text_file(path));
    const YAML::Node info = root["rosbag2_bagfile_information"];
    if (!info || !info.IsMap()) throw InputError(file, "rosbag2_bagfile_information", "missing: not a rosbag2 bag's metadata");
    const std::string key = "rosbag2_bagfile_information.";
    bag.version = info["version"] ? info["version"].as<int>() : 0;
    bag.storage = scalar(info["storage_identifier"], file, key + "storage_identifier");
    if (bag.storage != "sqlite3" && bag.storage != "mcap") {
      throw InputError(file, key + "storage_identifier", fmt::format("'{}': rcsim reads bags stored as sqlite3 or mcap", bag.storage));
    }
    if (const YAML::Node mode = info["compression_mode"]; mode && mode.IsScalar() && !mode.as<std::string>().empty()) {
      throw InputError(file, key + "compression_mode",
                       fmt::format("'{}': a compressed bag; decompress it first (`ros2 bag convert` with an output "
                                   "options file that names no compression)", mode.as<std::string>()));
    }
    const YAML::Node files = info["relative_file_paths"];
    if (!files || !files.IsSequence() || files.size() == 0) throw InputError(file, key + "relative_file_paths", "missing or empty");
    if (files.size() > kMaxBagFiles) {
      throw InputError(file, key + "relative_file_paths", fmt::format("{} files: more than {}", files.size(), kMaxBagFiles));
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string at = fmt::format("{}relative_file_paths[{}]", key, i);
      bag.files.push_back(bag_file(dir, file, at, scalar(files[i], file, at)));
    }
  } catch (const YAML::Exception& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1), e.msg);
  }
  return bag;
}

void for_each_sqlite_message(const fs::path& db3, const std::function<void(const SqliteMessage&)>& visit, std::vector<std::string>* topics) {
  const std::string file = db3.string();
  struct Topic {
    std::string name, type, format;
  };
  std::map<std::int64_t, Topic> by_id;
  const char* table = "topics";
  try {
    SQLite::Database db(file, SQLite::OPEN_READONLY);
    SQLite::Statement topic_rows(db, "SELECT id, name, type, serialization_format FROM topics");
    while (topic_rows.executeStep()) {
      Topic t{topic_rows.getColumn(1).getString(), topic_rows.getColumn(2).getString(), topic_rows.getColumn(3).getString()};
      if (topics != nullptr) topics->push_back(t.name);
      by_id[topic_rows.getColumn(0).getInt64()] = std::move(t);
    }
    table = "messages";
    // The rows' order is the order recorded: no sort of the whole bag.
    SQLite::Statement rows(db, "SELECT topic_id, timestamp, data FROM messages ORDER BY rowid");
    while (rows.executeStep()) {
      const std::int64_t topic_id = rows.getColumn(0).getInt64();
      const auto topic = by_id.find(topic_id);
      if (topic == by_id.end()) throw InputError(file, "messages", fmt::format("a message on topic id {}, not in table topics", topic_id));
      const std::int64_t timestamp_ns = rows.getColumn(1).getInt64();
      if (timestamp_ns < 0) throw InputError(file, "messages", fmt::format("a message on '{}' stamped {} ns, before 1970", topic->second.name, timestamp_ns));
      const SQLite::Column data = rows.getColumn(2);
      const auto* bytes = static_cast<const char*>(data.getBlob());
      visit({topic->second.name, topic->second.type, topic->second.format, static_cast<std::uint64_t>(timestamp_ns),
             std::string_view(bytes == nullptr ? "" : bytes, static_cast<std::size_t>(data.getBytes()))});
    }
  } catch (const SQLite::Exception& e) {
    throw InputError(file, std::string("table ") + table, fmt::format("not a rosbag2 SQLite storage file: {}", e.what()));
  }
}

}  // namespace rcsim::rosbag2
