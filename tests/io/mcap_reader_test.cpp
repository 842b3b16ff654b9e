// The MCAP reader (src/io/mcap_reader.cpp) on damaged files: each refused naming the file, the
// record and its byte offset, before a message of the damaged part is handed on.
#include "io/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include <fstream>
#include <lz4frame.h>
#include <sstream>
#include <string>
#include <zstd.h>

#include "common/input_error.hpp"
#include "peak_memory.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::mcap_reader_test {

using testing::refusal_of;

// A small file: one schema, one channel, three messages in one chunk.
std::string small_file() {
  std::ostringstream out;
  mcap::Writer writer(out);
  const auto schema = writer.add_schema("rcsim.Test", "jsonschema", R"({"type": "object"})");
  const auto channel = writer.add_channel("/a", "json", schema);
  for (int i = 0; i < 3; ++i) writer.write_message(channel, static_cast<std::uint64_t>(i), R"({"k": )" + std::to_string(i) + "}");
  writer.finish();
  return out.str();
}

class McapReader : public rcsim::testing::ScratchDirTest {
 protected:
  McapReader() : ScratchDirTest("mcap_reader") {}
  // What reading `bytes` as a.mcap gives: "read N" or the refusal.
  std::string read_back(const std::string& bytes) {
    const auto path = write_file("a.mcap", bytes);
    int messages = 0;
    const std::string refused = refusal_of([&] {
      mcap::Reader reader(path);
      reader.for_each_message([&](const mcap::Message&, const mcap::Channel&, const mcap::Schema*) { ++messages; });
    });
    return refused == "accepted" ? "read " + std::to_string(messages) : refused.substr(refused.find("a.mcap"));
  }
};

TEST_F(McapReader, AnIntactFileReadsWhole) { EXPECT_EQ(read_back(small_file()), "read 3"); }

// No MCAP at all is refused; a file cut short (a recorder that crashed, issue 50) is read up to its
// last whole record, and the reader's warning says what was left out.
TEST_F(McapReader, NoMcapIsRefusedAndATruncatedFileReadsUpToItsLastWholeRecord) {
  EXPECT_EQ(read_back(std::string(64, 'x')), "a.mcap: the start at byte 0: not an MCAP file (no magic 0x89 MCAP0)");
  const std::string whole = small_file();
  const std::string cut = whole.substr(0, whole.size() - 20);
  EXPECT_EQ(read_back(cut), "read 3");
  mcap::Reader reader(write_file("cut.mcap", cut));
  reader.for_each_message([](const mcap::Message&, const mcap::Channel&, const mcap::Schema*) {});
  EXPECT_NE(reader.warning().find("no footer (the recorder stopped before closing the log): read up to its last whole record"),
            std::string::npos) << reader.warning();
  // Cut inside the first message: nothing of it read, the rest left out.
  const std::size_t message = whole.find('\x05', 8);
  EXPECT_EQ(read_back(whole.substr(0, message + 12)), "read 0");
}

// Issue 51 (MEDIUM): a Data End record midway silently ended the read with half the log. Now only
// one where the summary or the footer follows ends it; another is refused at its offset.
TEST_F(McapReader, ADataEndMidwayIsRefusedNotAHalfLog) {
  const std::string whole = small_file();
  const auto u64_at = [&](const std::string& b, std::size_t at) {
    std::uint64_t v = 0;
    std::memcpy(&v, b.data() + at, 8);
    return v;
  };
  const std::size_t after_header = 8 + 9 + u64_at(whole, 8 + 1);
  const std::string data_end("\x0f\x04\0\0\0\0\0\0\0\0\0\0\0", 13);
  std::string midway = whole.substr(0, after_header) + data_end + whole.substr(after_header);
  // The footer's summary offsets moved with the records, its CRC left out.
  const std::size_t footer = midway.size() - 8 - 29;
  const std::uint64_t summary = u64_at(midway, footer + 9) + 13, offsets = u64_at(midway, footer + 17) + 13;
  std::memcpy(midway.data() + footer + 9, &summary, 8);
  std::memcpy(midway.data() + footer + 17, &offsets, 8);
  std::memset(midway.data() + footer + 25, 0, 4);
  EXPECT_EQ(read_back(midway), "a.mcap: Data End at byte " + std::to_string(after_header) + ": " + std::to_string(summary - after_header) +
                                   " bytes before the data section's end at byte " + std::to_string(summary) +
                                   ": the records after it would be left out");
}

TEST_F(McapReader, AByteChangedInTheSummaryOrAChunkIsFoundByItsCrc) {
  const std::string whole = small_file();
  // Where the summary starts, from the footer of the intact file.
  mcap::FileSummary summary;
  {
    const auto path = write_file("ok.mcap", whole);
    summary = mcap::Reader(path).summary();
  }
  std::string summary_changed = whole;
  summary_changed[summary.summary_start + 12] ^= 0x01;  // inside the first summary record
  EXPECT_NE(read_back(summary_changed).find("a.mcap: Summary at byte " + std::to_string(summary.summary_start) + ": CRC-32 0x"),
            std::string::npos)
      << read_back(summary_changed);
  // The last message's data, inside the chunk: its "2" becomes "3".
  std::string chunk_changed = whole;
  const auto at = chunk_changed.find(R"({"k": 2})");
  ASSERT_NE(at, std::string::npos);
  chunk_changed[at + 6] = '3';
  const std::string refused = read_back(chunk_changed);
  EXPECT_EQ(refused.find("a.mcap: Chunk at byte "), 0u) << refused;
  EXPECT_NE(refused.find(": CRC-32 0x"), std::string::npos) << refused;
}

TEST_F(McapReader, ARecordLongerThanTheFileOrAMessageOnAnUnknownChannelIsNamed) {
  // A hand-made file: magic, header, a message on channel 7 (never announced), data end, footer.
  std::string bytes(reinterpret_cast<const char*>(mcap::kMagic), 8);
  std::string header;
  mcap::put_string(header, "");
  mcap::put_string(header, "hand");
  const auto record = [&](mcap::Opcode op, const std::string& content) {
    mcap::put_u8(bytes, static_cast<std::uint8_t>(op));
    mcap::put_u64(bytes, content.size());
    bytes += content;
  };
  record(mcap::Opcode::header, header);
  const std::size_t message_at = bytes.size();
  std::string message;
  mcap::put_u16(message, 7);
  mcap::put_u32(message, 0);
  mcap::put_u64(message, 5);
  mcap::put_u64(message, 5);
  message += "data";
  record(mcap::Opcode::message, message);
  std::string data_end;
  mcap::put_u32(data_end, 0);
  record(mcap::Opcode::data_end, data_end);
  std::string footer;
  mcap::put_u64(footer, 0);
  mcap::put_u64(footer, 0);
  mcap::put_u32(footer, 0);
  record(mcap::Opcode::footer, footer);
  bytes += std::string(reinterpret_cast<const char*>(mcap::kMagic), 8);
  EXPECT_EQ(read_back(bytes), "a.mcap: Message at byte " + std::to_string(message_at) + ": a message on channel 7, never announced");
  // The same message claiming 2^40 bytes.
  std::string too_long = bytes;
  for (int i = 0; i < 8; ++i) too_long[message_at + 1 + static_cast<std::size_t>(i)] = i == 5 ? 1 : 0;
  EXPECT_EQ(read_back(too_long), "a.mcap: Message at byte " + std::to_string(message_at) +
                                     ": its length 1099511627776 runs past the end of the file");
}

// A file whose one chunk holds a schema, a channel and two messages, its records stored as
// `compress` makes them under the name `compression`, with the records' CRC-32.
template <typename Compress>
std::string file_with_chunk(const std::string& compression, Compress compress) {
  std::string records;
  const auto record = [](std::string& out, mcap::Opcode op, const std::string& content) {
    mcap::put_u8(out, static_cast<std::uint8_t>(op));
    mcap::put_u64(out, content.size());
    out += content;
  };
  std::string schema, channel;
  mcap::put_u16(schema, 1);
  mcap::put_string(schema, "rcsim.Test");
  mcap::put_string(schema, "jsonschema");
  mcap::put_u32(schema, 2);
  schema += "{}";
  record(records, mcap::Opcode::schema, schema);
  mcap::put_u16(channel, 1);
  mcap::put_u16(channel, 1);
  mcap::put_string(channel, "/a");
  mcap::put_string(channel, "json");
  mcap::put_u32(channel, 0);  // no metadata
  record(records, mcap::Opcode::channel, channel);
  for (int i = 0; i < 2; ++i) {
    std::string message;
    mcap::put_u16(message, 1);
    mcap::put_u32(message, static_cast<std::uint32_t>(i));
    mcap::put_u64(message, static_cast<std::uint64_t>(i));
    mcap::put_u64(message, static_cast<std::uint64_t>(i));
    message += R"({"k": )" + std::to_string(i) + "}";
    record(records, mcap::Opcode::message, message);
  }
  const std::string stored = compress(records);
  std::string chunk;
  mcap::put_u64(chunk, 0);
  mcap::put_u64(chunk, 1);
  mcap::put_u64(chunk, records.size());
  mcap::put_u32(chunk, mcap::crc32_of(records));
  mcap::put_string(chunk, compression);
  mcap::put_u64(chunk, stored.size());
  chunk += stored;
  std::string bytes(reinterpret_cast<const char*>(mcap::kMagic), 8), header, data_end, footer;
  mcap::put_string(header, "");
  mcap::put_string(header, "hand");
  record(bytes, mcap::Opcode::header, header);
  record(bytes, mcap::Opcode::chunk, chunk);
  mcap::put_u32(data_end, 0);
  record(bytes, mcap::Opcode::data_end, data_end);
  mcap::put_u64(footer, 0);
  mcap::put_u64(footer, 0);
  mcap::put_u32(footer, 0);
  record(bytes, mcap::Opcode::footer, footer);
  return bytes + std::string(reinterpret_cast<const char*>(mcap::kMagic), 8);
}

std::string zstd_of(const std::string& in) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
  return out;
}

std::string lz4_of(const std::string& in) {
  std::string out(LZ4F_compressFrameBound(in.size(), nullptr), '\0');
  out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
  return out;
}

TEST_F(McapReader, ZstdAndLz4ChunksReadAsTheUncompressed) {
  const auto same = [](const std::string& in) { return in; };
  EXPECT_EQ(read_back(file_with_chunk("", same)), "read 2");
  EXPECT_EQ(read_back(file_with_chunk("zstd", zstd_of)), "read 2");
  EXPECT_EQ(read_back(file_with_chunk("lz4", lz4_of)), "read 2");
}

TEST_F(McapReader, AnUnknownOrDamagedCompressionIsNamed) {
  const auto same = [](const std::string& in) { return in; };
  EXPECT_EQ(read_back(file_with_chunk("brotli", same)), "a.mcap: Chunk at byte 29: compression 'brotli' is not read (zstd, lz4 or none)");
  // zstd that is not: the library's own words.
  EXPECT_NE(read_back(file_with_chunk("zstd", same)).find("Chunk at byte 29: zstd: "), std::string::npos);
  // A zstd frame cut short, an lz4 frame cut short.
  const auto cut = [](auto compress) { return [compress](const std::string& in) { const std::string c = compress(in); return c.substr(0, c.size() - 6); }; };
  EXPECT_NE(read_back(file_with_chunk("zstd", cut(zstd_of))).find("Chunk at byte 29: zstd"), std::string::npos);
  EXPECT_NE(read_back(file_with_chunk("lz4", cut(lz4_of))).find("Chunk at byte 29: lz4"), std::string::npos);
}

// A Chunk record's content around `stored` (its records as `compression` stores them), saying
// `size` bytes uncompressed and (0: none) a CRC-32.
std::string chunk_content(const std::string& compression, const std::string& stored, std::uint64_t size, std::uint32_t crc) {
  std::string chunk;
  mcap::put_u64(chunk, 0);
  mcap::put_u64(chunk, 1);
  mcap::put_u64(chunk, size);
  mcap::put_u32(chunk, crc);
  mcap::put_string(chunk, compression);
  mcap::put_u64(chunk, stored.size());
  return chunk + stored;
}

std::string record_of(mcap::Opcode op, const std::string& content) {
  std::string out;
  mcap::put_u8(out, static_cast<std::uint8_t>(op));
  mcap::put_u64(out, content.size());
  return out + content;
}

// A file of the header, `records`, the data end and a footer without summary.
std::string file_around(const std::string& records) {
  std::string bytes(reinterpret_cast<const char*>(mcap::kMagic), 8), header, data_end, footer;
  mcap::put_string(header, "");
  mcap::put_string(header, "hand");
  bytes += record_of(mcap::Opcode::header, header) + records;
  mcap::put_u32(data_end, 0);
  bytes += record_of(mcap::Opcode::data_end, data_end);
  mcap::put_u64(footer, 0);
  mcap::put_u64(footer, 0);
  mcap::put_u32(footer, 0);
  bytes += record_of(mcap::Opcode::footer, footer);
  return bytes + std::string(reinterpret_cast<const char*>(mcap::kMagic), 8);
}

// The records of file_with_chunk's chunk: a schema, a channel, two messages.
std::string chunk_records() {
  const std::string file = file_with_chunk("", [](const std::string& in) { return in; });
  const std::size_t chunk_at = 8 + 9 + 4 + 4 + 4;  // after the magic and the header record ("", "hand")
  const std::size_t records_at = chunk_at + 9 + 8 + 8 + 8 + 4 + 4 + 8;
  std::uint64_t size = 0;
  for (int i = 0; i < 8; ++i) size |= std::uint64_t{static_cast<unsigned char>(file[chunk_at + 9 + 16 + static_cast<std::size_t>(i)])} << (8 * i);
  return file.substr(records_at, size);
}

// Issue 51, HIGH 7: chunks inside chunks were read recursively, each level copied three times
// (6 GB from 877 KB). The spec's chunks hold schemas, channels and messages; @mcap/core refuses a
// chunk in a chunk, and so does rcsim, naming the inner chunk's offset.
TEST_F(McapReader, AChunkInsideAChunkIsRefusedAtItsOffset) {
  const std::string records = chunk_records();
  ASSERT_EQ(read_back(file_around(record_of(mcap::Opcode::chunk, chunk_content("", records, records.size(), mcap::crc32_of(records))))),
            "read 2");
  const std::string inner = record_of(mcap::Opcode::chunk, chunk_content("", records, records.size(), 0));
  const std::string outer = record_of(mcap::Opcode::chunk, chunk_content("", inner, inner.size(), 0));
  const std::size_t inner_at = 8 + 9 + 4 + 4 + 4 + 9 + 8 + 8 + 8 + 4 + 4 + 8;
  EXPECT_EQ(read_back(file_around(outer)), "a.mcap: in a chunk, Chunk at byte " + std::to_string(inner_at) +
                                               ": a chunk inside a chunk: a chunk holds schemas, channels and messages only (mcap.dev/spec)");
  // Nested 200 deep, compressed at each level: refused at the first inner chunk all the same.
  std::string nested = inner;
  for (int depth = 0; depth < 200; ++depth) nested = record_of(mcap::Opcode::chunk, chunk_content("zstd", zstd_of(nested), nested.size(), 0));
  EXPECT_NE(read_back(file_around(nested)).find(": a chunk inside a chunk"), std::string::npos);
}

// Issue 51 (MEDIUM): a chunk claiming 1 GiB uncompressed allocated and zero-filled 1 GiB before
// the data were found to hold a few bytes. A zstd frame that states its size is checked against
// the chunk's before anything is decoded; otherwise (an lz4 frame, a zstd stream without a size)
// the output grows with what the data really decode to.
TEST_F(McapReader, AChunkClaimingAGibibyteCostsWhatItsDataDecodeTo) {
  const std::string records = chunk_records();
  constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
  const auto lying = [&](const std::string& compression, const std::string& stored) {
    return file_around(record_of(mcap::Opcode::chunk, chunk_content(compression, stored, kGiB, 0)));
  };
  // A zstd frame that does not state its size (as a stream's).
  const auto zstd_without_size = [](const std::string& in) {
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(context, ZSTD_c_contentSizeFlag, 0);
    std::string out(ZSTD_compressBound(in.size()), '\0');
    out.resize(ZSTD_compress2(context, out.data(), out.size(), in.data(), in.size()));
    ZSTD_freeCCtx(context);
    return out;
  };
  ASSERT_EQ(ZSTD_getFrameContentSize(zstd_without_size(records).data(), zstd_without_size(records).size()), ZSTD_CONTENTSIZE_UNKNOWN);
  const std::string n = std::to_string(records.size());
  std::string zstd, unsized, lz4;
  const auto peak_zstd = testing::peak_memory_added_by([&] { zstd = read_back(lying("zstd", zstd_of(records))); });
  const auto peak_unsized = testing::peak_memory_added_by([&] { unsized = read_back(lying("zstd", zstd_without_size(records))); });
  const auto peak_lz4 = testing::peak_memory_added_by([&] { lz4 = read_back(lying("lz4", lz4_of(records))); });
  EXPECT_EQ(zstd, "a.mcap: Chunk at byte 29: its zstd frame holds " + n + " bytes where the chunk says 1073741824");
  EXPECT_EQ(unsized, "a.mcap: Chunk at byte 29: zstd gave " + n + " bytes where it says 1073741824");
  EXPECT_EQ(lz4, "a.mcap: Chunk at byte 29: lz4 gave " + n + " bytes where it says 1073741824");
  for (const auto& peak : {peak_zstd, peak_unsized, peak_lz4}) {
    if (peak) {
      EXPECT_LT(*peak, 64 << 20) << "bytes of peak memory added by a chunk of " << n << " bytes claiming 1 GiB";
    }
  }
}

}  // namespace rcsim::mcap_reader_test
