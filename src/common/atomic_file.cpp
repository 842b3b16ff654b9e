#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/input_error.hpp"

namespace rcsim {

namespace {

// What stands at `path`, without following a symbolic link: nullopt if nothing does.
std::optional<mode_t> existing_node(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) return st.st_mode;
  if (errno == ENOENT) return std::nullopt;
  throw InputError(path.string(), "", std::string("cannot use as output: ") + std::strerror(errno));
}

[[noreturn]] void refuse_link(const std::filesystem::path& path) {
  throw InputError(path.string(), "",
                   "is a symbolic link: rcsim replaces an output whole and would replace the link, not write "
                   "through it; give the path it points to");
}

}  // namespace

void check_output_file(const std::filesystem::path& path) {
  const auto mode = existing_node(path);
  if (!mode || S_ISREG(*mode)) return;
  if (S_ISLNK(*mode)) refuse_link(path);
  throw InputError(path.string(), "",
                   "exists and is not a regular file (a directory, device, pipe or socket): rcsim writes an output "
                   "only as a regular file, and would replace this one");
}

void check_output_directory(const std::filesystem::path& path, const std::string& marker_file) {
  const auto mode = existing_node(path);
  if (!mode) return;
  if (S_ISLNK(*mode)) refuse_link(path);
  if (!S_ISDIR(*mode)) {
    throw InputError(path.string(), "", "exists and is not a directory: rcsim would replace it with one");
  }
  std::error_code error;
  if (std::filesystem::is_empty(path, error) || std::filesystem::exists(path / marker_file, error)) return;
  throw InputError(path.string(), "",
                   fmt::format("is a directory without a {}: rcsim replaces only what it wrote, give a new or empty "
                               "directory",
                               marker_file));
}

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  check_output_file(path_);
  const auto target = std::filesystem::path(path_);
  temp_path_ = (target.parent_path() / fmt::format(".{}.tmp.{}", target.filename().string(), ::getpid())).string();
  out_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(path_, "", std::string("cannot create output file: ") + std::strerror(errno));
}

AtomicFileWriter::~AtomicFileWriter() {
  if (!committed_) {
    out_.close();
    std::remove(temp_path_.c_str());
  }
}

void AtomicFileWriter::commit() {
  out_.flush();
  if (!out_) {
    // Not bad input: the disk is full, or the file system failed; nothing replaced the target.
    throw std::runtime_error(fmt::format("{}: cannot write the output: {}; the file is left as it was", path_,
                                         std::strerror(errno != 0 ? errno : EIO)));
  }
  out_.close();
  if (const int fd = ::open(temp_path_.c_str(), O_RDONLY); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  check_output_file(path_);  // again: a node may have appeared while the output was written
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    throw InputError(path_, "", std::string("cannot rename output into place: ") + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace rcsim
