// Reading input files with stated bounds (common/text_file.hpp): only regular files, a whole file
// up to its limit, lines through a fixed buffer (LF or CR LF), and FNV-1a 64 of a file's bytes.
#include "common/text_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::text_file_test {

namespace fs = std::filesystem;

using testing::refusal_of;

class TextFile : public testing::ScratchDirTest {
 protected:
  TextFile() : ScratchDirTest("text_file") {}
  fs::path write(const std::string& name, const std::string& bytes) { return write_file(name, bytes); }
  // Every line LineReader gives, with its number as "N:text".
  std::vector<std::string> lines_of(const fs::path& path) {
    LineReader reader(path);
    std::vector<std::string> lines;
    for (std::string_view line; reader.next(line);) {
      lines.push_back(std::to_string(reader.line_number()) + ":" + std::string(line));
    }
    return lines;
  }
};

TEST_F(TextFile, WholeFilesAreReadByteForByteUpToTheirLimit) {
  const std::string bytes("a\r\nb\0c\xFF", 7);
  const fs::path path = write("data.bin", bytes);
  EXPECT_EQ(read_text_file(path), bytes);  // CR LF, NUL and any byte kept
  EXPECT_EQ(read_text_file(path, 7), bytes);  // exactly at the limit
  EXPECT_EQ(refusal_of([&] { read_text_file(path, 6); }),
            path.string() + ": 7 bytes exceed the limit of 6 bytes for this file");
  EXPECT_EQ(read_text_file(write("empty", "")), "");
  EXPECT_EQ(refusal_of([&] { read_text_file(dir_ / "absent.json"); }),
            (dir_ / "absent.json").string() + ": cannot open file: it does not exist");
  EXPECT_EQ(refusal_of([&] { open_regular_file(dir_); }),
            dir_.string() +
                ": not a regular file (a directory, device, pipe or socket): rcsim reads only regular files, whose end "
                "is known");
  // A symbolic link to a regular file is followed.
  fs::create_symlink(path, dir_ / "link");
  EXPECT_EQ(read_text_file(dir_ / "link"), bytes);
}

TEST_F(TextFile, LinesEndWithLfOrCrLfAndTheLastNeedsNone) {
  EXPECT_EQ(lines_of(write("a.csv", "x,y\r\n1,2\n\nlast")),
            (std::vector<std::string>{"1:x,y", "2:1,2", "3:", "4:last"}));
  EXPECT_EQ(lines_of(write("b.csv", "only\n")), (std::vector<std::string>{"1:only"}));
  EXPECT_TRUE(lines_of(write("c.csv", "")).empty());
  LineReader reader(dir_ / "a.csv");
  EXPECT_EQ(reader.path(), (dir_ / "a.csv").string());
  EXPECT_EQ(reader.line_number(), 0);
  // Lines across the reader's buffer refills (2 x 64 KiB): 3000 lines of 100 bytes, each intact.
  std::string text;
  for (int i = 0; i < 3000; ++i) {
    std::string line = std::to_string(i);
    text += line + std::string(99 - line.size(), '.') + "\n";
  }
  const std::vector<std::string> many = lines_of(write("many.csv", text));
  ASSERT_EQ(many.size(), 3000u);
  EXPECT_EQ(many[1310], "1311:1310" + std::string(95, '.'));
  EXPECT_EQ(many[2999], "3000:2999" + std::string(95, '.'));
}

TEST_F(TextFile, ByteOrderMarksCarriageReturnsAndLongLinesAreRefusedByLine) {
  // A byte-order mark is refused on line 1 only; further down it is a line's text.
  EXPECT_EQ(refusal_of([&] { lines_of(write("bom.csv", "\xEF\xBB\xBFt_s\n1\n")); }),
            (dir_ / "bom.csv").string() + ": line 1: starts with a UTF-8 byte-order mark: save the file as UTF-8 without one");
  EXPECT_EQ(lines_of(write("bom2.csv", "t_s\n\xEF\xBB\xBF" "1\n")).size(), 2u);
  EXPECT_EQ(refusal_of([&] { lines_of(write("cr.csv", "a\nb\rc\n")); }),
            (dir_ / "cr.csv").string() +
                ": line 2: holds a carriage return inside the line: lines must end with LF (or CR LF), not CR alone");
  // A file with CR alone, longer than a line may be, is said to be one, not a binary file.
  std::string cr_only;
  for (int i = 0; i < 10000; ++i) cr_only += "0.04,1,2,3\r";
  EXPECT_EQ(refusal_of([&] { lines_of(write("old_mac.csv", cr_only)); }),
            (dir_ / "old_mac.csv").string() + ": line 1: lines end with CR alone (no LF): lines must end with LF or CR LF");
  // A line at the limit is read; one byte more is refused, numbered.
  const std::string at_limit(kMaxLineBytes, 'x');
  EXPECT_EQ(lines_of(write("at.csv", "h\n" + at_limit + "\n")).back().size(), 2 + kMaxLineBytes);
  EXPECT_EQ(refusal_of([&] { lines_of(write("over.csv", "h\n" + at_limit + "x\n")); }),
            (dir_ / "over.csv").string() + ": line 2: line longer than the limit of 65536 bytes (a binary file?)");
  EXPECT_EQ(refusal_of([&] { lines_of(write("tail.csv", "h\n" + at_limit + "x")); }),  // the last, without LF
            (dir_ / "tail.csv").string() + ": line 2: line longer than the limit of 65536 bytes (a binary file?)");
}

TEST_F(TextFile, FnvHashOfAFileChainsByteByByte) {
  constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
  // FNV-1a 64 of "a": (basis ^ 0x61) * 0x100000001b3 = 0xaf63dc4c8601ec8c (the published test vector).
  EXPECT_EQ(fnv1a64_file(write("a", "a"), kOffsetBasis), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64_file(write("empty", ""), 12345u), 12345u);  // no bytes: unchanged
  // Chained: the hash of "ab" is that of "b" continued from the hash of "a".
  EXPECT_EQ(fnv1a64_file(write("ab", "ab"), kOffsetBasis),
            fnv1a64_file(write("b", "b"), fnv1a64_file(dir_ / "a", kOffsetBasis)));
  EXPECT_NE(fnv1a64_file(dir_ / "ab", kOffsetBasis), fnv1a64_file(write("ba", "ba"), kOffsetBasis));
  EXPECT_THROW(fnv1a64_file(dir_, kOffsetBasis), InputError);
}

}  // namespace rcsim::text_file_test
