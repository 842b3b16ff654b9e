// rcsim models --sensors --export and rcsim profile derive from the command line (issue 30):
// what is written, and the refusals with status 2 that write nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

#include "app/cli/run_rcsim.hpp"
#include "common/json_reader.hpp"
#include "scratch_dir.hpp"
#include "sensor/sensor_config.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_rcsim;

class ProfileCli : public testing::ScratchDirTest {
 protected:
  ProfileCli() : ScratchDirTest("profile_cli") {}
};

TEST_F(ProfileCli, ExportWritesTheBuiltInProfileAsAFileThatLoadsAsItIs) {
  const fs::path out = dir_ / "lrr.json";
  const auto result = run_rcsim(fmt::format("models --sensors --export aimotive_lrr -o {}", out.string()));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(read_file(out), std::string(builtin_sensor_text("aimotive_lrr")));
  EXPECT_EQ(load_sensor_config_file(out.string()).name, "aimotive_lrr");
}

TEST_F(ProfileCli, AnUnknownProfileNamesEveryBuiltInOneAndTheNearest) {
  const fs::path out = dir_ / "x.json";
  const auto result = run_rcsim(fmt::format("models --sensors --export aimotive-lrr -o {}", out.string()));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("did you mean \"aimotive_lrr\"?"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("built-in: aimotive_lrr, astyx_hires, srr24"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run_rcsim("models --export srr24").exit_code, 2);  // --sensors forgotten: said, not ignored
}

TEST_F(ProfileCli, DeriveRefusesARecordingOfTracksWithStatus2AndWritesNothing) {
  const fs::path out = dir_ / "p.json";
  const auto result = run_rcsim(fmt::format("profile derive {} -o {}", (testing::kBundledRecordings / "two_in_one_cell").string(), out.string()));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("reports tracks; a profile is derived from raw detections"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(ProfileCli, DeriveWritesAProfileReplayReadsAndAReportWithItsFits) {
  if (!fs::is_directory(testing::kAimotiveRaw)) {
    GTEST_SKIP() << "real data absent (" << testing::kAimotiveRaw.string() << "): profile derive --report is not checked";
  }
  const fs::path rec = dir_ / "rec", profile = dir_ / "mine.json", page = dir_ / "mine.html";
  ASSERT_EQ(run_rcsim(fmt::format("import --from aimotive {} -o {}", testing::kAimotiveRaw.string(), rec.string())).exit_code, 0);
  const auto result = run_rcsim(fmt::format("profile derive {} -o {} --report {}", rec.string(), profile.string(), page.string()));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(load_sensor_config_file(profile.string()).name, "mine");
  const std::string html = read_file(page);
  EXPECT_NE(html.find("SNR - RCS against range"), std::string::npos);
  EXPECT_NE(html.find("Range distances of pairs at one radial speed"), std::string::npos);
  EXPECT_NE(html.find("amplitude.range_exponent"), std::string::npos);
  const auto replayed = run_rcsim(fmt::format("replay {} --sensor {} --db {}", rec.string(), profile.string(), (dir_ / "r.sqlite").string()));
  EXPECT_EQ(replayed.exit_code, 0) << replayed.output;
}

}  // namespace
}  // namespace rcsim
