// rcsim replay opens with its verdict (docs/verdicts.md): on a synthetic track recording and on
// the real drive, the default tolerances of its kind, --criteria defaults as a gate, and a run
// of the same identity judged again but not stored twice unless --again.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::run_rcsim;

class VerdictCli : public testing::ScratchDirTest {
 protected:
  VerdictCli() : ScratchDirTest("verdict_cli") {}
  std::string db() const { return (dir_ / "r.sqlite").string(); }
  static std::string bundled(const char* name) { return (testing::kBundledRecordings / name).string(); }
  int runs() const {
    SQLite::Database d(db());
    return d.execAndGet("SELECT count(*) FROM runs").getInt();
  }
};

// The lines of text before `marker`.
std::string before(const std::string& text, const std::string& marker) { return text.substr(0, text.find(marker)); }

TEST_F(VerdictCli, ATrackRecordingOpensWithItsVerdictAgainstTheTrackTolerances) {
  const auto r = run_rcsim(fmt::format("replay {} --db {} --seed 1", bundled("front_approach"), db()));
  ASSERT_EQ(r.exit_code, 0) << r.output;  // the defaults inform; they are no gate
  // The first line says the verdict; the figures come after the tolerances.
  EXPECT_EQ(r.output.rfind("run 1: front_approach: FAIL; stored in ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("verdict: FAIL, "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("default tolerances for tracks"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tracks; srr24 x2, fidelity full"), std::string::npos) << r.output;
  // front_approach: 196 simulated against 105 recorded targets, far outside 0.8 .. 1.25.
  EXPECT_NE(r.output.find("FAIL  target_count_ratio"), std::string::npos) << r.output;
  EXPECT_EQ(before(r.output, "all targets:").find("objects:"), std::string::npos) << r.output;
  // Asked for as a gate, the same verdict exits 3; the run is judged, not stored again.
  const auto gate = run_rcsim(fmt::format("replay {} --db {} --seed 1 --criteria defaults", bundled("front_approach"), db()));
  EXPECT_EQ(gate.exit_code, 3) << gate.output;
  EXPECT_EQ(runs(), 1);
}

TEST_F(VerdictCli, AReplayOfAStoredRunSaysSoAndStoresNothingUnlessAgain) {
  const std::string replay = fmt::format("replay {} --db {} --seed 1", bundled("overtaking"), db());
  ASSERT_EQ(run_rcsim(replay).exit_code, 0);
  const auto again = run_rcsim(replay);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("run 1: overtaking: "), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("stored already"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("--again"), std::string::npos) << again.output;
  EXPECT_EQ(runs(), 1);
  const auto json = run_rcsim(replay + " --json", false);
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto parsed = nlohmann::json::parse(json.output);
  EXPECT_EQ(parsed["already_stored"], true);
  EXPECT_EQ(parsed["run_id"], 1);
  EXPECT_EQ(runs(), 1);
  // Another seed is another run; --again stores a second copy of the same.
  ASSERT_EQ(run_rcsim(fmt::format("replay {} --db {} --seed 2", bundled("overtaking"), db())).exit_code, 0);
  EXPECT_EQ(runs(), 2);
  ASSERT_EQ(run_rcsim(replay + " --again").exit_code, 0);
  EXPECT_EQ(runs(), 3);
}

TEST_F(VerdictCli, TheRealDriveIsJudgedOnItsObjectsAndBackgroundNotOnAllTargetGospa) {
  if (!fs::is_directory(testing::kAimotiveRaw)) {
    GTEST_SKIP() << "real data absent (" << testing::kAimotiveRaw.string() << "): real-drive verdict test skipped";
  }
  const std::string rec = (dir_ / "aimotive").string();
  ASSERT_EQ(run_rcsim(fmt::format("import --from aimotive {} -o {}", testing::kAimotiveRaw.string(), rec)).exit_code, 0);
  const auto r = run_rcsim(fmt::format("replay {} --db {} --seed 1", rec, db()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("detections; aimotive_lrr x2, fidelity no_tracking"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("default tolerances for detections"), std::string::npos) << r.output;
  const std::string verdict = before(r.output, "all targets:");
  EXPECT_NE(verdict.find("gospa_object_mean_m"), std::string::npos) << r.output;
  EXPECT_NE(verdict.find("kolmogorov_smirnov.background_range"), std::string::npos) << r.output;
  EXPECT_EQ(verdict.find("  gospa_mean_m"), std::string::npos) << r.output;  // all-target GOSPA is not judged
  EXPECT_NE(r.output.find("(not judged: the background is drawn from a density"), std::string::npos) << r.output;
  // The built-in profile has no background density: 0.99 simulated against 31.9 recorded per cycle.
  EXPECT_NE(verdict.find("FAIL  background_target_count_ratio"), std::string::npos) << r.output;
  SQLite::Database d(db());
  EXPECT_EQ(d.execAndGet("SELECT level FROM runs").getString(), "detections");
}

TEST_F(VerdictCli, AReplayRefusedForADamagedRowLeavesNoDatabaseItCreated) {
  const fs::path damaged = dir_ / "overtaking";
  fs::copy(testing::kBundledRecordings / "overtaking", damaged);
  {
    std::ofstream(damaged / "targets.csv", std::ios::app) << "garbage,row\n";  // found at the end of the replay
  }
  const auto r = run_rcsim(fmt::format("replay {} --db {}", damaged.string(), db()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("targets.csv"), std::string::npos) << r.output;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) EXPECT_FALSE(fs::exists(db() + suffix)) << suffix;
  // A report that existed keeps its runs, and is not removed.
  ASSERT_EQ(run_rcsim(fmt::format("replay {} --db {}", bundled("overtaking"), db())).exit_code, 0);
  EXPECT_EQ(run_rcsim(fmt::format("replay {} --db {}", damaged.string(), db())).exit_code, 2);
  EXPECT_EQ(runs(), 1);
  // A report in a directory that does not exist is refused by name, before the replay.
  const std::string orphan = (dir_ / "no_such_dir" / "r.sqlite").string();
  const auto no_dir = run_rcsim(fmt::format("replay {} --db {}", bundled("overtaking"), orphan));
  EXPECT_EQ(no_dir.exit_code, 2) << no_dir.output;
  EXPECT_NE(no_dir.output.find(orphan + ": cannot create the report database: no directory"), std::string::npos)
      << no_dir.output;
}

}  // namespace
}  // namespace rcsim
