// The files of `rcsim merge` (report_merge_files.hpp).
#include "replay/store/report_merge_files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
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
  std::string uri = "file:";
  for (const unsigned char c : fs::absolute(path).lexically_normal().string()) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      uri += static_cast<char>(c);
    } else {
      uri += fmt::format("%{:02X}", c);
    }
  }
  return uri + (has_wal ? "?mode=ro" : "?mode=ro&immutable=1");
}

FileState file_state(const fs::path& path) {
  FileState state;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return state;
  state.exists = true;
  state.device = st.st_dev;
  state.inode = st.st_ino;
  state.size = st.st_size;
  state.mtime_ns = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  struct stat wal {};
  state.wal_written = ::stat((path.string() + "-wal").c_str(), &wal) == 0 && wal.st_size > 0;
  return state;
}

TemporaryDatabase::TemporaryDatabase(fs::path path) : path_(std::move(path)) { remove_with_companions(path_); }

TemporaryDatabase::~TemporaryDatabase() {
  if (!kept_) remove_with_companions(path_);
}

}  // namespace rcsim::replay::merge_files
