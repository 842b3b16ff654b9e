// The MCAP writer (src/io/mcap_writer.cpp): the spec's primitives byte by byte, the header record
// by hand, and a file read back by the reader: every message in order with its channel and
// schema, chunks cut at 1 MiB, the summary's CRC and the statistics.
#include "io/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "io/mcap_reader.hpp"
#include "scratch_dir.hpp"

namespace rcsim::mcap_writer_test {

std::string hex(const std::string& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (const char c : bytes) {
    const auto b = static_cast<unsigned char>(c);
    out += digits[b >> 4];
    out += digits[b & 15];
  }
  return out;
}

TEST(McapWriter, PrimitivesAreLittleEndianAndStringsCarryTheirLength) {
  std::string out;
  mcap::put_u16(out, 0x0102);
  mcap::put_u32(out, 0x03040506);
  mcap::put_u64(out, 0x0708090a0b0c0d0eULL);
  mcap::put_string(out, "ab");
  EXPECT_EQ(hex(out), "0201" "06050403" "0e0d0c0b0a090807" "02000000" "6162");
  // CRC-32 (zlib's, as the spec's): of "123456789" the check value 0xcbf43926.
  EXPECT_EQ(mcap::crc32_of("123456789"), 0xcbf43926u);
}

TEST(McapWriter, TheFileOpensWithTheMagicAndAHeaderByHand) {
  std::ostringstream out;
  mcap::Writer writer(out, "ros2");
  writer.finish();
  const std::string bytes = out.str();
  // Magic, then opcode 0x01, length 4 + 4 + 4 + 5 = 17, profile "ros2", library "rcsim".
  EXPECT_EQ(hex(bytes.substr(0, 8)), "894d434150300d0a");
  EXPECT_EQ(hex(bytes.substr(8, 9 + 17)), "01" "1100000000000000" "04000000" "726f7332" "05000000" "726373696d");
  EXPECT_EQ(bytes.substr(bytes.size() - 8), bytes.substr(0, 8));  // the closing magic
}

class McapRoundTrip : public rcsim::testing::ScratchDirTest {
 protected:
  McapRoundTrip() : ScratchDirTest("mcap_writer") {}
};

TEST_F(McapRoundTrip, EveryMessageComesBackInOrderWithItsChannelAndSchema) {
  const auto path = dir_ / "a.mcap";
  {
    std::ofstream out(path, std::ios::binary);
    mcap::Writer writer(out);
    const auto schema = writer.add_schema("rcsim.Test", "jsonschema", R"({"type": "object"})");
    const auto a = writer.add_channel("/a", "json", schema, {{"sensor", "front"}});
    const auto b = writer.add_channel("/b", "json", 0);  // no schema
    writer.write_message(a, 1000, R"({"k": 1})");
    writer.write_message(b, 1500, "x");
    writer.write_message(a, 2000, R"({"k": 2})");
    writer.finish();
  }
  mcap::Reader reader(path);
  std::vector<std::string> seen;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema* s) {
    seen.push_back(c.topic + "@" + std::to_string(m.log_time_ns) + "#" + std::to_string(m.sequence) + ":" + m.data + ":" +
                   (s ? s->name : "-"));
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"/a@1000#0:{\"k\": 1}:rcsim.Test", "/b@1500#0:x:-", "/a@2000#1:{\"k\": 2}:rcsim.Test"}));
  EXPECT_EQ(reader.channels().at(1).metadata.at("sensor"), "front");
  EXPECT_EQ(reader.summary().library, "rcsim");
  EXPECT_NE(reader.summary().summary_crc, 0u);  // given, and checked before the messages
  EXPECT_EQ(reader.summary().chunks, 1u);
}

TEST_F(McapRoundTrip, ChunksAreCutAtOneMebibyte) {
  const auto path = dir_ / "big.mcap";
  const std::string payload(100000, 'p');
  {
    std::ofstream out(path, std::ios::binary);
    mcap::Writer writer(out);
    const auto c = writer.add_channel("/big", "binary", 0);
    for (int i = 0; i < 30; ++i) writer.write_message(c, static_cast<std::uint64_t>(i), payload);  // 3 MB
    writer.finish();
  }
  mcap::Reader reader(path);
  int messages = 0;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel&, const mcap::Schema*) {
    EXPECT_EQ(m.log_time_ns, static_cast<std::uint64_t>(messages));
    EXPECT_EQ(m.data.size(), payload.size());
    ++messages;
  });
  EXPECT_EQ(messages, 30);
  // 100,033 bytes a message record: a chunk closes at the 11th (1,100,363 >= 1,048,576): 11 + 11 + 8.
  EXPECT_EQ(reader.summary().chunks, 3u);
}

// zstd chunks: the same messages back through the reader, the file a fraction of the
// uncompressed one (3 MB of one repeated byte: a few hundred bytes a chunk).
TEST_F(McapRoundTrip, ZstdChunksReadBackAndShrink) {
  const std::string payload(100000, 'p');
  std::uint64_t bytes[2] = {0, 0};
  for (const auto compression : {mcap::Compression::none, mcap::Compression::zstd}) {
    const auto path = dir_ / (compression == mcap::Compression::zstd ? "zstd.mcap" : "plain.mcap");
    {
      std::ofstream out(path, std::ios::binary);
      mcap::Writer writer(out, "", compression);
      const auto c = writer.add_channel("/big", "binary", 0);
      for (int i = 0; i < 30; ++i) writer.write_message(c, static_cast<std::uint64_t>(i), payload + std::to_string(i));
      bytes[compression == mcap::Compression::zstd] = writer.finish();
    }
    mcap::Reader reader(path);
    int messages = 0;
    reader.for_each_message([&](const mcap::Message& m, const mcap::Channel&, const mcap::Schema*) {
      EXPECT_EQ(m.data, payload + std::to_string(messages));
      ++messages;
    });
    EXPECT_EQ(messages, 30);
    EXPECT_EQ(reader.summary().chunks, 3u);
  }
  EXPECT_GT(bytes[0], 3'000'000u);
  EXPECT_LT(bytes[1], 20'000u);
}

}  // namespace rcsim::mcap_writer_test
