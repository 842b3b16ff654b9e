#include "io/robot_log.hpp"

#include <fmt/format.h>

#include "common/input_error.hpp"
#include "io/mcap_reader.hpp"
#include "io/rosbag2_reader.hpp"

namespace rcsim::robot_log {
namespace {

namespace fs = std::filesystem;

// One MCAP file's messages, its header and topics into `summary`.
void read_mcap(const fs::path& file, const std::function<void(const LogMessage&)>& visit, LogSummary& summary, bool first) {
  mcap::Reader reader(file);
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& channel, const mcap::Schema* schema) {
    visit({channel.topic, schema != nullptr ? std::string_view(schema->name) : std::string_view("(none)"), channel.message_encoding,
           m.log_time_ns, m.data});
  });
  if (first) summary.profile = reader.summary().profile, summary.library = reader.summary().library;
  for (const auto& [id, channel] : reader.channels()) summary.topics.insert(channel.topic);
  if (!reader.warning().empty()) summary.warnings.push_back(reader.warning());
}

}  // namespace

Log::Log(fs::path path) : path_(std::move(path)) {
  std::error_code ec;
  if (rosbag2::is_bag_directory(path_)) {
    const rosbag2::BagMetadata bag = rosbag2::read_bag_metadata(path_);
    bag_ = true, storage_ = bag.storage, files_ = bag.files;
  } else if (fs::is_directory(path_, ec)) {
    throw InputError(path_.string(), "", "a directory without a metadata.yaml: neither an MCAP log nor a ROS 2 bag");
  } else {
    files_ = {path_};
  }
  for (const fs::path& f : files_) {
    const std::uintmax_t size = fs::file_size(f, ec);
    if (ec) throw InputError(f.string(), "", "cannot read its size: " + ec.message());
    bytes_ += size;
  }
}

std::string Log::name() const {
  const fs::path p = path_.has_filename() ? path_ : path_.parent_path();
  return bag_ ? p.filename().string() : p.stem().string();
}

std::string Log::kind() const {
  return bag_ ? fmt::format("rosbag2 bag ({}, {} file{})", storage_, files_.size(), files_.size() == 1 ? "" : "s") : "MCAP log";
}

LogSummary Log::for_each_message(const std::function<void(const LogMessage&)>& visit) const {
  LogSummary summary;
  for (std::size_t i = 0; i < files_.size(); ++i) {
    if (storage_ == "sqlite3") {
      std::vector<std::string> topics;
      rosbag2::for_each_sqlite_message(
          files_[i], [&](const rosbag2::SqliteMessage& m) { visit({m.topic, m.type, m.serialization_format, m.timestamp_ns, m.data}); },
          &topics);
      summary.topics.insert(topics.begin(), topics.end());
    } else {
      read_mcap(files_[i], visit, summary, i == 0);
    }
  }
  return summary;
}

}  // namespace rcsim::robot_log
