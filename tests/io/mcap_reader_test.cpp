// The MCAP reader (src/io/mcap_reader.cpp) on damaged files: each refused naming the file, the
// record and its byte offset, before a message of the damaged part is handed on.
#include "io/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
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

TEST_F(McapReader, NoMcapOrATruncatedFileIsRefusedAtItsEnds) {
  EXPECT_EQ(read_back(std::string(64, 'x')), "a.mcap: the start at byte 0: not an MCAP file (no magic 0x89 MCAP0)");
  const std::string whole = small_file();
  const std::string cut = whole.substr(0, whole.size() - 20);
  EXPECT_EQ(read_back(cut), "a.mcap: the end at byte " + std::to_string(cut.size() - 8) +
                                ": no closing magic: the file is truncated or still being written");
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

}  // namespace rcsim::mcap_reader_test
