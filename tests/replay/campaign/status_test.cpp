// Where a planned campaign stands (replay/campaign/status.hpp): stored runs are found in the
// shard reports, failures in the shards' logs (run-local's and Slurm's), the last attempt wins,
// and the unfinished shards come out as `submit --shards` ranges.
#include "replay/campaign/status.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "replay/campaign/shard_runner.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::campaign {
namespace {


TEST(IndexRanges, RunsOfConsecutiveIndicesBecomeRanges) {
  EXPECT_EQ(index_ranges({}), "");
  EXPECT_EQ(index_ranges({4}), "4");
  EXPECT_EQ(index_ranges({0, 1}), "0-1");
  EXPECT_EQ(index_ranges({0, 3, 4, 5, 9, 11, 12}), "0,3-5,9,11-12");
}

class CampaignStatusTest : public rcsim::testing::ScratchDirTest {
 protected:
  CampaignStatusTest() : ScratchDirTest("campaign_status") {}

  // Four bundled recordings in three shards (LPT by duration: shard 0 holds one recording).
  CampaignPlan plan() {
    const auto path = dir_ / "campaign.json";
    std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "status", "recordings": [")"
                        << (testing::kBundledRecordings / "close_front").string() << R"(", ")" << (testing::kBundledRecordings / "front_approach").string()
                        << R"(", ")" << (testing::kBundledRecordings / "overtaking").string() << R"(", ")"
                        << (testing::kBundledRecordings / "two_in_one_cell").string() << R"("], "replay": {"seed": 3}})";
    return write_plan(read_manifest(path), 3, dir_ / "plan", "/usr/bin/true");
  }
};

TEST_F(CampaignStatusTest, StoredRunsFailuresAndWhatToResubmit) {
  const CampaignPlan p = plan();
  ASSERT_EQ(p.shards.size(), 3u);
  CampaignStatus status = campaign_status(p);
  EXPECT_EQ(status.planned, 4);
  EXPECT_EQ(status.stored, 0);
  for (const ShardStatus& s : status.shards) EXPECT_EQ(s.state, ShardState::not_started) << s.index;
  EXPECT_EQ(index_ranges(status.unfinished()), "0-2");

  // Shard 0 runs whole. Shard 1's recording failed in two Slurm submissions (logs/slurm-JOB_1.out);
  // the newer log's error is shown, and task 11's log is not shard 1's. Shard 2's log says its
  // recording failed, then was stored: the last word is no failure, but the report holds no run of
  // it (as after a report was deleted), so the shard is unfinished, not failed.
  std::ostringstream log;
  ASSERT_TRUE(run_shard(p, 0, log).failures.empty()) << log.str();
  const Shard& one = p.shards[1];
  const Shard& two = p.shards[2];
  ASSERT_GE(one.recordings.size(), 1u);
  ASSERT_GE(two.recordings.size(), 1u);
  const std::string failed_dir = one.recordings[0].dir.string();
  std::ofstream(p.dir / "logs" / "slurm-17_1.out") << "shard 1: " << failed_dir << ": FAILED: first error\n";
  std::ofstream(p.dir / "logs" / "slurm-18_1.out") << "shard 1: " << failed_dir << ": FAILED: targets.csv: line 5: bad row\n";
  std::ofstream(p.dir / "logs" / "slurm-18_11.out") << "shard 1: " << failed_dir << ": FAILED: not this shard's log\n";
  std::filesystem::last_write_time(p.dir / "logs" / "slurm-17_1.out",
                                   std::filesystem::last_write_time(p.dir / "logs" / "slurm-18_1.out") - std::chrono::hours(1));
  std::ofstream(p.shard_log(2)) << "shard 2: " << two.recordings[0].dir.string() << ": FAILED: an old error\n"
                                << "shard 2: " << two.recordings[0].dir.string() << ": run 1 stored (1 cycles)\n";

  status = campaign_status(p);
  EXPECT_EQ(status.shards[0].state, ShardState::done);
  EXPECT_EQ(status.shards[0].stored, status.shards[0].planned);
  EXPECT_DOUBLE_EQ(status.shards[0].stored_s, p.shards[0].duration_s);
  EXPECT_EQ(status.shards[1].state, ShardState::failed);
  ASSERT_EQ(status.shards[1].failed.size(), 1u);
  EXPECT_EQ(status.shards[1].failed[0].dir.string(), failed_dir);
  EXPECT_EQ(status.shards[1].failed[0].message, "targets.csv: line 5: bad row");  // the newer log wins
  EXPECT_EQ(status.shards[2].state, ShardState::unfinished);
  EXPECT_TRUE(status.shards[2].failed.empty());
  EXPECT_EQ(status.stored, status.shards[0].planned);
  EXPECT_EQ(status.failed, 1);
  EXPECT_EQ(index_ranges(status.unfinished()), "1-2");
}

}  // namespace
}  // namespace rcsim::replay::campaign
