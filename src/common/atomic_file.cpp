#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include <fmt/format.h>

#include "common/input_error.hpp"

namespace rcsim {

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
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
  if (!out_) throw InputError(path_, "", "write failed");
  out_.close();
  if (const int fd = ::open(temp_path_.c_str(), O_RDONLY); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    throw InputError(path_, "", std::string("cannot rename output into place: ") + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace rcsim
