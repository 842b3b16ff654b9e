// The files of `rcsim merge` (report_merge_files.hpp).
#include "replay/store/report_merge_files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <utility>
#include <vector>

#include "common/input_error.hpp"

namespace rcsim::replay::merge_files {

namespace fs = std::filesystem;

namespace {

// The name of the rcsim executable's host, for the temporary file's name: on a shared filesystem
// a merge judges only the temporary files of its own host by their pid.
std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) return "host";
  std::string host(name.data());
  for (char& c : host) {
    if (c == '/' || c == '-') c = '_';
  }
  return host.empty() ? "host" : host;
}

void remove_with_companions(const fs::path& db) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(db.string() + suffix, ignored);
}

}  // namespace

fs::path temporary_path(const fs::path& output) {
  return output.parent_path() / fmt::format(".{}.merge-{}-{}.tmp", output.filename().string(), host_name(), ::getpid());
}

int remove_stale_temporaries(const fs::path& output) {
  const fs::path dir = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  const std::string prefix = fmt::format(".{}.merge-{}-", output.filename().string(), host_name());
  int removed = 0;
  std::error_code error;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // PID.tmp
    const std::size_t dot = rest.find(".tmp");
    if (dot == 0 || dot == std::string::npos || rest.substr(0, dot).find_first_not_of("0123456789") != std::string::npos ||
        rest.size() != dot + 4 || dot > 9) {
      continue;  // a companion (-wal, -shm) goes with its database, or not ours
    }
    const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dot)));
    // Our own pid: left by an earlier process that had it, since this one has not made its file yet.
    const bool alive = pid != ::getpid() && (::kill(pid, 0) == 0 || errno == EPERM);
    if (!alive) stale.push_back(entry.path());
  }
  for (const fs::path& path : stale) {
    remove_with_companions(path);
    ++removed;
  }
  return removed;
}

void fsync_path(const fs::path& path, int flags, const std::string& name_for_errors) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw InputError(name_for_errors, "", fmt::format("cannot sync {}: {}", path.string(), std::strerror(error)));
  }
  ::close(fd);
}

std::string read_only_uri(const std::string& path) {
  std::error_code error;
  const bool has_wal = fs::exists(path + "-wal", error);
  // immutable=1 reads without locks, which is right only for a file nobody writes: a replay that
  // starts writing a shard the merge reads would make intact pages look "malformed". So only a
  // file this process could not write either (a read-only copy, whose -shm SQLite cannot create).
  const fs::path dir = fs::absolute(path).parent_path();
  const bool writable = ::access(path.c_str(), W_OK) == 0 && ::access(dir.c_str(), W_OK) == 0;
  std::string uri = "file:";
  for (const unsigned char c : fs::absolute(path).lexically_normal().string()) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      uri += static_cast<char>(c);
    } else {
      uri += fmt::format("%{:02X}", c);
    }
  }
  return uri + (has_wal || writable ? "?mode=ro" : "?mode=ro&immutable=1");
}

void install_new(const fs::path& temporary, const fs::path& output) {
  int error = ::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, output.c_str(), RENAME_NOREPLACE) == 0 ? 0 : errno;
  if (error == EINVAL || error == ENOSYS) {
    // A filesystem without RENAME_NOREPLACE: link() refuses an existing name as well.
    error = ::link(temporary.c_str(), output.c_str()) == 0 ? 0 : errno;
    if (error == 0) ::unlink(temporary.c_str());
  }
  if (error == EEXIST) {
    throw InputError(output.string(), "", "created by another process while the merge built it (it did not exist when "
                                          "the merge began): left as it is, nothing merged; merge again to add the "
                                          "runs to it");
  }
  if (error != 0) {
    throw InputError(output.string(), "", fmt::format("cannot move the merged report into place: {}",
                                                      std::strerror(error)));
  }
  fsync_path(output.parent_path().empty() ? fs::path(".") : output.parent_path(), O_RDONLY | O_DIRECTORY,
             output.string());
}

TemporaryDatabase::TemporaryDatabase(fs::path path) : path_(std::move(path)) { remove_with_companions(path_); }

TemporaryDatabase::~TemporaryDatabase() {
  if (!kept_) remove_with_companions(path_);
}

}  // namespace rcsim::replay::merge_files
