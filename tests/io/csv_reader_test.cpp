// Strict CSV reading (io/csv_reader.hpp): the header names the columns, quoted fields, blank lines
// skipped, numbers parsed whole and finite; every complaint names the file, line and column.
#include "io/csv_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::csv_reader_test {

namespace fs = std::filesystem;

using testing::refusal_of;

class CsvReaderFile : public testing::ScratchDirTest {
 protected:
  CsvReaderFile() : ScratchDirTest("csv_reader") {}
  std::string write(const std::string& name, const std::string& text) {
    return write_file(name, text).string();
  }
};

TEST_F(CsvReaderFile, ColumnsByNameQuotedFieldsAndBlankLinesSkipped) {
  const std::string path = write("t.csv",
                                 "id,note,x_m\n"
                                 "7,\"a,b\",1.5\n"
                                 "  \t\n"  // blank: skipped, but counted as a line
                                 "-3,\"say \"\"hi\"\"\",-2e3\n"
                                 "8,,0\n");
  CsvReader csv(path, {"x_m", "id"});
  EXPECT_EQ(csv.path(), path);
  EXPECT_EQ(csv.column("id"), 0);
  EXPECT_EQ(csv.column("x_m"), 2);
  EXPECT_EQ(csv.column("y_m"), -1);
  EXPECT_FALSE(csv.has_column("y_m"));
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.line(), 2);
  EXPECT_EQ(csv.integer(0), 7);
  EXPECT_EQ(csv.text(1), "a,b");
  EXPECT_DOUBLE_EQ(csv.number(2), 1.5);
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.line(), 4);
  EXPECT_EQ(csv.integer(0), -3);
  EXPECT_EQ(csv.text(1), "say \"hi\"");
  EXPECT_DOUBLE_EQ(csv.number(2), -2000.0);
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.text(1), "");
  EXPECT_FALSE(csv.next());
}

TEST_F(CsvReaderFile, BadHeadersAndRowsAreRefusedByLine) {
  EXPECT_EQ(refusal_of([&] { CsvReader(write("e.csv", ""), {}); }),
            dir_.string() + "/e.csv: line 1: empty file: expected a header line");
  EXPECT_EQ(refusal_of([&] { CsvReader(write("d.csv", "a,b,a\n"), {}); }),
            dir_.string() + "/d.csv: line 1: column 'a' appears twice in the header");
  EXPECT_EQ(refusal_of([&] { CsvReader(write("m.csv", "\n\nt_s,x_m\n"), {"t_s", "y_m"}); }),
            dir_.string() + "/m.csv: line 3: header lacks the column 'y_m'");  // blank lines before it
  CsvReader short_row(write("s.csv", "a,b\n1,2\n1\n"), {});
  ASSERT_TRUE(short_row.next());
  EXPECT_EQ(refusal_of([&] { short_row.next(); }),
            dir_.string() + "/s.csv: line 3: 1 fields where the header has 2 (truncated or malformed row?)");
  CsvReader open_quote(write("q.csv", "a,b\n1,\"2\n"), {});
  EXPECT_EQ(refusal_of([&] { open_quote.next(); }), dir_.string() + "/q.csv: line 2: a quoted field is not closed");
  EXPECT_EQ(refusal_of([&] { CsvReader(dir_.string() + "/absent.csv", {}); }),
            dir_.string() + "/absent.csv: cannot open file: it does not exist");
}

TEST_F(CsvReaderFile, NumbersMustParseWholeAndBeFinite) {
  CsvReader csv(write("n.csv", "x_m\n1.5\n 1\n+1\n1e999\nnan\n-inf\n10m\n0x1A\n"), {"x_m"});
  const std::string where = dir_.string() + "/n.csv: line ";
  ASSERT_TRUE(csv.next());
  EXPECT_DOUBLE_EQ(csv.number(0), 1.5);
  EXPECT_EQ(refusal_of([&] { csv.integer(0); }), where + "2, column 'x_m': '1.5' is not a whole number");
  for (const auto& [line, message] : {std::pair{3, "' 1' is not a number"},  // no spaces
                                      std::pair{4, "'+1' is not a number"},  // no plus sign
                                      std::pair{5, "'1e999' is not a number"},  // beyond a double
                                      std::pair{6, "'nan' is not finite"}, std::pair{7, "'-inf' is not finite"},
                                      std::pair{8, "'10m' is not a number"},  // no units
                                      std::pair{9, "'0x1A' is not a number"}}) {
    ASSERT_TRUE(csv.next());
    EXPECT_EQ(refusal_of([&] { csv.number(0); }), where + std::to_string(line) + ", column 'x_m': " + message);
  }
  EXPECT_EQ(refusal_of([&] { csv.text(1); }), where + "9: internal: column index out of range");
  EXPECT_EQ(refusal_of([&] { csv.fail(-1, "odd"); }), where + "9, column '?': odd");
}

TEST(CsvField, QuotesOnlyWhatWouldBreakTheRowAndReadsBack) {
  EXPECT_EQ(csv_field("front_left"), "front_left");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
  // What CsvReader reads back is the text (a line break is refused by the reader: fields may not
  // span lines).
  const fs::path dir = testing::fresh_scratch_dir("csv_field");
  std::ofstream(dir / "r.csv") << "a,b\n" << csv_field("x,\"y\"") << ',' << csv_field("z") << '\n';
  CsvReader csv((dir / "r.csv").string(), {"a", "b"});
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.text(0), "x,\"y\"");
  EXPECT_EQ(csv.text(1), "z");
  fs::remove_all(dir);
}

}  // namespace rcsim::csv_reader_test
