#pragma once
// Reading input files with stated bounds (schemas/limits.md): only regular files (a device such
// as /dev/zero or /dev/urandom, or a pipe, may never end), a whole file up to a size limit, a
// line up to a length limit. Every refusal is an InputError naming the file (and the line).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace rcsim {

inline constexpr std::uintmax_t kMaxTextFileBytes = 256ull << 20;  // a JSON document: 256 MiB
inline constexpr std::size_t kMaxLineBytes = 64u << 10;            // a CSV line: 64 KiB

// Opens `path` for reading, refusing what is not a regular file (after symlinks).
std::ifstream open_regular_file(const std::filesystem::path& path);

// A whole file as text, up to max_bytes.
std::string read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxTextFileBytes);

// Reads a regular file line by line through a fixed buffer: no line longer than kMaxLineBytes is
// ever held (such a line is refused), so a file of any size is read in bounded memory.
class LineReader {
 public:
  explicit LineReader(std::filesystem::path path);
  // The next line without its '\n' (a trailing '\r' removed); false at the end of the file. The
  // view stays valid until the next call.
  bool next(std::string_view& line);
  int line_number() const { return line_number_; }
  const std::string& path() const { return path_text_; }

 private:
  bool fill();
  // Refuses a byte-order mark on line 1 and a carriage return inside a line, naming the line.
  void check_line(std::string_view line) const;
  std::string path_text_;
  std::ifstream in_;
  std::string buffer_;
  std::size_t begin_ = 0, end_ = 0;  // unread bytes in buffer_
  bool eof_ = false;
  int line_number_ = 0;
};

// The fields of a line separated by spaces and tabs (a dataset's text rows: Astyx, KITTI).
std::vector<std::string_view> whitespace_fields(std::string_view line);

// A field that must be a finite decimal number; an InputError naming `file` and `where` (the text
// quoted where it is short and printable) otherwise.
double finite_number_field(std::string_view text, const std::string& file, const std::string& where);

// FNV-1a 64 of a file's bytes, chained onto `hash`, read through a fixed buffer.
std::uint64_t fnv1a64_file(const std::filesystem::path& path, std::uint64_t hash);

}  // namespace rcsim
