// rcsim models --sensors --export and rcsim profile derive from the command line (issue 30):
// what is written, and the refusals with status 2 that write nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

#include <nlohmann/json.hpp>

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

// Every value with its source, weak mark and interval (issue 48), printed, in --json and in the
// report, on the model's own drive (docs/examples/round_trip/lined_road.json) derived from srr24:
// the base's values listed as such, the derived numbers each with an interval.
TEST_F(ProfileCli, DeriveGivesEachValueItsIntervalAndMarkInTheTableTheJsonAndTheReport) {
  const fs::path rec = dir_ / "lined", profile = dir_ / "lined.json", page = dir_ / "lined.html";
  const std::string scene = (fs::path(RCSIM_SOURCE_DIR) / "docs/examples/round_trip/lined_road.json").string();
  ASSERT_EQ(run_rcsim(fmt::format("simulate {} --seed 7 --format recording -o {}", scene, rec.string())).exit_code, 0);
  const auto json = run_rcsim(fmt::format("profile derive {} --base srr24 -o {} --json --report {}", rec.string(), profile.string(), page.string()));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const nlohmann::json printed = nlohmann::json::parse(json.output);
  int derived_numbers = 0, base_values = 0;
  for (const nlohmann::json& v : printed.at("values")) {
    ASSERT_TRUE(v.contains("weak") && v.contains("interval")) << v.dump();
    if (v.at("source") == "base") ++base_values;
    if (v.at("source") != "derived" || !v.at("value").is_number()) continue;
    ++derived_numbers;
    ASSERT_TRUE(v.at("interval").is_array()) << v.dump();
    EXPECT_LE(v.at("interval").at(0).get<double>(), v.at("value").get<double>() + 1e-9) << v.dump();
    EXPECT_GE(v.at("interval").at(1).get<double>(), v.at("value").get<double>() - 1e-9) << v.dump();
  }
  EXPECT_GE(derived_numbers, 15);
  EXPECT_GE(base_values, 10);  // tracking, clutter, multibounce, monopulse, ...
  const std::string html = read_file(page);
  EXPECT_NE(html.find("<th>source</th><th>interval</th>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>tracking.gate_chi2</td>"), std::string::npos);
  const auto table = run_rcsim(fmt::format("profile derive {} --base srr24 -o {}", rec.string(), profile.string()));
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("monopulse.pointer_noise_sigma"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("resolution.range_cell_m"), std::string::npos) << table.output;
  const std::string description = load_sensor_config_file(profile.string()).description;
  EXPECT_NE(description.find("taken from the base: "), std::string::npos) << description;
}

}  // namespace
}  // namespace rcsim
