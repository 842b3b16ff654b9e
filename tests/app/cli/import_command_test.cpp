// `rcsim import --from DATASET` as a user runs it: the importers listed in --help, --frames, a
// mistyped dataset directory, the Astyx parent directory (both datasets) refused naming both,
// --frames refused where it has no meaning. Exit 2 and nothing written on every refusal.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::import_cli_test {

namespace fs = std::filesystem;

using rcsim::testing::run_rcsim;

class ImportCli : public rcsim::testing::ScratchDirTest {
 protected:
  ImportCli() : ScratchDirTest("import_cli") {}
  // Runs `rcsim import ARGS -o DIR/rec`; a refusal must exit 2 and leave no recording.
  rcsim::testing::CommandResult refused(const std::string& args) {
    const fs::path out = dir_ / "rec";
    auto r = run_rcsim("import " + args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
    return r;
  }
  static bool have_astyx() { return fs::is_directory(rcsim::testing::kAstyxRaw / "dataset_astyx_demo"); }
};

TEST_F(ImportCli, HelpListsTheImportersAndFrames) {
  const auto r = run_rcsim("import --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("aimotive:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("astyx:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--frames LIST"), std::string::npos) << r.output;
}

TEST_F(ImportCli, AMistypedDatasetDirectoryIsNamed) {
  const auto r = refused("--from astyx " + (dir_ / "dataset_astyx_hires2109").string());
  EXPECT_NE(r.output.find("rcsim: error: " + (dir_ / "dataset_astyx_hires2109").string() + ": no such directory"),
            std::string::npos)
      << r.output;
  const auto unknown = refused("--from astyks " + dir_.string());
  EXPECT_NE(unknown.output.find("unknown dataset 'astyks' (known: aimotive, astyx, mcap, rosbag2, vod)"), std::string::npos) << unknown.output;
  const auto empty = refused("--from astyx " + dir_.string());
  EXPECT_NE(empty.output.find("no Astyx dataset here"), std::string::npos) << empty.output;
}

TEST_F(ImportCli, FramesNeedFromAndAreRefusedByTheAimotiveImporter) {
  const auto without_from = refused(dir_.string() + " --frames 0-9");
  EXPECT_NE(without_from.output.find("--frames requires --from"), std::string::npos) << without_from.output;
  if (!fs::is_directory(rcsim::testing::kAimotiveRaw)) {
    GTEST_SKIP() << "real data absent (" << rcsim::testing::kAimotiveRaw.string() << "): the aimotive --frames refusal skipped";
  }
  const auto aimotive = refused("--from aimotive " + rcsim::testing::kAimotiveRaw.string() + " --frames 0-9");
  EXPECT_NE(aimotive.output.find("--frames: an aiMotive sequence is one drive"), std::string::npos) << aimotive.output;
}

TEST_F(ImportCli, TheAstyxParentDirectoryIsRefusedNamingBothDatasets) {
  if (!have_astyx()) GTEST_SKIP() << "real data absent (" << rcsim::testing::kAstyxRaw.string() << "): Astyx CLI tests skipped";
  const fs::path raw = rcsim::testing::kAstyxRaw;
  const auto r = refused("--from astyx " + raw.string());
  EXPECT_NE(r.output.find("holds 2 Astyx datasets"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((raw / "dataset_astyx_demo").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((raw / "dataset_astyx_hires2019").string()), std::string::npos) << r.output;
  // A mistyped dataset beside the real ones: they are named.
  const auto typo = refused("--from astyx " + (raw / "dataset_astyx_hires2109").string());
  EXPECT_NE(typo.output.find("no such directory; the Astyx datasets beside it:"), std::string::npos) << typo.output;
  EXPECT_NE(typo.output.find("dataset_astyx_hires2019"), std::string::npos) << typo.output;
  // A folder of a dataset: the dataset named.
  const auto folder = refused("--from astyx " + (raw / "dataset_astyx_demo" / "radar_hires1").string() + "/");
  const std::string dataset = (fs::absolute(raw) / "dataset_astyx_demo").lexically_normal().string();
  EXPECT_NE(folder.output.find("a folder of the Astyx dataset " + dataset + ": give the dataset directory"), std::string::npos)
      << folder.output;
  // A frame the dataset does not hold.
  const auto frame = refused("--from astyx " + (raw / "dataset_astyx_demo").string() + " --frames 0-5");
  EXPECT_NE(frame.output.find("rcsim: error: --frames: frame 5 is not in"), std::string::npos) << frame.output;
  // And the import that works: what it prints.
  const auto ok = run_rcsim("import --from astyx " + (raw / "dataset_astyx_demo").string() + " --frames 0,4 -o " +
                            (dir_ / "standing").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("dataset_astyx_demo frames 0,4: 2 cycles, 1 sensor,"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "standing" / "recording.json"));
}

}  // namespace rcsim::import_cli_test
