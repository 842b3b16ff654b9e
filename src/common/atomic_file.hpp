#pragma once
// Output files appear whole or not at all: written to a temporary file beside the target and
// renamed over it on commit; a writer destroyed without commit removes its temporary file.
// An output is only ever a regular file or a directory rcsim wrote: a device, pipe, socket or
// symbolic link at the output path is refused before anything is written (docs/hardening.md).
#include <filesystem>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>

namespace rcsim {

// Refuses, naming it (InputError), an output path that is a symbolic link or exists as anything but
// a regular file: a rename would replace the link or the device node itself, not write to it.
void check_output_file(const std::filesystem::path& path);

// The same for an output directory that is replaced whole (a recording): refuses a symbolic link,
// anything but a directory, and a non-empty directory without `marker_file` in it, so that only
// what rcsim wrote there before is ever replaced.
void check_output_directory(const std::filesystem::path& path, const std::string& marker_file);

// Refuses, naming it (InputError), an output folder that files cannot be written into, before a
// long computation whose result it is to hold (rcsim calibrate): the folder, or where it does not
// exist yet the nearest folder above it that does, must be a directory that takes a new file
// (tried: a temporary file made and removed, so a read-only file system or a missing permission
// is found whoever runs it). Nothing is left behind.
void check_output_folder_writable(const std::filesystem::path& path);

// A temporary name beside `target` that no one can guess: ".NAME.TAG.RANDOM", 16 hex digits drawn
// from std::random_device (a PID is no secret: a planted link at the next PIDs' names would be
// written through).
std::filesystem::path random_temp_path(const std::filesystem::path& target, std::string_view tag);

// A new regular file beside `target`, opened for writing: O_CREAT | O_EXCL | O_NOFOLLOW (nothing
// that stands at the name, a symbolic link least of all, is ever opened), mode 0666 less the
// umask, under a new random name while one is taken. Its descriptor; its path in `temp_path`.
int create_temp_file(const std::filesystem::path& target, std::filesystem::path& temp_path);

// A new directory beside `target` likewise: mkdir(2) fails on anything standing at the name and
// never follows a link there. Its path.
std::filesystem::path create_temp_directory(const std::filesystem::path& target, std::string_view tag);

class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::string path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  std::ostream& stream() { return out_; }
  // Flushes, syncs and renames the temporary file onto the target path.
  void commit();

 private:
  std::string path_;
  std::filesystem::path temp_path_;
  int fd_ = -1;
  std::unique_ptr<std::streambuf> buffer_;  // writes to fd_
  std::ostream out_{nullptr};
  bool committed_ = false;
};

}  // namespace rcsim
