// One owner of the report database (docs/architecture.md): outside replay/store/ no source of the
// product or its bench tools names SQLite or writes SQL; they hold a ReportDatabase and ask the
// store (replay/store/report_database.hpp). The one other database read is a robot's: a ROS 2 bag's
// SQLite storage files, read by src/io/rosbag2_reader.cpp, which never opens a report.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace rcsim {
namespace {

namespace fs = std::filesystem;

TEST(StoreOwnsSql, NoSourceOutsideTheStoreNamesSqliteOrWritesSql) {
  const fs::path root = RCSIM_SOURCE_DIR;
  const std::regex sql(R"re(SQLite::|SQLiteCpp|\b(SELECT|INSERT INTO|UPDATE|DELETE FROM|CREATE TABLE)\b [a-z_*])re");
  int files = 0;
  for (const char* top : {"src", "metrics", "replay", "app", "bench"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string rel = fs::relative(entry.path(), root).string();
      if (rel.rfind("replay/store/", 0) == 0 || rel == "src/io/rosbag2_reader.cpp") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        EXPECT_FALSE(std::regex_search(line, sql)) << rel << ":" << number << ": " << line;
      }
    }
  }
  EXPECT_GT(files, 150);
}

}  // namespace
}  // namespace rcsim
