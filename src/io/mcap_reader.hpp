#pragma once
// An MCAP reader (mcap.dev/spec, major version 0): checks the magic at both ends and the footer,
// the summary's CRC-32 where the file gives one, and each chunk's; then visits the messages in
// file order, each with its channel and schema, one chunk in memory at a time. A damaged file (a
// bad CRC, a record longer than what is left, a truncated chunk, a message on a channel never
// announced) is refused naming the file, the record and its byte offset. A log without its footer
// (a recorder that stopped before closing it) is read up to its last whole record, and warning()
// says so. Attachments, metadata, indexes and statistics are skipped unread. Chunks may be
// uncompressed or compressed with zstd or lz4 (the LZ4 frame format), decompressed by Debian's
// libzstd and liblz4; another compression is refused, naming it, and so is a chunk inside a chunk
// (the spec's chunks hold schemas, channels and messages). A chunk holds at most 1 GiB, and costs
// the memory its data really decode to, whatever size it claims (schemas/limits.md).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "io/mcap_writer.hpp"

namespace rcsim::mcap {

struct Schema {
  std::uint16_t id = 0;
  std::string name, encoding, data;
};

struct Channel {
  std::uint16_t id = 0, schema_id = 0;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};

struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0, publish_time_ns = 0;
  std::string data;
};

struct FileSummary {
  std::string profile, library;
  std::uint64_t summary_start = 0, summary_offset_start = 0;
  std::uint32_t summary_crc = 0;  // 0: none given
  std::uint64_t chunks = 0, messages = 0;
};

class Reader {
 public:
  // Opens `path`, checks both magics and reads the footer; refuses a file that is no MCAP.
  explicit Reader(const std::filesystem::path& path);

  // Visits every message in file order; the channel and (0 if none) schema are the ones announced
  // before it. Checks the summary's CRC first, each chunk's as it comes.
  using Visit = std::function<void(const Message&, const Channel&, const Schema*)>;
  void for_each_message(const Visit& visit);

  const FileSummary& summary() const { return summary_; }
  // After for_each_message: what a person should know of the read ("" when nothing), e.g. that an
  // unfinished log was read up to its last whole record.
  const std::string& warning() const { return unfinished_warning_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }

 private:
  [[noreturn]] void fail(const std::string& where, std::uint64_t offset, const std::string& what) const;
  void check_summary_crc();
  // A chunk's records from its stored bytes, zstd / lz4 decompressed to exactly `size` bytes (at
  // most 1 GiB), the output growing with what the data decode to; another compression is refused
  // naming the chunk.
  std::string decompressed(std::string_view stored, const std::string& compression, std::uint64_t size,
                           const std::string& where, std::uint64_t offset) const;
  // The records of `bytes`: the file's top level (one record at a time), or a chunk's, which may
  // hold no chunk.
  void read_records(std::string_view bytes, std::uint64_t base_offset, bool in_chunk, const Visit& visit);

  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  FileSummary summary_;
  std::map<std::uint16_t, Channel> channels_;
  std::map<std::uint16_t, Schema> schemas_;
  bool unfinished_ = false;  // no closing magic and footer
  std::string unfinished_warning_;
};

}  // namespace rcsim::mcap
