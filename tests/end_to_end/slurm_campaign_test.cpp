// A campaign through a real Slurm (tests/end_to_end/slurm_cluster.hpp): `rcsim campaign submit`
// of the array over bundled recordings, the merged shards equal to a serial replay figure for
// figure; tasks SIGKILLed mid-run, resubmitted by index, redo only what they had not stored.
// Skipped, with the reason, where Slurm cannot run (not root, packages missing).
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fstream>

#include "end_to_end/campaign_figures.hpp"
#include "end_to_end/slurm_cluster.hpp"
#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::testing {
namespace {

const std::vector<std::string> kSlurmCampaignRecordings = {"close_front",  "corner_approach", "front_approach",
                                              "overtaking",   "two_in_one_cell", "perpendicular_crossing"};

class SlurmCampaign : public ScratchDirTest {
 protected:
  SlurmCampaign() : ScratchDirTest("sc") {}
  // The test cluster, or nullopt with the reason printed in one line (not root, no packages).
  std::optional<SlurmCluster> start_cluster() {
    auto cluster = SlurmCluster::start(dir_ / "c", &why_not_);
    if (!cluster) std::cout << "Slurm test cluster unavailable: " << why_not_ << '\n';
    return cluster;
  }
  // The plan's shards run `rcsim` (or, to be killed, tests/hooks/' rcsim_killable).
  void plan(int shards, const std::string& rcsim = RCSIM_BINARY) {
    std::string recordings;
    for (const auto& r : kSlurmCampaignRecordings) recordings += (recordings.empty() ? "\"" : ", \"") + (kBundledRecordings / r).string() + "\"";
    std::ofstream(dir_ / "campaign.json") << R"({"format": "rcsim-campaign", "version": 1, "name": "slurm-test", )"
                                          << R"("recordings": [)" << recordings << R"(], "replay": {"seed": 5}})";
    const auto planned = run_rcsim(fmt::format("campaign plan {} --shards {} -o {} --rcsim {}", (dir_ / "campaign.json").string(),
                                               shards, (dir_ / "plan").string(), rcsim));
    ASSERT_EQ(planned.exit_code, 0) << planned.output;
  }
  // `rcsim campaign submit` against the cluster: the job id it prints first.
  std::string submit(const SlurmCluster& cluster, const std::string& options = "", const std::string& env = "") {
    const auto submitted =
        cluster.run(fmt::format("{} {} campaign submit {} {} 2>/dev/null", env, RCSIM_BINARY, (dir_ / "plan").string(), options));
    EXPECT_EQ(submitted.exit_code, 0) << submitted.output;
    return submitted.output.substr(0, submitted.output.find('\n'));
  }
  void merge_and_compare_with_serial() {
    std::string shards;
    for (const auto& entry : std::filesystem::directory_iterator(dir_ / "plan" / "shards")) {
      if (entry.path().extension() == ".sqlite") shards += " " + entry.path().string();
    }
    const auto merged = run_rcsim(fmt::format("merge{} -o {}", shards, (dir_ / "campaign.sqlite").string()));
    ASSERT_EQ(merged.exit_code, 0) << merged.output;
    for (const auto& r : kSlurmCampaignRecordings) {
      const auto serial = run_rcsim(fmt::format("replay {} --db {} --seed 5 --store summary", (kBundledRecordings / r).string(),
                                                (dir_ / "serial.sqlite").string()));
      ASSERT_EQ(serial.exit_code, 0) << serial.output;
    }
    const auto campaign = figures_by_recording(dir_ / "campaign.sqlite");
    EXPECT_EQ(campaign.size(), kSlurmCampaignRecordings.size());
    EXPECT_EQ(campaign, figures_by_recording(dir_ / "serial.sqlite"));
  }
  std::string why_not_;
};

TEST_F(SlurmCampaign, ArrayMergesToSerial) {
  auto cluster = start_cluster();
  if (!cluster) GTEST_SKIP() << why_not_;
  plan(3);
  const std::string job = submit(*cluster);
  ASSERT_FALSE(job.empty());
  const auto states = cluster->wait(job, std::chrono::seconds(120));
  ASSERT_EQ(states.size(), 3u);
  for (const auto& [task, state] : states) EXPECT_EQ(state, "COMPLETED") << "task " << task;
  merge_and_compare_with_serial();
}

TEST_F(SlurmCampaign, KilledTasksResubmitted) {
  auto cluster = start_cluster();
  if (!cluster) GTEST_SKIP() << why_not_;
  plan(2, RCSIM_KILLABLE_BINARY);
  // sbatch passes the environment on: every task (rcsim_killable) kills itself (SIGKILL) inside the first run that
  // reaches 420 sensor cycles, mid-transaction. The shards (longest first onto the least loaded):
  // 0 = close_front (176 cycles x 2 sensors), overtaking (251 x 2), two_in_one_cell (126 x 2);
  // 1 = corner_approach (201 x 2), front_approach (101 x 2), perpendicular_crossing (226 x 2).
  // Each stores its first run(s) and dies in overtaking or perpendicular_crossing.
  const std::string job = submit(*cluster, "", "RCSIM_TEST_KILL_AFTER_CYCLES=420");
  std::string failed;
  for (const auto& [task, state] : cluster->wait(job, std::chrono::seconds(120))) {
    if (state != "COMPLETED") failed += (failed.empty() ? "" : ",") + std::to_string(task);
  }
  ASSERT_EQ(failed, "0,1") << "both tasks must have been killed, or the test proves nothing";
  // Resubmit just the failed indices, without the kill.
  const std::string again = submit(*cluster, "--shards " + failed);
  for (const auto& [task, state] : cluster->wait(again, std::chrono::seconds(120))) {
    EXPECT_EQ(state, "COMPLETED") << "task " << task;
  }
  for (const auto& [task, kept] : std::vector<std::pair<int, std::string>>{{0, "1 stored before"}, {1, "2 stored before"}}) {
    const std::string log = read_file(dir_ / "plan" / "logs" / fmt::format("slurm-{}_{}.out", again, task));
    EXPECT_NE(log.find(kept), std::string::npos) << log;  // the runs stored before the kill were kept
  }
  merge_and_compare_with_serial();
}

}  // namespace
}  // namespace rcsim::testing
