#pragma once
// The files of `rcsim merge` (report_merge.cpp), apart from what is in them: the temporary output
// `.NAME.merge-HOST-PID.tmp` a new report is built in beside the output and moved into place, the
// leftovers of merges that died, syncs, and the read-only URI an input is opened by.
#include <filesystem>
#include <string>

namespace rcsim::replay::merge_files {

// The temporary output of this process's merge into `output`, beside it. The host is in the name:
// on a shared filesystem a merge judges only the temporary files of its own host by their pid.
std::filesystem::path temporary_path(const std::filesystem::path& output);

// Removes the temporary files `.NAME.merge-HOST-PID.tmp` (and their -wal, -shm, -journal) of
// merges into this output on this host whose process is gone. Returns how many it removed.
int remove_stale_temporaries(const std::filesystem::path& output);

// Syncs the file or directory at `path`, opened with `flags`; an InputError naming
// `name_for_errors` if it cannot.
void fsync_path(const std::filesystem::path& path, int flags, const std::string& name_for_errors);

// The `file:` URI that opens an input read-only, so that it is never written. A report is in WAL
// mode; a read-only connection to it makes an empty -wal and -shm beside it where there are none,
// and cannot remove them. A shard with no -wal was closed by its last writer and has nobody
// writing it: it is read as immutable, leaving nothing behind (and readable from a read-only
// directory). One with a -wal (a writer killed after a commit, or still at work) is read with its
// WAL.
std::string read_only_uri(const std::string& path);

// Moves the finished temporary output to `output`, which must not exist: an output that another
// process created meanwhile (a replay into it) is never replaced, but refused naming it. Then
// syncs the directory, so that the new name survives a power loss. renameat2(RENAME_NOREPLACE),
// or link() and unlink() on a filesystem without it.
void install_new(const std::filesystem::path& temporary, const std::filesystem::path& output);

// The temporary output (with its -wal, -shm, -journal), removed on construction and again on
// destruction unless it was moved into place.
class TemporaryDatabase {
 public:
  explicit TemporaryDatabase(std::filesystem::path path);
  ~TemporaryDatabase();
  TemporaryDatabase(const TemporaryDatabase&) = delete;
  TemporaryDatabase& operator=(const TemporaryDatabase&) = delete;
  const std::filesystem::path& path() const { return path_; }
  void installed() { kept_ = true; }

 private:
  std::filesystem::path path_;
  bool kept_ = false;
};

}  // namespace rcsim::replay::merge_files
