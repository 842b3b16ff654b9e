#pragma once
// Where a planned campaign stands (`rcsim campaign status`): per shard, how many of its
// recordings have a run stored in the shard's report and which failed in their last attempt,
// read from the plan directory alone (plan.json, shards/*.sqlite, logs/). Slurm is not asked: a
// shard with runs missing and no failure is running, queued or was killed, and resubmitting it
// redoes only what is missing (the shards are restartable).
#include <string>
#include <vector>

#include "replay/campaign/plan.hpp"

namespace rcsim::replay::campaign {

struct FailedRecording {
  std::filesystem::path dir;
  std::string message;  // the last attempt's error, as the shard's log has it
};

enum class ShardState { not_started, unfinished, failed, done };
std::string_view shard_state_name(ShardState state);  // "not started", "unfinished", "failed", "done"

struct ShardStatus {
  int index = 0;
  int planned = 0;                       // recordings
  int stored = 0;                        // of them with a run in the shard's report
  double planned_s = 0.0, stored_s = 0.0;  // their recorded durations
  std::vector<FailedRecording> failed;   // not stored, and their last attempt failed
  ShardState state = ShardState::not_started;
};

struct CampaignStatus {
  std::vector<ShardStatus> shards;
  int planned = 0, stored = 0, failed = 0;
  double planned_s = 0.0, stored_s = 0.0;

  std::vector<int> unfinished() const;  // the shards not done, to resubmit
};

// Reads the shard reports read-only (a shard being written is read as of its last stored run).
CampaignStatus campaign_status(const CampaignPlan& plan);

// "0,3-5,9": shard indices as `sbatch --array` and `rcsim campaign submit --shards` take them.
std::string index_ranges(const std::vector<int>& sorted_indices);

}  // namespace rcsim::replay::campaign
