#include "io/mcap_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <lz4frame.h>
#include <zstd.h>

#include "common/input_error.hpp"

namespace rcsim::mcap {

namespace {

constexpr std::uint64_t kFooterRecordBytes = 1 + 8 + 20;
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;  // 1 GiB uncompressed at the most

std::string opcode_name(std::uint8_t op) {
  switch (static_cast<Opcode>(op)) {
    case Opcode::header: return "Header";
    case Opcode::footer: return "Footer";
    case Opcode::schema: return "Schema";
    case Opcode::channel: return "Channel";
    case Opcode::message: return "Message";
    case Opcode::chunk: return "Chunk";
    case Opcode::message_index: return "Message Index";
    case Opcode::chunk_index: return "Chunk Index";
    case Opcode::statistics: return "Statistics";
    case Opcode::summary_offset: return "Summary Offset";
    case Opcode::data_end: return "Data End";
  }
  return fmt::format("record 0x{:02x}", op);
}

// Reads the spec's little-endian primitives from a record's content; throws std::out_of_range
// (turned into the caller's refusal) where the content ends first.
class Cursor {
 public:
  explicit Cursor(std::string_view bytes) : bytes_(bytes) {}
  std::uint64_t unsigned_of(int n) {
    need(static_cast<std::size_t>(n));
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint64_t{static_cast<unsigned char>(bytes_[at_ + static_cast<std::size_t>(i)])} << (8 * i);
    at_ += static_cast<std::size_t>(n);
    return v;
  }
  std::uint8_t u8() { return static_cast<std::uint8_t>(unsigned_of(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(unsigned_of(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(unsigned_of(4)); }
  std::uint64_t u64() { return unsigned_of(8); }
  std::string bytes(std::size_t n) { return std::string(view(n)); }
  // The next n bytes where they lie: no copy.
  std::string_view view(std::size_t n) {
    need(n);
    const std::string_view s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::string string() { return bytes(u32()); }
  std::map<std::string, std::string> string_map() {
    const std::size_t length = u32();
    need(length);
    const std::size_t end = at_ + length;
    std::map<std::string, std::string> m;
    while (at_ < end) {
      std::string key = string();
      m[key] = string();
    }
    if (at_ != end) throw std::out_of_range("map");
    return m;
  }
  std::string rest() { return bytes(bytes_.size() - at_); }
  std::size_t at() const { return at_; }

 private:
  void need(std::size_t n) const {
    if (n > bytes_.size() - at_) throw std::out_of_range("record");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

void Reader::fail(const std::string& where, std::uint64_t offset, const std::string& what) const {
  throw InputError(path_.string(), fmt::format("{} at byte {}", where, offset), what);
}

Reader::Reader(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw InputError(path_.string(), "", "cannot open for reading");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(in_.tellg());
  const auto read_at = [&](std::uint64_t offset, std::size_t n) {
    std::string bytes(n, '\0');
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(bytes.data(), static_cast<std::streamsize>(n));
    return bytes;
  };
  const std::string magic(reinterpret_cast<const char*>(kMagic), sizeof kMagic);
  if (size_ < sizeof kMagic || read_at(0, sizeof kMagic) != magic) fail("the start", 0, "not an MCAP file (no magic 0x89 MCAP0)");
  if (size_ < 2 * sizeof kMagic + kFooterRecordBytes || read_at(size_ - sizeof kMagic, sizeof kMagic) != magic) {
    // A recorder that stopped before writing its footer: read up to the last whole record.
    unfinished_ = true;
    return;
  }
  const std::uint64_t footer_at = size_ - sizeof kMagic - kFooterRecordBytes;
  const std::string footer = read_at(footer_at, kFooterRecordBytes);
  Cursor f(footer);
  if (f.u8() != static_cast<std::uint8_t>(Opcode::footer) || f.u64() != 20) fail("Footer", footer_at, "not a footer record");
  summary_.summary_start = f.u64();
  summary_.summary_offset_start = f.u64();
  summary_.summary_crc = f.u32();
  if (summary_.summary_start > footer_at || summary_.summary_offset_start > footer_at) {
    fail("Footer", footer_at, "its summary offsets point beyond the footer");
  }
}

void Reader::check_summary_crc() {
  if (summary_.summary_crc == 0 || summary_.summary_start == 0) return;
  const std::uint64_t footer_at = size_ - sizeof kMagic - kFooterRecordBytes;
  std::string bytes(footer_at + 1 + 8 + 16 - summary_.summary_start, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(summary_.summary_start));
  in_.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (crc32_of(bytes) != summary_.summary_crc) {
    fail("Summary", summary_.summary_start, fmt::format("CRC-32 0x{:08x} where the footer says 0x{:08x}", crc32_of(bytes), summary_.summary_crc));
  }
}

void Reader::for_each_message(const Visit& visit) {
  check_summary_crc();
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(sizeof kMagic));
  std::uint64_t offset = sizeof kMagic;
  const std::uint64_t data_end = unfinished_ ? size_ : summary_.summary_start != 0 ? summary_.summary_start : size_ - sizeof kMagic - kFooterRecordBytes;
  bool first = true;
  // An unfinished log ends where its last whole record does; what follows is left out, said once.
  const auto stop_unfinished = [&](std::uint64_t at) {
    unfinished_warning_ = fmt::format("{}: no footer (the recorder stopped before closing the log): read up to its last whole record, "
                                      "{} of its {} bytes; the {} bytes after byte {} are left out",
                                      path_.string(), at, size_, size_ - at, at);
  };
  while (offset < data_end) {
    char head[9];
    in_.read(head, 9);
    if (!in_) {
      if (unfinished_) return stop_unfinished(offset);
      fail("a record", offset, "the file ends inside its opcode and length");
    }
    Cursor h(std::string_view(head, 9));
    const std::uint8_t op = h.u8();
    const std::uint64_t length = h.u64();
    if (length > size_ - offset - 9) {
      if (unfinished_ && !first) return stop_unfinished(offset);
      fail(opcode_name(op), offset, fmt::format("its length {} runs past the end of the file", length));
    }
    if (op == static_cast<std::uint8_t>(Opcode::chunk) && length > kMaxChunkBytes + 64) {
      fail("Chunk", offset, fmt::format("{} bytes: more than the 1 GiB a chunk may hold here", length));
    }
    if (first && op != static_cast<std::uint8_t>(Opcode::header)) fail(opcode_name(op), offset, "the first record is not the header");
    first = false;
    // Attachments, metadata, indexes and statistics are not needed to read the messages: skipped
    // unread (an attachment may be any size).
    const bool needed = op == static_cast<std::uint8_t>(Opcode::header) || op == static_cast<std::uint8_t>(Opcode::schema) ||
                        op == static_cast<std::uint8_t>(Opcode::channel) || op == static_cast<std::uint8_t>(Opcode::message) ||
                        op == static_cast<std::uint8_t>(Opcode::chunk);
    if (!needed) {
      const std::uint64_t at = offset;
      offset += 9 + length;
      if (op == static_cast<std::uint8_t>(Opcode::data_end) || op == static_cast<std::uint8_t>(Opcode::footer)) {
        // The data section ends here only where the summary or the footer follows: a Data End or a
        // footer midway would leave the rest of the log out silently.
        if (op == static_cast<std::uint8_t>(Opcode::footer) || (offset != data_end && !unfinished_)) {
          fail(opcode_name(op), at, fmt::format("{} bytes before the data section's end at byte {}: the records after it would be left out",
                                                data_end - at, data_end));
        }
        break;
      }
      in_.seekg(static_cast<std::streamoff>(offset));
      continue;
    }
    // The record read once into one buffer, its content read where it lies (no copy of it).
    std::string record(9 + length, '\0');
    std::memcpy(record.data(), head, 9);
    in_.read(record.data() + 9, static_cast<std::streamsize>(length));
    if (!in_) {
      if (unfinished_) return stop_unfinished(offset);
      fail(opcode_name(op), offset, "the file ends inside it");
    }
    if (unfinished_) {
      // A chunk the recorder was still writing may be damaged: the log ends before it (a refusal
      // of a message by the visitor still stops the read).
      bool visiting = false;
      const Visit guarded = [&](const Message& m, const Channel& c, const Schema* schema) {
        visiting = true;
        visit(m, c, schema);
        visiting = false;
      };
      try {
        read_records(record, offset, false, guarded);
      } catch (const InputError&) {
        if (visiting || op != static_cast<std::uint8_t>(Opcode::chunk)) throw;
        return stop_unfinished(offset);
      }
    } else {
      read_records(record, offset, false, visit);
    }
    offset += 9 + length;
  }
  if (unfinished_) stop_unfinished(offset);
}

// Records in `bytes` (at `base_offset` in the file): the top level, or a chunk's records.
void Reader::read_records(std::string_view bytes, std::uint64_t base_offset, bool in_chunk, const Visit& visit) {
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::uint64_t offset = base_offset + at;
    std::string where = "a record";
    try {
      Cursor head(bytes.substr(at, std::min<std::size_t>(9, bytes.size() - at)));
      const std::uint8_t op = head.u8();
      const std::uint64_t length = head.u64();
      where = (in_chunk ? "in a chunk, " : "") + opcode_name(op);
      if (length > bytes.size() - at - 9) fail(where, offset, fmt::format("its length {} runs past its chunk", length));
      Cursor c(bytes.substr(at + 9, length));
      switch (static_cast<Opcode>(op)) {
        case Opcode::header:
          summary_.profile = c.string();
          summary_.library = c.string();
          break;
        case Opcode::schema: {
          Schema s;
          s.id = c.u16();
          s.name = c.string();
          s.encoding = c.string();
          s.data = c.string();
          if (s.id != 0) schemas_[s.id] = s;
          break;
        }
        case Opcode::channel: {
          Channel ch;
          ch.id = c.u16();
          ch.schema_id = c.u16();
          ch.topic = c.string();
          ch.message_encoding = c.string();
          ch.metadata = c.string_map();
          if (ch.schema_id != 0 && !schemas_.count(ch.schema_id)) {
            fail(where, offset, fmt::format("channel {} ({}) names schema {}, never announced", ch.id, ch.topic, ch.schema_id));
          }
          channels_[ch.id] = ch;
          break;
        }
        case Opcode::message: {
          Message m;
          m.channel_id = c.u16();
          m.sequence = c.u32();
          m.log_time_ns = c.u64();
          m.publish_time_ns = c.u64();
          m.data = c.rest();
          const auto channel = channels_.find(m.channel_id);
          if (channel == channels_.end()) fail(where, offset, fmt::format("a message on channel {}, never announced", m.channel_id));
          const auto schema = schemas_.find(channel->second.schema_id);
          ++summary_.messages;
          visit(m, channel->second, schema == schemas_.end() ? nullptr : &schema->second);
          break;
        }
        case Opcode::chunk: {
          // The spec's chunks hold schemas, channels and messages only (@mcap/core refuses a chunk
          // in a chunk): read recursively, each level's copies made memory quadratic in the depth.
          if (in_chunk) fail(where, offset, "a chunk inside a chunk: a chunk holds schemas, channels and messages only (mcap.dev/spec)");
          c.u64(), c.u64();
          const std::uint64_t uncompressed_size = c.u64();
          const std::uint32_t crc = c.u32();
          const std::string compression = c.string();
          const std::string_view stored = c.view(c.u64());
          std::string inflated;
          if (!compression.empty()) inflated = decompressed(stored, compression, uncompressed_size, where, offset);
          const std::string_view records = compression.empty() ? stored : std::string_view(inflated);
          if (records.size() != uncompressed_size) {
            fail(where, offset, fmt::format("{} bytes of records where it says {}", records.size(), uncompressed_size));
          }
          if (crc != 0 && crc32_of(records) != crc) fail(where, offset, fmt::format("CRC-32 0x{:08x} where it says 0x{:08x}", crc32_of(records), crc));
          ++summary_.chunks;
          read_records(records, offset + 9 + 8 + 8 + 8 + 4 + 4 + compression.size() + 8, true, visit);
          break;
        }
        default:
          break;  // indexes, statistics, attachments, metadata: not needed to read the messages in order
      }
      at += 9 + length;
    } catch (const std::out_of_range&) {
      fail(where, offset, "its content ends before its fields do");
    }
  }
}

std::string Reader::decompressed(std::string_view stored, const std::string& compression, std::uint64_t size,
                                 const std::string& where, std::uint64_t offset) const {
  if (compression != "zstd" && compression != "lz4") {
    fail(where, offset, fmt::format("compression '{}' is not read (zstd, lz4 or none)", compression));
  }
  if (size > kMaxChunkBytes) {
    fail(where, offset, fmt::format("{} bytes uncompressed exceed the limit of {} bytes", size, kMaxChunkBytes));
  }
  // The output grows with what the data really decode to (doubling, up to the size the chunk
  // claims): a chunk that claims 1 GiB and holds a few bytes costs a few bytes, not 1 GiB zeroed.
  std::string out;
  const auto grow = [&](std::size_t written) {
    if (out.size() - written > 0) return;
    out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(size, std::max<std::uint64_t>(2 * out.size(), 64 * 1024))));
  };
  if (compression == "zstd") {
    // One frame that states its size must state the chunk's: told before anything is decoded.
    const unsigned long long claimed = ZSTD_getFrameContentSize(stored.data(), stored.size());
    if (claimed != ZSTD_CONTENTSIZE_UNKNOWN && claimed != ZSTD_CONTENTSIZE_ERROR && claimed != size &&
        ZSTD_findFrameCompressedSize(stored.data(), stored.size()) == stored.size()) {
      fail(where, offset, fmt::format("its zstd frame holds {} bytes where the chunk says {}", claimed, size));
    }
    ZSTD_DStream* stream = ZSTD_createDStream();
    if (stream == nullptr) fail(where, offset, "zstd: no context");
    ZSTD_inBuffer in{stored.data(), stored.size(), 0};
    std::size_t written = 0, hint = 1;
    for (;;) {
      grow(written);
      const std::size_t read_before = in.pos;
      ZSTD_outBuffer o{out.data(), out.size(), written};
      hint = ZSTD_decompressStream(stream, &o, &in);
      if (ZSTD_isError(hint) != 0) {
        const std::string error = ZSTD_getErrorName(hint);
        ZSTD_freeDStream(stream);
        fail(where, offset, "zstd: " + error);
      }
      const bool progress = o.pos != written || in.pos != read_before;
      written = o.pos;
      if ((hint == 0 && in.pos == in.size) || !progress) break;  // the last frame ends, or the output is full or the input cut
    }
    ZSTD_freeDStream(stream);
    if (hint != 0) fail(where, offset, fmt::format("zstd: the frame does not decode to the {} bytes it says ({} decoded)", size, written));
    if (written != size) fail(where, offset, fmt::format("zstd gave {} bytes where it says {}", written, size));
    out.resize(written);
    return out;
  }
  {
    LZ4F_dctx* context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION)) != 0) fail(where, offset, "lz4: no context");
    std::size_t written = 0, read = 0, hint = 1;
    while (hint != 0 && read < stored.size()) {
      grow(written);
      std::size_t out_bytes = out.size() - written, in_bytes = stored.size() - read;
      hint = LZ4F_decompress(context, out.data() + written, &out_bytes, stored.data() + read, &in_bytes, nullptr);
      if (LZ4F_isError(hint) != 0) {
        const std::string error = LZ4F_getErrorName(hint);
        LZ4F_freeDecompressionContext(context);
        fail(where, offset, "lz4: " + error);
      }
      written += out_bytes, read += in_bytes;
      if (out_bytes == 0 && in_bytes == 0) break;  // no progress: the output is full or the input cut
    }
    LZ4F_freeDecompressionContext(context);
    if (hint != 0) fail(where, offset, fmt::format("lz4: the frame does not decode to the {} bytes it says ({} decoded)", size, written));
    if (written != size) fail(where, offset, fmt::format("lz4 gave {} bytes where it says {}", written, size));
    out.resize(written);
    return out;
  }
}

}  // namespace rcsim::mcap
