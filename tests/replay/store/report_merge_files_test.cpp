// The files of `rcsim merge` (replay/store/report_merge_files.hpp): a new report is moved into
// place only where no file is; one that another process created meanwhile is never replaced.
#include "replay/store/report_merge_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "common/input_error.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::merge_files {
namespace {

namespace fs = std::filesystem;

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class ReportMergeFiles : public testing::ScratchDirTest {
 protected:
  ReportMergeFiles() : ScratchDirTest("report_merge_files") {}
};

TEST_F(ReportMergeFiles, ANewReportIsMovedIntoPlaceOnlyWhereNoFileIs) {
  const fs::path output = dir_ / "campaign.sqlite", temporary = temporary_path(output);
  EXPECT_EQ(temporary.parent_path(), dir_);
  std::ofstream(temporary) << "merged";
  install_new(temporary, output);
  EXPECT_EQ(text_of(output), "merged");
  EXPECT_FALSE(fs::exists(temporary));
  // Someone else's output appeared meanwhile: refused naming it, both files as they were.
  std::ofstream(temporary) << "merged again";
  try {
    install_new(temporary, output);
    ADD_FAILURE() << "replaced an existing output";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(output.string() + ": created by another process while the merge built it"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(text_of(output), "merged");
  EXPECT_EQ(text_of(temporary), "merged again");
}

TEST_F(ReportMergeFiles, TheTemporaryFileGoesUnlessInstalled) {
  const fs::path output = dir_ / "campaign.sqlite", temporary = temporary_path(output);
  {
    TemporaryDatabase db(temporary);
    std::ofstream(temporary) << "half a report";
    std::ofstream(temporary.string() + "-journal") << "its journal";
  }
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_FALSE(fs::exists(temporary.string() + "-journal"));
  {
    TemporaryDatabase db(temporary);
    std::ofstream(temporary) << "a report";
    install_new(temporary, output);
    db.installed();
  }
  EXPECT_EQ(text_of(output), "a report");
}

}  // namespace
}  // namespace rcsim::replay::merge_files
