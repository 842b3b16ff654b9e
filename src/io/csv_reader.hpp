#pragma once
// Strict CSV reading for the files of a recording: the header names the columns, every data row
// has exactly that many fields, numbers must parse whole and be finite, and every complaint names
// the file, the line and the column. Fields may be quoted ("a,b", "say ""hi""") but may not span
// lines.
#include <string>
#include <string_view>
#include <vector>

#include "common/text_file.hpp"

namespace rcsim {

class CsvReader {
 public:
  // Opens the file and reads its header; refuses a missing file, a special file (a device or
  // pipe), an empty file, a missing required column or a duplicate column name. Lines longer
  // than kMaxLineBytes are refused (text_file.hpp): a file of any size is read in bounded memory.
  CsvReader(std::string path, const std::vector<std::string_view>& required_columns);

  // Reads the next data row (blank lines are skipped); false at the end of the file.
  bool next();

  // Index of a column (required ones always exist); -1 for an absent optional column.
  int column(std::string_view name) const;
  bool has_column(std::string_view name) const { return column(name) >= 0; }

  double number(int column) const;          // finite
  long long integer(int column) const;      // whole number
  const std::string& text(int column) const;
  int line() const { return line_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(int column, const std::string& message) const;
  [[noreturn]] void fail_line(const std::string& message) const;

 private:
  bool read_fields();

  std::string path_;
  LineReader in_;
  std::vector<std::string> header_;
  std::vector<std::string> fields_;
  int line_ = 0;
};

// A field as CSV writes it: quoted (with doubled quotes) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text);

}  // namespace rcsim
