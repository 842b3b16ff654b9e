#include "common/text_file.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <sstream>
#include <system_error>

#include "common/input_error.hpp"
#include "common/safe_text.hpp"

namespace rcsim {

namespace fs = std::filesystem;

std::ifstream open_regular_file(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) throw InputError(path.string(), "", "cannot open file: it does not exist");
  if (!fs::is_regular_file(status)) {
    throw InputError(path.string(), "",
                     "not a regular file (a directory, device, pipe or socket): rcsim reads only regular files, "
                     "whose end is known");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", std::string("cannot open file: ") + std::strerror(errno));
  return in;
}

std::string read_text_file(const fs::path& path, std::uintmax_t max_bytes) {
  std::ifstream in = open_regular_file(path);
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > max_bytes) {
    throw InputError(path.string(), "",
                     fmt::format("{} bytes exceed the limit of {} bytes for this file", size, max_bytes));
  }
  std::string text;
  text.reserve(error ? 0 : static_cast<std::size_t>(size));
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      throw InputError(path.string(), "", fmt::format("longer than the limit of {} bytes for this file", max_bytes));
    }
  }
  return text;
}

LineReader::LineReader(fs::path path) : path_text_(path.string()), in_(open_regular_file(path)) {
  buffer_.resize(2 * kMaxLineBytes);
}

bool LineReader::fill() {
  if (eof_) return false;
  if (begin_ > 0) {  // move the unread tail to the front
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  in_.read(buffer_.data() + end_, static_cast<std::streamsize>(buffer_.size() - end_));
  const auto n = static_cast<std::size_t>(in_.gcount());
  end_ += n;
  if (n == 0) eof_ = true;
  return n > 0;
}

bool LineReader::next(std::string_view& line) {
  std::size_t scanned = begin_;
  for (;;) {
    const void* newline = std::memchr(buffer_.data() + scanned, '\n', end_ - scanned);
    if (newline != nullptr) {
      const std::size_t at = static_cast<std::size_t>(static_cast<const char*>(newline) - buffer_.data());
      line = std::string_view(buffer_.data() + begin_, at - begin_);
      begin_ = at + 1;
      break;
    }
    if (end_ - begin_ > kMaxLineBytes) {
      const bool cr_only = std::memchr(buffer_.data() + begin_, '\r', end_ - begin_) != nullptr;
      throw InputError(path_text_, fmt::format("line {}", line_number_ + 1),
                       cr_only ? "lines end with CR alone (no LF): lines must end with LF or CR LF"
                               : fmt::format("line longer than the limit of {} bytes (a binary file?)", kMaxLineBytes));
    }
    scanned = end_ - begin_;  // relative to the front after fill()
    if (!fill()) {
      if (begin_ == end_) return false;
      line = std::string_view(buffer_.data() + begin_, end_ - begin_);  // a last line without '\n'
      begin_ = end_;
      break;
    }
  }
  if (line.size() > kMaxLineBytes) {
    throw InputError(path_text_, fmt::format("line {}", line_number_ + 1),
                     fmt::format("line longer than the limit of {} bytes (a binary file?)", kMaxLineBytes));
  }
  ++line_number_;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  check_line(line);
  return true;
}

void LineReader::check_line(std::string_view line) const {
  // What an editor or a spreadsheet adds, named as such rather than as a broken first column.
  if (line_number_ == 1 && line.starts_with("\xEF\xBB\xBF")) {
    throw InputError(path_text_, "line 1", "starts with a UTF-8 byte-order mark: save the file as UTF-8 without one");
  }
  if (line.find('\r') != std::string_view::npos) {
    throw InputError(path_text_, fmt::format("line {}", line_number_),
                     "holds a carriage return inside the line: lines must end with LF (or CR LF), not CR alone");
  }
}

std::uint64_t fnv1a64_file(const fs::path& path, std::uint64_t hash) {
  std::ifstream in = open_regular_file(path);
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      hash ^= static_cast<unsigned char>(chunk[i]);
      hash *= 0x100000001b3ULL;
    }
  }
  return hash;
}

std::vector<std::string_view> whitespace_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > begin) fields.push_back(line.substr(begin, i - begin));
  }
  return fields;
}

double finite_number_field(std::string_view text, const std::string& file, const std::string& where) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    const bool printable = text.size() <= 40 && !find_control_character(text);
    throw InputError(file, where, printable ? fmt::format("'{}' is not a number", text) : std::string("not a number"));
  }
  if (!std::isfinite(value)) throw InputError(file, where, fmt::format("{} is not finite", text));
  return value;
}

}  // namespace rcsim
