// rcsim calibrate as a user runs it: fit on a bundled recording, replay and bench with the
// calibration (the bench flags in-sample recordings), and refusals that name the input.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::run_rcsim;

class CalibrateCli : public testing::ScratchDirTest {
 protected:
  CalibrateCli() : ScratchDirTest("calibrate_cli") {}
  static std::string recording(const std::string& name) {
    return (fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / name).string();
  }
};

// The GOSPA mean of `rcsim replay ... --json` (stdout only).
double gospa_of_replay(const std::string& args) {
  const auto r = run_rcsim("replay " + args + " --json", false);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return nlohmann::json::parse(r.output).at("gospa_mean").get<double>();
}

TEST_F(CalibrateCli, FitsThenReplaysAndBenchesWithTheCalibration) {
  const std::string out = (dir_ / "cal").string();
  const auto fit = run_rcsim("calibrate " + recording("front_approach") + " -o " + out +
                             " --fit ercs,slope --initial-step-db 6 --final-step-db 6");
  ASSERT_EQ(fit.exit_code, 0) << fit.output;
  EXPECT_NE(fit.output.find("srr24.amplitude.reference_slope_db_per_m"), std::string::npos) << fit.output;
  const auto index = nlohmann::json::parse(testing::read_file(fs::path(out) / "calibration.json"));
  const double before = index["recordings"][0]["gospa_before_m"].get<double>();
  const double after = index["recordings"][0]["gospa_after_m"].get<double>();
  EXPECT_LT(after, before);

  // replay's figure is the fit's, with and without the calibration.
  const std::string db = (dir_ / "r.sqlite").string();
  EXPECT_NEAR(gospa_of_replay(recording("front_approach") + " --db " + db + " --seed 1"), before, 1e-9);
  EXPECT_NEAR(gospa_of_replay(recording("front_approach") + " --db " + db + " --seed 1 --calibration " + out), after, 1e-9);

  const auto bench = run_rcsim("bench " + recording("front_approach") + " " + recording("standstill_1m") +
                               " --no-reference --levels full --min-cpu-s 0 --calibration " + out);
  ASSERT_EQ(bench.exit_code, 0) << bench.output;
  EXPECT_NE(bench.output.find("fitted on front_approach (their errors are in-sample)"), std::string::npos) << bench.output;
}

TEST_F(CalibrateCli, RefusalsNameTheInput) {
  const auto group = run_rcsim("calibrate " + recording("front_approach") + " -o " + (dir_ / "x").string() + " --fit ercs,colour");
  EXPECT_EQ(group.exit_code, 2);
  EXPECT_NE(group.output.find("--fit"), std::string::npos) << group.output;
  EXPECT_NE(group.output.find("colour"), std::string::npos) << group.output;
  EXPECT_FALSE(fs::exists(dir_ / "x"));

  const auto steps = run_rcsim("calibrate " + recording("front_approach") + " -o " + (dir_ / "x").string() +
                               " --initial-step-db 1 --final-step-db 3");
  EXPECT_EQ(steps.exit_code, 2) << steps.output;
  EXPECT_NE(steps.output.find("--final-step-db"), std::string::npos) << steps.output;

  const auto missing = run_rcsim("replay " + recording("front_approach") + " --db " + (dir_ / "r.sqlite").string() +
                                 " --calibration " + dir_.string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("calibration.json"), std::string::npos) << missing.output;

  // A start directory that is no calibration is refused before the search, and nothing is written.
  const auto start = run_rcsim("calibrate " + recording("standstill_1m") + " -o " + (dir_ / "x").string() +
                               " --start " + dir_.string());
  EXPECT_EQ(start.exit_code, 2) << start.output;
  EXPECT_NE(start.output.find("calibration.json"), std::string::npos) << start.output;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
}

}  // namespace
}  // namespace rcsim
