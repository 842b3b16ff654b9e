#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <optional>
#include <random>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

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

// An output stream's buffer over a file descriptor (std::ofstream cannot open with O_EXCL and
// O_NOFOLLOW). A failed write leaves the stream bad; commit() then refuses to rename.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* data = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      const ssize_t written = ::write(fd_, data, left);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) return false;
      data += written;
      left -= static_cast<std::size_t>(written);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }
  int fd_;
  std::vector<char> buffer_;
};

// Tries to make something at a fresh random name until one is free (EEXIST: taken, by chance or
// by design); at most this many names, then the last error.
constexpr int kTempNameAttempts = 64;

}  // namespace

std::filesystem::path random_temp_path(const std::filesystem::path& target, std::string_view tag) {
  static thread_local std::random_device device;
  const std::uint64_t bits = (static_cast<std::uint64_t>(device()) << 32) ^ device();
  return target.parent_path() / fmt::format(".{}.{}.{:016x}", target.filename().string(), tag, bits);
}

int create_temp_file(const std::filesystem::path& target, std::filesystem::path& temp_path) {
  for (int attempt = 0; attempt < kTempNameAttempts; ++attempt) {
    temp_path = random_temp_path(target, "tmp");
    const int fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST) break;
  }
  // The error is the temporary file's, in the output's folder: said as such (issue 51: `-o
  // /proc/self/status`, which exists, was "cannot create output file: No such file or directory").
  const int error = errno;
  const std::filesystem::path folder = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  std::error_code ignored;
  if (!std::filesystem::is_directory(folder, ignored)) {
    throw InputError(target.string(), "", std::string("cannot create output file: ") + std::strerror(error));
  }
  throw InputError(target.string(), "",
                   fmt::format("cannot create output file: its folder {} takes no new file ({} for a temporary file there; "
                               "rcsim writes an output beside it and renames it into place)",
                               folder.string(), std::strerror(error)));
}

std::filesystem::path create_temp_directory(const std::filesystem::path& target, std::string_view tag) {
  for (int attempt = 0; attempt < kTempNameAttempts; ++attempt) {
    std::filesystem::path path = random_temp_path(target, tag);
    if (::mkdir(path.c_str(), 0777) == 0) return path;
    if (errno != EEXIST) break;
  }
  throw InputError(target.string(), "", std::string("cannot create a directory beside it: ") + std::strerror(errno));
}

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

void check_output_folder_writable(const std::filesystem::path& path) {
  const std::filesystem::path folder = std::filesystem::absolute(path).lexically_normal();
  std::filesystem::path existing = folder;
  while (!existing_node(existing) && existing.has_relative_path()) existing = existing.parent_path();
  const std::string name = existing == folder ? path.string() : existing.string();
  const std::string role = existing == folder ? "" : fmt::format(" (the folder {} would be made in)", path.string());
  struct stat st {};
  if (::stat(existing.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw InputError(name, "", fmt::format("is not a directory{}: the output cannot be written there", role));
  }
  const std::filesystem::path probe = random_temp_path(existing / "probe", "tmp");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int error = errno;
    throw InputError(name, "", fmt::format("cannot be written{}: {}; nothing was done", role, std::strerror(error)));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  check_output_file(path_);
  fd_ = create_temp_file(path_, temp_path_);
  buffer_ = std::make_unique<DescriptorBuffer>(fd_);
  out_.rdbuf(buffer_.get());
}

AtomicFileWriter::~AtomicFileWriter() {
  if (!committed_) {
    if (fd_ >= 0) ::close(fd_);
    ::unlink(temp_path_.c_str());
  }
}

void AtomicFileWriter::commit() {
  out_.flush();
  if (!out_ || ::fsync(fd_) != 0) {
    // Not bad input: the disk is full, or the file system failed; nothing replaced the target.
    throw std::runtime_error(fmt::format("{}: cannot write the output: {}; the file is left as it was", path_,
                                         std::strerror(errno != 0 ? errno : EIO)));
  }
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    throw std::runtime_error(fmt::format("{}: cannot write the output: {}; the file is left as it was", path_, std::strerror(errno)));
  }
  check_output_file(path_);  // again: a node may have appeared while the output was written
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    throw InputError(path_, "", std::string("cannot rename output into place: ") + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace rcsim
