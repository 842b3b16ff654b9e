#pragma once
// A campaign split into shards (`rcsim campaign plan`, schemas/campaign.md, "The plan
// directory"): the recordings spread over N shards balanced by recorded duration, written as
// DIR/plan.json (`rcsim-campaign-plan` v1), a Slurm batch script DIR/campaign.sbatch that runs
// shard $SLURM_ARRAY_TASK_ID, and DIR/shards/ where each shard stores its own report.
#include <filesystem>
#include <string>
#include <vector>

#include "replay/campaign/manifest.hpp"

namespace rcsim::replay::campaign {

struct PlannedRecording {
  std::filesystem::path dir;
  double duration_s = 0.0;
};

struct Shard {
  int index = 0;
  double duration_s = 0.0;  // of its recordings
  std::vector<PlannedRecording> recordings;
};

struct CampaignPlan {
  std::filesystem::path dir;          // the plan directory
  CampaignManifest manifest;          // as planned (read back from plan.json)
  std::filesystem::path rcsim;        // the executable the batch script runs
  std::vector<Shard> shards;

  std::filesystem::path shard_report(int shard) const;  // DIR/shards/shard-0003.sqlite
  std::filesystem::path shard_log(int shard) const;     // DIR/logs/shard-0003.log
};

// The recorded duration of a recording: the span of its ego.csv plus one cycle, from the file's
// first and last rows (the rows between are not read).
double recorded_duration_s(const std::filesystem::path& dir);

// Longest first onto the least loaded shard (Graham's LPT rule: within 4/3 of the best
// makespan); ties go to the lower shard, so a plan is reproducible.
std::vector<Shard> balance_shards(std::vector<PlannedRecording> recordings, int shards);

// Plans the manifest's campaign into `dir` (created; refused if it holds a plan already). The
// batch script runs `rcsim`.
CampaignPlan write_plan(const CampaignManifest& manifest, int shards, const std::filesystem::path& dir,
                        const std::filesystem::path& rcsim);

// Reads DIR/plan.json back; the manifest document in it is checked again.
CampaignPlan read_plan(const std::filesystem::path& dir);

// The batch script's text: an array of one task per shard, each running its shard.
std::string batch_script(const CampaignPlan& plan);

}  // namespace rcsim::replay::campaign
