// Planning a campaign (replay/campaign/plan.hpp, manifest.hpp): the shard balance computed by
// hand, the recorded duration, the batch script, and what of a manifest reaches the script.
#include "replay/campaign/plan.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "io/recording.hpp"
#include "app/cli/run_rcsim.hpp"
#include "replay/campaign/manifest_fixtures.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::campaign {
namespace {


TEST(BalanceShards, LongestFirstOntoTheLeastLoaded) {
  // 5, 4, 3, 3, 3 into two: 5 -> A, 4 -> B, 3 -> B (7), 3 -> A (8), 3 -> B (10). LPT's makespan is
  // 10 where the best is 9 (5 + 4 | 3 + 3 + 3): within Graham's 4/3.
  std::vector<PlannedRecording> r;
  for (const auto& [name, d] : std::vector<std::pair<std::string, double>>{{"a", 3}, {"b", 5}, {"c", 3}, {"d", 4}, {"e", 3}}) {
    r.push_back({name, d});
  }
  const auto shards = balance_shards(r, 2);
  ASSERT_EQ(shards.size(), 2u);
  EXPECT_DOUBLE_EQ(shards[0].duration_s, 8.0);
  EXPECT_DOUBLE_EQ(shards[1].duration_s, 10.0);
  ASSERT_EQ(shards[0].recordings.size(), 2u);
  EXPECT_EQ(shards[0].recordings[0].dir, "b");  // each shard in path order
  EXPECT_EQ(shards[1].recordings.size(), 3u);
  // One shard per recording at most is the caller's choice; more shards than recordings leave some empty.
  EXPECT_EQ(balance_shards(r, 7)[6].recordings.size(), 0u);
}

TEST(RecordedDuration, IsTheEgoLogsSpanPlusOneCycle) {
  for (const char* name : {"front_approach", "city_drive_60s"}) {
    const Recording rec = read_recording(testing::kBundledRecordings / name);
    EXPECT_NEAR(recorded_duration_s(testing::kBundledRecordings / name),
                rec.ego.back().t_s - rec.ego.front().t_s + rec.cycle_time_s, 1e-9)
        << name;
  }
}

class PlanTest : public rcsim::testing::ManifestFileTest {
 protected:
  PlanTest() : ManifestFileTest("plan") {}
};

TEST_F(PlanTest, WritesPlanAndBatchScriptAndReadsThemBack) {
  const auto manifest = read_manifest(write_manifest(
      R"("recordings": [")" + (testing::kBundledRecordings / "[fo]*").string() + R"(", ")" + (testing::kBundledRecordings / "close_front").string() +
      R"("], "replay": {"seed": 7, "store": "full"}, "criteria": [{"figure": "gospa_mean_m", "max": 2}],
      "slurm": {"partition": "cpu", "time_limit": "00:30:00", "extra": ["--qos=short"]})"));
  ASSERT_EQ(manifest.recordings.size(), 3u);  // front_approach, overtaking, close_front; sorted
  EXPECT_EQ(manifest.recordings[0].filename(), "close_front");
  const auto plan = write_plan(manifest, 2, dir_ / "plan", "/opt/rcsim/bin/rcsim");
  ASSERT_EQ(plan.shards.size(), 2u);
  const std::string script = rcsim::testing::read_file(dir_ / "plan" / "campaign.sbatch");
  for (const char* line : {"#SBATCH --array=0-1\n", "#SBATCH --partition=cpu\n", "#SBATCH --time=00:30:00\n",
                           "#SBATCH --qos=short\n", "exec '/opt/rcsim/bin/rcsim' campaign run-shard '"}) {
    EXPECT_NE(script.find(line), std::string::npos) << line << " in\n" << script;
  }
  const CampaignPlan back = read_plan(dir_ / "plan");
  EXPECT_EQ(back.manifest.name, "t");
  EXPECT_EQ(back.manifest.replay.options.seed, 7u);
  EXPECT_EQ(back.manifest.replay.store, StoreLevel::full);
  EXPECT_EQ(back.manifest.criteria, manifest.criteria);
  ASSERT_EQ(back.shards.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    ASSERT_EQ(back.shards[s].recordings.size(), plan.shards[s].recordings.size());
    EXPECT_DOUBLE_EQ(back.shards[s].duration_s, plan.shards[s].duration_s);
  }
  EXPECT_EQ(back.shard_report(1), dir_ / "plan" / "shards" / "shard-0001.sqlite");
  // A second plan into the same directory is refused: its shard reports would mix. So is a
  // directory holding other files, and read_plan says what is wrong with a path that is no plan.
  EXPECT_THROW(write_plan(manifest, 2, dir_ / "plan", "/opt/rcsim/bin/rcsim"), InputError);
  std::filesystem::create_directories(dir_ / "busy");
  std::ofstream(dir_ / "busy" / "notes.txt") << "mine";
  try {
    write_plan(manifest, 2, dir_ / "busy", "/opt/rcsim/bin/rcsim");
    ADD_FAILURE() << "a non-empty directory was planned into";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not an empty directory"), std::string::npos) << e.what();
  }
  const auto read_error = [](const std::filesystem::path& dir) {
    try {
      read_plan(dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(read_error(dir_ / "nothing").find("no such plan directory"), std::string::npos);
  EXPECT_NE(read_error(dir_ / "busy" / "notes.txt").find("not a directory"), std::string::npos);
  EXPECT_NE(read_error(dir_ / "busy").find("no campaign plan here"), std::string::npos);
}

TEST_F(PlanTest, NothingInAManifestReachesTheBatchScriptButAsItsOwnLine) {
  const std::string recordings = R"("recordings": [")" + (testing::kBundledRecordings / "close_front").string() + R"("])";
  const auto manifest_with_name = [&](const std::string& json_name) {
    const auto path = dir_ / "named.json";
    std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": )" << json_name << ", " << recordings << "}";
    return path;
  };
  // A newline would end the #SBATCH lines and start a command; CR, NUL and U+2028 as well.
  for (const char* name : {R"("A\ntouch INJECTED;#")", R"("A\rB")", R"("A\u0000B")", R"("A\u2028B")", R"("a b")",
                           "\"$(id)\"", R"("")", R"("-x")"}) {
    try {
      read_manifest(manifest_with_name(name));
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("named.json: name: "), std::string::npos) << e.what();
    }
  }
  // A slurm field or a sbatch option with a line separator.
  EXPECT_NE(error_of(recordings + R"(, "slurm": {"partition": "cpu\u2028touch X"})").find("slurm.partition: must be one line"),
            std::string::npos);
  EXPECT_NE(error_of(recordings + R"(, "slurm": {"extra": ["--qos=a\rb"]})").find("slurm.extra[0]"), std::string::npos);
  // A plan directory whose path would break an #SBATCH line.
  const auto manifest = read_manifest(write_manifest(recordings));
  EXPECT_THROW(write_plan(manifest, 1, dir_ / "a\nb", "/opt/rcsim/bin/rcsim"), InputError);
  EXPECT_THROW(write_plan(manifest, 1, dir_ / "a\"b", "/opt/rcsim/bin/rcsim"), InputError);
  // A path with a space is quoted where the script names it.
  write_plan(manifest, 1, dir_ / "with space", "/opt/rcsim/bin/rcsim");
  const std::string script = rcsim::testing::read_file(dir_ / "with space" / "campaign.sbatch");
  EXPECT_NE(script.find("#SBATCH --output=\"" + (dir_ / "with space" / "logs").string() + "/slurm-%A_%a.out\"\n"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("campaign run-shard '" + (dir_ / "with space").string() + "'"), std::string::npos) << script;
}

}  // namespace
}  // namespace rcsim::replay::campaign
