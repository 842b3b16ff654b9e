// Output files appear whole or not at all (common/atomic_file.hpp): the writer's temporary file,
// commit and abandonment, and the refusal of links, devices and foreign directories as outputs.
#include "common/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::atomic_file_test {

namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

using testing::refusal_of;

class AtomicFile : public testing::ScratchDirTest {
 protected:
  AtomicFile() : ScratchDirTest("atomic_file") {}
};

TEST_F(AtomicFile, TheTargetChangesOnlyAtCommitAndNoTemporaryIsLeft) {
  const fs::path target = dir_ / "out.csv";
  std::ofstream(target) << "old\n";
  // The temporary file sits beside the target: ".<name>.tmp.<16 random hex digits>".
  fs::path temp;
  {
    AtomicFileWriter writer(target.string());
    writer.stream() << "new\n";
    for (const auto& entry : fs::directory_iterator(dir_)) {
      if (entry.path().filename().string().starts_with(".out.csv.tmp.")) temp = entry.path();
    }
    ASSERT_FALSE(temp.empty());
    EXPECT_EQ(temp.filename().string().size(), std::string(".out.csv.tmp.").size() + 16);
    EXPECT_EQ(contents(target), "old\n");  // not yet replaced
    writer.commit();
  }
  EXPECT_EQ(contents(target), "new\n");
  EXPECT_FALSE(fs::exists(temp));
  // Without commit, the target stays as it was and the temporary file is removed.
  {
    AtomicFileWriter abandoned(target.string());
    abandoned.stream() << "half written";
  }
  EXPECT_EQ(contents(target), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// Issue 51, HIGH 9: links planted at the names a writer would use (the PIDs' names of old, every
// name now) are never written through, and two names drawn are never the same.
TEST_F(AtomicFile, PlantedLinksAtTemporaryNamesAreNeverFollowed) {
  const fs::path victim = dir_ / "victim.txt";
  std::ofstream(victim) << "root's\n";
  for (int pid = ::getpid(); pid < ::getpid() + 50; ++pid) {
    fs::create_symlink(victim, dir_ / (".out.csv.tmp." + std::to_string(pid)));
    fs::create_symlink(victim, dir_ / (".rec.tmp." + std::to_string(pid)));
  }
  {
    AtomicFileWriter writer((dir_ / "out.csv").string());
    writer.stream() << "new\n";
    writer.commit();
  }
  EXPECT_EQ(contents(victim), "root's\n");
  EXPECT_EQ(contents(dir_ / "out.csv"), "new\n");
  EXPECT_NE(random_temp_path(dir_ / "out.csv", "tmp"), random_temp_path(dir_ / "out.csv", "tmp"));
  // A directory is made only where nothing stands: a link to one is not taken for it.
  const fs::path made = create_temp_directory(dir_ / "rec", "tmp");
  EXPECT_TRUE(fs::is_directory(fs::symlink_status(made)));
  EXPECT_TRUE(made.filename().string().starts_with(".rec.tmp."));
}

// An output folder is tried before the work whose result it holds: a folder that exists, or one
// to be made under a writable one, passes and is left as it was; a file where a folder should be is
// refused naming it.
TEST_F(AtomicFile, AnOutputFolderIsTriedBeforeTheWork) {
  EXPECT_NO_THROW(check_output_folder_writable(dir_));
  EXPECT_NO_THROW(check_output_folder_writable(dir_ / "new" / "deeper"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "new"));
  EXPECT_TRUE(std::filesystem::is_empty(dir_)) << "the probe was left behind";
  std::ofstream(dir_ / "file") << "x";
  try {
    check_output_folder_writable(dir_ / "file");
    FAIL() << "a file taken as a folder";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir_ / "file").string());
    EXPECT_NE(std::string(e.what()).find("is not a directory"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_output_folder_writable(dir_ / "file" / "fit"), InputError);
}

TEST_F(AtomicFile, LinksAndSpecialFilesAreRefusedAsOutputsAndNothingIsWritten) {
  std::ofstream(dir_ / "real.csv") << "kept\n";
  fs::create_symlink(dir_ / "real.csv", dir_ / "link.csv");
  ASSERT_EQ(::mkfifo((dir_ / "pipe").c_str(), 0600), 0);
  fs::create_directory(dir_ / "sub");
  EXPECT_NO_THROW(check_output_file(dir_ / "absent.csv"));
  EXPECT_NO_THROW(check_output_file(dir_ / "real.csv"));
  EXPECT_EQ(refusal_of([&] { check_output_file(dir_ / "link.csv"); }),
            (dir_ / "link.csv").string() +
                ": is a symbolic link: rcsim replaces an output whole and would replace the link, not write through "
                "it; give the path it points to");
  for (const char* name : {"pipe", "sub"}) {
    EXPECT_EQ(refusal_of([&] { check_output_file(dir_ / name); }),
              (dir_ / name).string() +
                  ": exists and is not a regular file (a directory, device, pipe or socket): rcsim writes an output "
                  "only as a regular file, and would replace this one");
  }
  // The writer checks before it creates anything: the link and the file behind it stay.
  EXPECT_NE(refusal_of([&] { AtomicFileWriter writer((dir_ / "link.csv").string()); }).find("is a symbolic link"),
            std::string::npos);
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.csv"));
  EXPECT_EQ(contents(dir_ / "real.csv"), "kept\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 4);
  // A directory that does not exist: the file cannot be created, said with the path.
  EXPECT_EQ(refusal_of([&] { AtomicFileWriter writer((dir_ / "missing" / "out.csv").string()); }),
            (dir_ / "missing" / "out.csv").string() + ": cannot create output file: No such file or directory");
  // Issue 51: a folder that takes no new file (/proc/self) named the temporary file's error as if
  // the output were missing: the output is named, and the error said to be its folder's.
  if (fs::is_directory("/proc/self")) {
    EXPECT_EQ(refusal_of([&] { AtomicFileWriter writer("/proc/self/status"); }).rfind(
                  "/proc/self/status: cannot create output file: its folder /proc/self takes no new file (", 0),
              0u);
  }
}

TEST_F(AtomicFile, AnOutputDirectoryIsReplacedOnlyWhenNewEmptyOrMarked) {
  EXPECT_NO_THROW(check_output_directory(dir_ / "new", "recording.json"));
  fs::create_directory(dir_ / "empty");
  EXPECT_NO_THROW(check_output_directory(dir_ / "empty", "recording.json"));
  fs::create_directory(dir_ / "ours");
  std::ofstream(dir_ / "ours" / "recording.json") << "{}";
  EXPECT_NO_THROW(check_output_directory(dir_ / "ours", "recording.json"));
  fs::create_directory(dir_ / "photos");
  std::ofstream(dir_ / "photos" / "holiday.jpg") << "x";
  EXPECT_EQ(refusal_of([&] { check_output_directory(dir_ / "photos", "recording.json"); }),
            (dir_ / "photos").string() +
                ": is a directory without a recording.json: rcsim replaces only what it wrote, give a new or empty "
                "directory");
  // The marker is the one asked for: a report directory's marker does not make it a recording.
  EXPECT_NE(refusal_of([&] { check_output_directory(dir_ / "ours", "report.html"); }).find("without a report.html"),
            std::string::npos);
  std::ofstream(dir_ / "file") << "x";
  EXPECT_EQ(refusal_of([&] { check_output_directory(dir_ / "file", "recording.json"); }),
            (dir_ / "file").string() + ": exists and is not a directory: rcsim would replace it with one");
  fs::create_directory_symlink(dir_ / "ours", dir_ / "link");
  EXPECT_NE(refusal_of([&] { check_output_directory(dir_ / "link", "recording.json"); }).find("is a symbolic link"),
            std::string::npos);
}

}  // namespace rcsim::atomic_file_test
