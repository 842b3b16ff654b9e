#include "io/mcap_writer.hpp"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <stdexcept>

namespace rcsim::mcap {

namespace {

constexpr std::size_t kChunkBytes = 1 << 20;

std::string string_map(const std::map<std::string, std::string>& m) {
  std::string entries;
  for (const auto& [key, value] : m) put_string(entries, key), put_string(entries, value);
  std::string out;
  put_u32(out, static_cast<std::uint32_t>(entries.size()));
  return out + entries;
}

std::string schema_content(std::uint16_t id, const std::string& name, const std::string& encoding, const std::string& data) {
  std::string c;
  put_u16(c, id);
  put_string(c, name);
  put_string(c, encoding);
  put_string(c, data);  // bytes: uint32 length, then the data
  return c;
}

std::string channel_content(std::uint16_t id, std::uint16_t schema_id, const std::string& topic, const std::string& encoding,
                            const std::map<std::string, std::string>& metadata) {
  std::string c;
  put_u16(c, id);
  put_u16(c, schema_id);
  put_string(c, topic);
  put_string(c, encoding);
  return c + string_map(metadata);
}

std::string record(Opcode op, const std::string& content) {
  std::string r;
  put_u8(r, static_cast<std::uint8_t>(op));
  put_u64(r, content.size());
  return r + content;
}

}  // namespace

void put_u8(std::string& out, std::uint8_t v) { out.push_back(static_cast<char>(v)); }
void put_u16(std::string& out, std::uint16_t v) {
  for (int i = 0; i < 2; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void put_string(std::string& out, const std::string& s) {
  put_u32(out, static_cast<std::uint32_t>(s.size()));
  out += s;
}
std::uint32_t crc32_of(std::string_view bytes) {
  return static_cast<std::uint32_t>(::crc32_z(0L, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

Writer::Writer(std::ostream& out, const std::string& profile, Compression compression) : out_(out), compression_(compression) {
  out_.write(reinterpret_cast<const char*>(kMagic), sizeof kMagic);
  offset_ = sizeof kMagic;
  std::string header;
  put_string(header, profile);
  put_string(header, "rcsim");
  write_record(Opcode::header, header);
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({id, name, encoding, data});
  chunk_records_ += record(Opcode::schema, schema_content(id, name, encoding, data));
  return id;
}

std::uint16_t Writer::add_channel(const std::string& topic, const std::string& message_encoding, std::uint16_t schema_id,
                                  const std::map<std::string, std::string>& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  channels_.push_back({id, schema_id, topic, message_encoding, metadata});
  chunk_records_ += record(Opcode::channel, channel_content(id, schema_id, topic, message_encoding, metadata));
  return id;
}

void Writer::write_message(std::uint16_t channel_id, std::uint64_t log_time_ns, const std::string& data) {
  if (finished_) throw std::logic_error("mcap::Writer: a message after finish()");
  std::string m;
  put_u16(m, channel_id);
  put_u32(m, sequences_[channel_id]++);
  put_u64(m, log_time_ns);
  put_u64(m, log_time_ns);  // publish time: as logged
  m += data;
  if (chunk_index_entries_.empty()) chunk_start_ns_ = chunk_end_ns_ = log_time_ns;
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  chunk_index_entries_[channel_id].emplace_back(log_time_ns, chunk_records_.size());
  chunk_records_ += record(Opcode::message, m);
  first_ns_ = message_count_ == 0 ? log_time_ns : std::min(first_ns_, log_time_ns);
  last_ns_ = std::max(last_ns_, log_time_ns);
  ++message_count_;
  ++message_counts_[channel_id];
  if (chunk_records_.size() >= kChunkBytes) flush_chunk();
}

void Writer::write_record(Opcode op, const std::string& content) {
  const std::string r = record(op, content);
  out_.write(r.data(), static_cast<std::streamsize>(r.size()));
  offset_ += r.size();
}

// The open chunk (uncompressed), then its message indexes, one per channel with messages in it.
void Writer::flush_chunk() {
  if (chunk_records_.empty()) return;
  std::string chunk;
  put_u64(chunk, chunk_start_ns_);
  put_u64(chunk, chunk_end_ns_);
  put_u64(chunk, chunk_records_.size());  // uncompressed size
  put_u32(chunk, crc32_of(chunk_records_));
  std::string stored;  // the records as stored
  if (compression_ == Compression::zstd) {
    stored.resize(ZSTD_compressBound(chunk_records_.size()));
    const std::size_t n = ZSTD_compress(stored.data(), stored.size(), chunk_records_.data(), chunk_records_.size(), 1);
    if (ZSTD_isError(n) != 0) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    stored.resize(n);
  }
  const std::string& records = compression_ == Compression::zstd ? stored : chunk_records_;
  put_string(chunk, compression_ == Compression::zstd ? "zstd" : "");
  put_u64(chunk, records.size());  // records: uint64 length, then the records
  chunk += records;
  ChunkIndexRecord index{chunk_start_ns_, chunk_end_ns_, offset_, 0, {}, 0, chunk_records_.size(), records.size()};
  write_record(Opcode::chunk, chunk);
  index.length = offset_ - index.offset;
  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_entries_) {
    std::string mi;
    put_u16(mi, channel);
    put_u32(mi, static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time_ns, at] : entries) put_u64(mi, time_ns), put_u64(mi, at);
    index.message_index_offsets[channel] = offset_;
    write_record(Opcode::message_index, mi);
  }
  index.message_index_length = offset_ - indexes_start;
  chunk_indexes_.push_back(index);
  chunk_records_.clear();
  chunk_index_entries_.clear();
}

std::uint64_t Writer::finish() {
  if (finished_) return offset_;
  flush_chunk();
  std::string data_end;
  put_u32(data_end, 0);  // the data section's CRC: not computed
  write_record(Opcode::data_end, data_end);

  // The summary: each group of records, and where it starts.
  const std::uint64_t summary_start = offset_;
  std::string summary;
  std::vector<std::pair<Opcode, std::pair<std::uint64_t, std::uint64_t>>> groups;
  const auto group = [&](Opcode op, const std::vector<std::string>& contents) {
    if (contents.empty()) return;
    const std::uint64_t start = summary_start + summary.size();
    for (const std::string& c : contents) summary += record(op, c);
    groups.push_back({op, {start, summary_start + summary.size() - start}});
  };
  std::vector<std::string> schema_records, channel_records, chunk_index_records;
  for (const SchemaRecord& s : schemas_) schema_records.push_back(schema_content(s.id, s.name, s.encoding, s.data));
  for (const ChannelRecord& c : channels_) {
    channel_records.push_back(channel_content(c.id, c.schema_id, c.topic, c.message_encoding, c.metadata));
  }
  std::string statistics;
  put_u64(statistics, message_count_);
  put_u16(statistics, static_cast<std::uint16_t>(schemas_.size()));
  put_u32(statistics, static_cast<std::uint32_t>(channels_.size()));
  put_u32(statistics, 0);  // attachments
  put_u32(statistics, 0);  // metadata
  put_u32(statistics, static_cast<std::uint32_t>(chunk_indexes_.size()));
  put_u64(statistics, first_ns_);
  put_u64(statistics, last_ns_);
  std::string counts;
  for (const auto& [channel, n] : message_counts_) put_u16(counts, channel), put_u64(counts, n);
  put_u32(statistics, static_cast<std::uint32_t>(counts.size()));
  statistics += counts;
  for (const ChunkIndexRecord& ci : chunk_indexes_) {
    std::string c;
    put_u64(c, ci.start_ns);
    put_u64(c, ci.end_ns);
    put_u64(c, ci.offset);
    put_u64(c, ci.length);
    std::string offsets;
    for (const auto& [channel, at] : ci.message_index_offsets) put_u16(offsets, channel), put_u64(offsets, at);
    put_u32(c, static_cast<std::uint32_t>(offsets.size()));
    c += offsets;
    put_u64(c, ci.message_index_length);
    put_string(c, compression_ == Compression::zstd ? "zstd" : "");
    put_u64(c, ci.compressed_size);
    put_u64(c, ci.size);
    chunk_index_records.push_back(c);
  }
  group(Opcode::schema, schema_records);
  group(Opcode::channel, channel_records);
  group(Opcode::statistics, {statistics});
  group(Opcode::chunk_index, chunk_index_records);
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& [op, where] : groups) {
    std::string so;
    put_u8(so, static_cast<std::uint8_t>(op));
    put_u64(so, where.first);
    put_u64(so, where.second);
    summary += record(Opcode::summary_offset, so);
  }
  // The footer's CRC covers the summary, the summary offsets and the footer up to its CRC.
  std::string footer_start;
  put_u8(footer_start, static_cast<std::uint8_t>(Opcode::footer));
  put_u64(footer_start, 20);
  put_u64(footer_start, summary_start);
  put_u64(footer_start, summary_offset_start);
  const std::uint32_t crc = crc32_of(summary + footer_start);
  out_.write(summary.data(), static_cast<std::streamsize>(summary.size()));
  offset_ += summary.size();
  std::string footer;
  put_u64(footer, summary_start);
  put_u64(footer, summary_offset_start);
  put_u32(footer, crc);
  write_record(Opcode::footer, footer);
  out_.write(reinterpret_cast<const char*>(kMagic), sizeof kMagic);
  offset_ += sizeof kMagic;
  finished_ = true;
  return offset_;
}

}  // namespace rcsim::mcap
