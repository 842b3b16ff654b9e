#include "io/csv_reader.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "common/input_error.hpp"

namespace rcsim {

namespace {

// Splits one line into fields; false if a quote is left open.
bool split_csv_line(std::string_view line, std::vector<std::string>& fields) {
  fields.clear();
  if (line.find('"') == std::string_view::npos) {  // the common case: no quotes
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = line.find(',', start);
      fields.emplace_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
      if (comma == std::string_view::npos) return true;
      start = comma + 1;
    }
  }
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else {
      field += c;
    }
  }
  fields.push_back(std::move(field));
  return !quoted;
}

}  // namespace

CsvReader::CsvReader(std::string path, const std::vector<std::string_view>& required_columns)
    : path_(std::move(path)), in_(path_) {
  if (!read_fields()) throw InputError(path_, "line 1", "empty file: expected a header line");
  header_ = fields_;
  for (std::size_t i = 0; i < header_.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (header_[i] == header_[j]) fail_line(fmt::format("column '{}' appears twice in the header", header_[i]));
    }
  }
  for (const auto name : required_columns) {
    if (column(name) < 0) fail_line(fmt::format("header lacks the column '{}'", name));
  }
}

bool CsvReader::read_fields() {
  std::string_view line_text;
  while (in_.next(line_text)) {
    line_ = in_.line_number();
    if (line_text.find_first_not_of(" \t") == std::string_view::npos) continue;
    if (!split_csv_line(line_text, fields_)) fail_line("a quoted field is not closed");
    return true;
  }
  return false;
}

bool CsvReader::next() {
  if (!read_fields()) return false;
  if (fields_.size() != header_.size()) {
    fail_line(fmt::format("{} fields where the header has {} (truncated or malformed row?)", fields_.size(),
                          header_.size()));
  }
  return true;
}

int CsvReader::column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return static_cast<int>(i);
  }
  return -1;
}

double CsvReader::number(int col) const {
  const std::string& field = text(col);
  double value = 0.0;
  const char* first = field.data();
  const char* last = field.data() + field.size();
  const auto [end, error] = std::from_chars(first, last, value);
  if (field.empty() || error != std::errc() || end != last) fail(col, fmt::format("'{}' is not a number", field));
  if (!std::isfinite(value)) fail(col, fmt::format("'{}' is not finite", field));
  return value;
}

long long CsvReader::integer(int col) const {
  const std::string& field = text(col);
  long long value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (field.empty() || error != std::errc() || end != field.data() + field.size()) {
    fail(col, fmt::format("'{}' is not a whole number", field));
  }
  return value;
}

const std::string& CsvReader::text(int col) const {
  if (col < 0 || col >= static_cast<int>(fields_.size())) fail_line("internal: column index out of range");
  return fields_[static_cast<std::size_t>(col)];
}

void CsvReader::fail(int col, const std::string& message) const {
  const std::string name = col >= 0 && col < static_cast<int>(header_.size()) ? header_[col] : std::string("?");
  throw InputError(path_, fmt::format("line {}, column '{}'", line_, name), message);
}

void CsvReader::fail_line(const std::string& message) const {
  throw InputError(path_, fmt::format("line {}", line_), message);
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace rcsim
