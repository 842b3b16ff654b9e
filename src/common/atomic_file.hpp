#pragma once
// Output files appear whole or not at all: written to a temporary file beside the target and
// renamed over it on commit; a writer destroyed without commit removes its temporary file.
// An output is only ever a regular file or a directory rcsim wrote: a device, pipe, socket or
// symbolic link at the output path is refused before anything is written (docs/hardening.md).
#include <filesystem>
#include <fstream>
#include <string>

namespace rcsim {

// Refuses, naming it (InputError), an output path that is a symbolic link or exists as anything but
// a regular file: a rename would replace the link or the device node itself, not write to it.
void check_output_file(const std::filesystem::path& path);

// The same for an output directory that is replaced whole (a recording): refuses a symbolic link,
// anything but a directory, and a non-empty directory without `marker_file` in it, so that only
// what rcsim wrote there before is ever replaced.
void check_output_directory(const std::filesystem::path& path, const std::string& marker_file);

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
  std::string temp_path_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace rcsim
