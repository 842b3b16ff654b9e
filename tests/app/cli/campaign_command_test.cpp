// rcsim campaign plan / run-local / run-shard, then rcsim merge, as a user runs them: the merged
// report equals a serial replay figure for figure; a shard killed mid-run and run again redoes
// only the run it had not finished; rcsim replay --criteria gives exit status 3 and JUnit.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <fstream>
#include <map>
#include <set>
#include <csignal>

#include "end_to_end/campaign_figures.hpp"
#include "app/cli/run_rcsim.hpp"
#include "replay/verdict/run_figures.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::testing {
namespace {

const std::vector<std::string> kCampaignRecordings = {"close_front", "front_approach", "overtaking", "two_in_one_cell"};

class CampaignCli : public ScratchDirTest {
 protected:
  CampaignCli() : ScratchDirTest("campaign_cli") {}
  std::filesystem::path write_manifest(const std::string& extra = "") {
    std::string recordings;
    for (const auto& r : kCampaignRecordings) recordings += (recordings.empty() ? "\"" : ", \"") + (kBundledRecordings / r).string() + "\"";
    const auto path = dir_ / "campaign.json";
    std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "cli-test", "recordings": [)"
                        << recordings << R"(], "replay": {"seed": 3}, "criteria": [{"figure": "gospa_mean_m", "max": 100}])"
                        << extra << "}";
    return path;
  }
  std::string dir(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(CampaignCli, RunLocalThenMergeEqualsASerialReplay) {
  const auto plan = run_rcsim(fmt::format("campaign plan {} --shards 2 -o {}", write_manifest().string(), dir("plan")));
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("4 recordings"), std::string::npos) << plan.output;
  const auto local = run_rcsim(fmt::format("campaign run-local {} -j 2", dir("plan")));
  ASSERT_EQ(local.exit_code, 0) << local.output;
  EXPECT_NE(local.output.find("all 2 shards done"), std::string::npos) << local.output;
  const auto status = run_rcsim(fmt::format("campaign status {}", dir("plan")));
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("4 of 4 recordings stored"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("shard 1: done, "), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("all 2 shards done; next: rcsim merge"), std::string::npos) << status.output;
  const auto merge = run_rcsim(fmt::format("merge {0}/shards/shard-0000.sqlite {0}/shards/shard-0001.sqlite -o {1}",
                                           dir("plan"), dir("campaign.sqlite")));
  ASSERT_EQ(merge.exit_code, 0) << merge.output;

  for (const auto& r : kCampaignRecordings) {
    const auto serial = run_rcsim(fmt::format("replay {} --db {} --seed 3 --store summary", (kBundledRecordings / r).string(),
                                              dir("serial.sqlite")));
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
  }
  const auto merged = figures_by_recording(dir_ / "campaign.sqlite");
  const auto serial = figures_by_recording(dir_ / "serial.sqlite");
  ASSERT_EQ(merged.size(), kCampaignRecordings.size());
  EXPECT_EQ(merged, serial);  // figure for figure, bit for bit

  EXPECT_NE(merge.output.find("verdicts: 4 of 4 runs passed 1 criterion per recording; 0 of 0 campaign criteria passed"),
            std::string::npos)
      << merge.output;

  // Judged again by stricter criteria: every run fails, exit status 3, JUnit lists the failures.
  std::ofstream(dir_ / "strict.json") << R"({"format": "rcsim-criteria", "version": 1, "criteria": [
      {"figure": "gospa_mean_m", "max": 0}, {"figure": "gospa_mean_m", "scope": "campaign", "statistic": "max", "max": 1e6}]})";
  const auto strict = run_rcsim(fmt::format("merge {0}/shards/shard-0000.sqlite -o {1} --criteria {2} --junit {3}",
                                            dir("plan"), dir("campaign.sqlite"), dir("strict.json"), dir("junit.xml")));
  EXPECT_EQ(strict.exit_code, 3) << strict.output;
  EXPECT_NE(strict.output.find("0 of 4 runs passed"), std::string::npos) << strict.output;
  EXPECT_NE(strict.output.find("pass campaign: max gospa_mean_m = "), std::string::npos) << strict.output;
  EXPECT_NE(read_file(dir_ / "junit.xml").find(R"(tests="5" failures="4")"), std::string::npos);

  // FILE judged that merge only: the campaign's report keeps its manifest's criterion, so merging
  // the shards again is no refusal (other criteria) but a merge with nothing new, judged as before.
  const auto again_merged = run_rcsim(fmt::format("merge {0}/shards/shard-0000.sqlite {0}/shards/shard-0001.sqlite -o {1} --json",
                                                  dir("plan"), dir("campaign.sqlite")));
  ASSERT_EQ(again_merged.exit_code, 0) << again_merged.output;
  const auto json = nlohmann::json::parse(again_merged.output.substr(again_merged.output.find('{')));
  EXPECT_EQ(json["added"], 0);
  EXPECT_EQ(json["criteria"], 1);
  EXPECT_EQ(json["verdicts"]["passed"], true);
  EXPECT_EQ(json["verdicts"]["runs"], 4);
  EXPECT_EQ(json["verdicts"]["criteria"][0]["text"], "gospa_mean_m <= 100");

  // A bad criteria file is refused before anything is merged: no output is made.
  std::ofstream(dir_ / "bad.json") << R"({"format": "rcsim-criteria", "version": 1, "criteria": [{"figure": "gospa", "max": 1}]})";
  const auto bad = run_rcsim(fmt::format("merge {0}/shards/shard-0000.sqlite -o {1} --criteria {2}", dir("plan"),
                                         dir("never.sqlite"), dir("bad.json")));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.json: criteria[0].figure: unknown figure 'gospa'"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "never.sqlite"));

  // Run again: every shard finds its runs stored and replays nothing.
  const auto again = run_rcsim(fmt::format("campaign run-shard {} --shard 0", dir("plan")));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 runs stored"), std::string::npos) << again.output;
}

TEST_F(CampaignCli, APlanBeyondSlurmsDefaultArraySizeSaysSo) {
  // 1,002 recordings (links to one) in 1,002 shards: task ids 0 to 1001, one beyond MaxArraySize.
  const std::filesystem::path many = dir_ / "many";
  std::filesystem::create_directories(many);
  for (int i = 0; i < 1002; ++i) {
    std::filesystem::create_directory_symlink(kBundledRecordings / "close_front", many / fmt::format("r{:04d}", i));
  }
  const auto path = dir_ / "many.json";
  std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "many", "recordings": [")"
                      << (many / "*").string() << R"("]})";
  const auto plan = run_rcsim(fmt::format("campaign plan {} --shards 100000 -o {}", path.string(), dir("plan")));
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("note: 1002 array tasks; Slurm's default MaxArraySize takes 1001"), std::string::npos)
      << plan.output.substr(0, 2000);
  const auto few = run_rcsim(fmt::format("campaign plan {} --shards 2 -o {}", write_manifest().string(), dir("few")));
  EXPECT_EQ(few.output.find("MaxArraySize"), std::string::npos) << few.output;
}

TEST_F(CampaignCli, AShardKilledMidRunRedoesOnlyWhatIsMissing) {
  ASSERT_EQ(run_rcsim(fmt::format("campaign plan {} --shards 1 -o {}", write_manifest().string(), dir("plan"))).exit_code, 0);
  // Killed (SIGKILL, as from outside) in the middle of a run's transaction: the first run of the
  // shard that reaches 400 sensor cycles is overtaking (251 cycles x 2 sensors), the third;
  // close_front (176 x 2) and front_approach (101 x 2) are stored before.
  const std::string command = fmt::format("RCSIM_TEST_KILL_AFTER_CYCLES=400 {} campaign run-shard {} --shard 0 > {} 2>&1",
                                          RCSIM_KILLABLE_BINARY, dir("plan"), dir("killed.log"));
  const int status = std::system(command.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGKILL) << read_file(dir_ / "killed.log");
  const auto report = dir_ / "plan" / "shards" / "shard-0000.sqlite";
  {
    SQLite::Database db(report.string());
    EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
    EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs").getInt(), 2);  // the first two, whole; no trace of the third
  }
  const auto where = run_rcsim(fmt::format("campaign status {}", dir("plan")));
  EXPECT_NE(where.output.find("2 of 4 recordings stored"), std::string::npos) << where.output;
  EXPECT_NE(where.output.find("shard 0: unfinished, 2 of 4 stored"), std::string::npos) << where.output;
  EXPECT_NE(where.output.find("rcsim campaign submit '" + dir("plan") + "' --shards 0\n"), std::string::npos) << where.output;
  const auto rerun = run_rcsim(fmt::format("campaign run-shard {} --shard 0", dir("plan")));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("2 runs stored, 2 stored before, 0 failed"), std::string::npos) << rerun.output;
  SQLite::Database db(report.string());
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
  std::set<std::string> keys;
  for (const auto& [run, identity] : replay::stored_run_identities(db)) keys.insert(identity.key());
  EXPECT_EQ(keys.size(), 4u);  // four runs, no two alike
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM summaries").getInt(), 4);
}

TEST_F(CampaignCli, ReplayCriteriaExitStatusAndJunit) {
  const auto criteria = dir_ / "criteria.json";
  std::ofstream(criteria) << R"({"format": "rcsim-criteria", "version": 1, "criteria": [{"figure": "gospa_mean_m", "max": 0.0}]})";
  const auto failed = run_rcsim(fmt::format("replay {} --db {} --criteria {} --junit {}", (kBundledRecordings / "front_approach").string(),
                                            dir("r.sqlite"), criteria.string(), dir("junit.xml")));
  EXPECT_EQ(failed.exit_code, 3) << failed.output;
  EXPECT_NE(failed.output.find("run 1: front_approach: FAIL"), std::string::npos) << failed.output;
  EXPECT_NE(failed.output.find("FAIL  gospa_mean_m"), std::string::npos) << failed.output;
  EXPECT_NE(read_file(dir_ / "junit.xml").find("<failure message=\"gospa_mean_m = "), std::string::npos);
  // The criteria stay in the report: the next replay is judged by them without --criteria, and
  // a passing criterion gives exit status 0. (The same run again: judged, not stored again.)
  std::ofstream(criteria) << R"({"format": "rcsim-criteria", "version": 1, "criteria": [{"figure": "gospa_mean_m", "max": 1000}]})";
  EXPECT_EQ(run_rcsim(fmt::format("replay {} --db {} --criteria {}", (kBundledRecordings / "front_approach").string(), dir("r.sqlite"),
                                  criteria.string()))
                .exit_code,
            0);
  // A file that is no criteria document is refused before the replay: no third run is stored.
  const auto bad = run_rcsim(fmt::format("replay {} --db {} --criteria {}", (kBundledRecordings / "front_approach").string(),
                                         dir("r.sqlite"), (dir_ / "r.sqlite").string()));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  SQLite::Database db(dir("r.sqlite"));
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  // --json carries the verdicts.
  const auto json = run_rcsim(fmt::format("replay {} --db {} --json", (kBundledRecordings / "front_approach").string(), dir("r.sqlite")));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto summary = nlohmann::json::parse(json.output.substr(json.output.find('{')));
  EXPECT_EQ(summary["verdicts"]["passed"], true);
  EXPECT_EQ(summary["verdicts"]["criteria"][0]["text"], "gospa_mean_m <= 1000");
}

}  // namespace
}  // namespace rcsim::testing
