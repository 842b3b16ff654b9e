// One shard of a campaign (replay/campaign/shard_runner.hpp), called directly: a failing recording
// is reported and the others still run; a run again skips what is stored and redoes only the rest;
// a shard beyond the plan and a report of another campaign are refused, naming what is wrong.
#include "replay/campaign/shard_runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
#include "app/cli/run_rcsim.hpp"
#include "common/json_reader.hpp"
#include "replay/campaign/status.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::campaign::shard_runner_test {

namespace fs = std::filesystem;

class ShardRunnerTest : public rcsim::testing::ScratchDirTest {
 protected:
  ShardRunnerTest() : ScratchDirTest("shard_runner") {}

  // A copy of the bundled standstill_1m (51 cycles: the shortest) under dir_/name.
  fs::path copy_of_standstill(const std::string& name) {
    const fs::path to = dir_ / "recordings" / name;
    fs::create_directories(to);
    fs::copy(testing::kBundledRecordings / "standstill_1m", to, fs::copy_options::recursive);
    return to;
  }
  // A manifest of `recordings` planned into one shard.
  CampaignPlan plan_of(const std::vector<fs::path>& recordings) {
    std::string list;
    for (const fs::path& r : recordings) list += (list.empty() ? "\"" : ", \"") + r.string() + "\"";
    const fs::path path = dir_ / "campaign.json";
    std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "shards", "recordings": [)" << list
                        << R"(], "replay": {"seed": 5}})";
    return write_plan(read_manifest(path), 1, dir_ / "plan", "/usr/bin/true");
  }
  static long long runs_in(const fs::path& report) {
    const auto db = open_report_database(report.string(), false);
    return db->execAndGet("SELECT count(*) FROM runs").getInt64();
  }
};

TEST_F(ShardRunnerTest, AFailingRecordingIsReportedAndARunAgainRedoesOnlyIt) {
  const fs::path good = copy_of_standstill("good"), broken = copy_of_standstill("broken");
  // The second copy differs in one amplitude (not needed since a directory is part of what is
  // stored already, kept so that the two runs differ) ...
  std::string targets = testing::read_file(broken / "targets.csv");
  targets.replace(targets.find(",16.016\n"), 8, ",16.017\n");
  // ... and line 3 of its targets.csv (cycle 3's second row) loses its range: the replay fails there.
  {
    std::string damaged = targets;
    damaged.replace(damaged.find(",2.1262,"), 8, ",x,");
    std::ofstream(broken / "targets.csv") << damaged;
  }
  const CampaignPlan plan = plan_of({good, broken});
  ASSERT_EQ(plan.shards.size(), 1u);
  ASSERT_EQ(plan.shards[0].recordings.size(), 2u);

  std::ostringstream log;
  const ShardOutcome first = run_shard(plan, 0, log);
  EXPECT_EQ(first.stored, 1);
  EXPECT_EQ(first.skipped, 0);
  ASSERT_EQ(first.failures.size(), 1u) << log.str();
  EXPECT_EQ(first.failures[0].rfind(broken.string() + ": " + (broken / "targets.csv").string() + ": line 3", 0), 0u)
      << first.failures[0];
  // One line per recording, in the shard's (path) order: broken before good.
  EXPECT_EQ(log.str().rfind("shard 0: " + broken.string() + ": FAILED: " + (broken / "targets.csv").string() + ": line 3", 0), 0u)
      << log.str();
  EXPECT_NE(log.str().find("\nshard 0: " + good.string() + ": run 1 stored (51 cycles, GOSPA mean "), std::string::npos) << log.str();
  EXPECT_EQ(runs_in(plan.shard_report(0)), 1);

  // Repaired and run again: the stored run is skipped (no second copy), the other replayed.
  std::ofstream(broken / "targets.csv") << targets;
  std::ostringstream again_log;
  const ShardOutcome again = run_shard(plan, 0, again_log);
  EXPECT_EQ(again.stored, 1);
  EXPECT_EQ(again.skipped, 1);
  EXPECT_TRUE(again.failures.empty()) << again_log.str();
  EXPECT_NE(again_log.str().find("shard 0: " + good.string() + ": stored already (run 1), skipped\n"), std::string::npos)
      << again_log.str();
  EXPECT_NE(again_log.str().find("shard 0: " + broken.string() + ": run 2 stored ("), std::string::npos) << again_log.str();
  EXPECT_EQ(runs_in(plan.shard_report(0)), 2);
}

// Two byte-identical recordings in two directories: the plan lists both, so each gets its run, and
// campaign status, which counts runs by directory, calls the shard done (it once stayed unfinished:
// the second copy was skipped as "stored already" under the first's run).
TEST_F(ShardRunnerTest, IdenticalRecordingsInTwoDirectoriesAreTwoRunsAndTheShardIsDone) {
  const fs::path a = copy_of_standstill("a"), b = copy_of_standstill("b");
  const CampaignPlan plan = plan_of({a, b});
  std::ostringstream log;
  const ShardOutcome first = run_shard(plan, 0, log);
  EXPECT_EQ(first.stored, 2) << log.str();
  EXPECT_EQ(first.skipped, 0) << log.str();
  const CampaignStatus status = campaign_status(plan);
  EXPECT_EQ(status.planned, 2);
  EXPECT_EQ(status.stored, 2);
  ASSERT_EQ(status.shards.size(), 1u);
  EXPECT_EQ(status.shards[0].state, ShardState::done);
  std::ostringstream again_log;
  const ShardOutcome again = run_shard(plan, 0, again_log);
  EXPECT_EQ(again.stored, 0) << again_log.str();
  EXPECT_EQ(again.skipped, 2) << again_log.str();
  EXPECT_EQ(runs_in(plan.shard_report(0)), 2);
}

TEST_F(ShardRunnerTest, AShardBeyondThePlanIsRefusedNamingTheShards) {
  const CampaignPlan plan = plan_of({copy_of_standstill("only")});
  for (const int shard : {1, -1}) {
    std::ostringstream log;
    try {
      run_shard(plan, shard, log);
      ADD_FAILURE() << "shard " << shard << " was run";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "--shard");
      EXPECT_EQ(std::string(e.what()),
                "--shard: " + std::to_string(shard) + ": the plan in " + plan.dir.string() + " has shards 0 to 0");
    }
    EXPECT_EQ(log.str(), "");
  }
  EXPECT_FALSE(fs::exists(plan.shard_report(0)));  // refused before any report is opened
}

TEST_F(ShardRunnerTest, AReportBelongsToOneCampaignAndItsCriteria) {
  const auto manifest = [](const std::string& name, const std::string& criteria) {
    CampaignManifest m;
    m.name = name;
    m.document = nlohmann::json::parse(R"({"format": "rcsim-campaign", "version": 1, "name": ")" + name +
                                       R"(", "recordings": ["x"], "criteria": )" + criteria + "}");
    m.criteria = verdict::parse_criteria(JsonField(m.document, "campaign.json", ""));
    return m;
  };
  const std::string path = (dir_ / "report.sqlite").string();
  const auto db = open_report_database(path, true);
  const CampaignManifest mine = manifest("mine", R"([{"figure": "gospa_mean_m", "max": 2}])");
  claim_report_for_campaign(*db, path, mine);  // claimed now
  claim_report_for_campaign(*db, path, mine);  // its own: no refusal
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM campaign").getInt(), 1);
  const auto refusal = [&](const CampaignManifest& m) {
    try {
      claim_report_for_campaign(*db, path, m);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no refusal");
  };
  EXPECT_EQ(refusal(manifest("theirs", R"([{"figure": "gospa_mean_m", "max": 2}])")),
            path + ": campaign: holds the runs of campaign 'mine', not 'theirs'");
  EXPECT_EQ(refusal(manifest("mine", R"([{"figure": "gospa_mean_m", "max": 3}])")),
            path + ": criteria: holds other criteria than the campaign's manifest; plan into a new directory");
}

}  // namespace rcsim::replay::campaign::shard_runner_test
