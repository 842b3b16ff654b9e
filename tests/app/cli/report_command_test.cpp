// `rcsim report` as a user runs it: a page that opens with the run's verdict, and refusals (a
// missing or damaged database, a run it does not hold, a bad word) with exit status 2, the file or
// option named, and an earlier page left as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::report_command_test {

namespace fs = std::filesystem;
using rcsim::testing::read_file;
using rcsim::testing::run_rcsim;

const std::string kRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/standstill_1m";

class ReportCli : public rcsim::testing::ScratchDirTest {
 protected:
  ReportCli() : ScratchDirTest("report_cli") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = (dir_ / "r.sqlite").string();
    ASSERT_EQ(run_rcsim("replay " + kRecording + " --db " + db_).exit_code, 0);
  }
  std::string db_;
};

TEST_F(ReportCli, ThePageOpensWithTheRunsVerdict) {
  const fs::path html = dir_ / "r.html";
  const auto r = run_rcsim("report " + db_ + " -o " + html.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rcsim report: wrote " + html.string()), std::string::npos) << r.output;
  const std::string page = read_file(html);
  const auto run_heading = page.find("<h2>Run 1: standstill_1m");
  const auto verdict = page.find("class=\"verdict pass\"");
  ASSERT_NE(run_heading, std::string::npos);
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_LT(verdict - run_heading, 2000u) << "the verdict is not at the top of the run's section";
  EXPECT_EQ(page.find("<h2>Speed against error"), std::string::npos) << "no bench was stored";
}

TEST_F(ReportCli, WhatCannotBeReportedIsRefusedNamingItAndTheEarlierPageStays) {
  const fs::path html = dir_ / "r.html";
  std::ofstream(html) << "earlier page";
  std::ofstream(dir_ / "bad.sqlite") << "garbage";
  const std::string out = " -o " + html.string();
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"report " + db_ + out + " --run 9", "no run with id 9 (the database holds runs 1 to 1, 1 in all)"},
      {"report " + (dir_ / "none.sqlite").string() + out, "none.sqlite: no such report database"},
      {"report " + (dir_ / "bad.sqlite").string() + out, "bad.sqlite: cannot use as a report database"},
      {"report " + db_ + out + " --campaign sometimes", "--campaign: sometimes not in {auto,always,never,only}"},
      {"report " + db_ + out + " --pictures 21", "--pictures"},
      {"report " + db_, "--output is required"},
  };
  for (const auto& [args, message] : refused) {
    const auto r = run_rcsim(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << ": " << r.output;
    EXPECT_EQ(read_file(html), "earlier page") << args;
  }
  const auto no_directory = run_rcsim("report " + db_ + " -o " + (dir_ / "no_dir" / "r.html").string());
  EXPECT_EQ(no_directory.exit_code, 2);
  EXPECT_NE(no_directory.output.find("no_dir/r.html: cannot create output file"), std::string::npos) << no_directory.output;
}

}  // namespace rcsim::report_command_test
