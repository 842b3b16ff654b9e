#pragma once
// An MCAP writer (the container of ROS 2 bags and Foxglove, mcap.dev/spec, major version 0):
// schemas, channels and timestamped messages, written in chunks (uncompressed, or zstd at level 1:
// a tenth of the size for a replay's JSON at a quarter more time) with a message
// index per channel after each, then a summary (schemas, channels, statistics, chunk indexes and
// the offsets of their groups) and a footer whose CRC-32 covers the summary, so that a reader can
// seek. Messages must come in log-time order within a channel; chunks are cut at 1 MiB.
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rcsim::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// The records' opcodes (mcap.dev/spec, "Records").
enum class Opcode : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  statistics = 0x0B,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

enum class Compression { none, zstd };

class Writer {
 public:
  // Writes the magic and the header record (`profile`: "" or e.g. "ros2"; library "rcsim").
  explicit Writer(std::ostream& out, const std::string& profile = "", Compression compression = Compression::none);
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids from 1, in the order added.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t add_channel(const std::string& topic, const std::string& message_encoding, std::uint16_t schema_id,
                            const std::map<std::string, std::string>& metadata = {});
  void write_message(std::uint16_t channel_id, std::uint64_t log_time_ns, const std::string& data);

  // The last chunk, the data end, the summary and the footer; nothing may follow. Returns the
  // file's size in bytes.
  std::uint64_t finish();

 private:
  struct SchemaRecord {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct ChannelRecord {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
  };
  struct ChunkIndexRecord {
    std::uint64_t start_ns, end_ns, offset, length;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length, size, compressed_size;
  };

  void write_record(Opcode op, const std::string& content);
  void flush_chunk();

  std::ostream& out_;
  Compression compression_;
  std::uint64_t offset_ = 0;  // bytes written so far
  std::vector<SchemaRecord> schemas_;
  std::vector<ChannelRecord> channels_;
  // The open chunk: its records, time span and each channel's (log time, offset in the records).
  std::string chunk_records_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_entries_;
  std::vector<ChunkIndexRecord> chunk_indexes_;
  std::map<std::uint16_t, std::uint64_t> message_counts_;
  std::map<std::uint16_t, std::uint32_t> sequences_;
  std::uint64_t message_count_ = 0, first_ns_ = 0, last_ns_ = 0;
  bool finished_ = false;
};

// Little-endian encoding of the spec's primitive types, appended to `out` (for the writer, the
// reader's tests and the exporters' own message encodings).
void put_u8(std::string& out, std::uint8_t v);
void put_u16(std::string& out, std::uint16_t v);
void put_u32(std::string& out, std::uint32_t v);
void put_u64(std::string& out, std::uint64_t v);
void put_string(std::string& out, const std::string& s);  // uint32 length, bytes
std::uint32_t crc32_of(std::string_view bytes);

}  // namespace rcsim::mcap
