#include "replay/campaign/status.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay::campaign {
namespace fs = std::filesystem;
namespace {

// The recording directories with a run in the shard's report; none while it does not exist.
std::set<std::string> stored_dirs(const fs::path& report) {
  std::set<std::string> out;
  if (!fs::exists(report)) return out;
  const auto db = open_report_database_read_only(report.string());
  for (const std::string& dir : stored_recording_dirs(*db)) out.insert(fs::path(dir).lexically_normal().string());  // absolute
  return out;
}

// The shard's logs, oldest first: run-local's logs/shard-NNNN.log and Slurm's
// logs/slurm-JOB_TASK.out (one per submission).
std::vector<fs::path> shard_logs(const CampaignPlan& plan, int shard) {
  std::vector<std::pair<fs::file_time_type, fs::path>> logs;
  const std::string slurm_suffix = fmt::format("_{}.out", shard);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(plan.dir / "logs", ec)) {
    const std::string name = entry.path().filename().string();
    const bool slurm = name.starts_with("slurm-") && name.ends_with(slurm_suffix) &&
                       name.find('_') == name.size() - slurm_suffix.size();
    if (entry.path() == plan.shard_log(shard) || slurm) logs.emplace_back(entry.last_write_time(), entry.path());
  }
  std::sort(logs.begin(), logs.end());
  std::vector<fs::path> out;
  for (auto& [time, path] : logs) out.push_back(std::move(path));
  return out;
}

// The last word of the shard's logs on each recording: run_shard writes "shard N: DIR: ..." per
// recording, "FAILED: message" when it failed.
std::map<std::string, std::string> last_failures(const CampaignPlan& plan, int shard) {
  std::map<std::string, std::string> failure;  // dir -> message; "" when its last attempt did not fail
  const std::string prefix = fmt::format("shard {}: ", shard);
  for (const fs::path& log : shard_logs(plan, shard)) {
    std::ifstream in(log);
    std::string line;
    while (std::getline(in, line)) {
      if (!line.starts_with(prefix)) continue;
      const std::string rest = line.substr(prefix.size());
      const std::size_t failed = rest.find(": FAILED: ");
      if (failed != std::string::npos) {
        failure[rest.substr(0, failed)] = rest.substr(failed + 10);
      } else if (const std::size_t colon = rest.find(": "); colon != std::string::npos) {
        failure[rest.substr(0, colon)] = "";
      }
    }
  }
  return failure;
}

ShardStatus shard_status(const CampaignPlan& plan, const Shard& shard) {
  ShardStatus s;
  s.index = shard.index;
  const std::set<std::string> stored = stored_dirs(plan.shard_report(shard.index));
  const auto failures = last_failures(plan, shard.index);
  for (const PlannedRecording& r : shard.recordings) {
    ++s.planned;
    s.planned_s += r.duration_s;
    if (stored.contains(fs::absolute(r.dir).lexically_normal().string())) {
      ++s.stored;
      s.stored_s += r.duration_s;
    } else if (const auto f = failures.find(r.dir.string()); f != failures.end() && !f->second.empty()) {
      s.failed.push_back({r.dir, f->second});
    }
  }
  const bool begun = fs::exists(plan.shard_report(shard.index)) || !failures.empty();
  s.state = s.stored == s.planned ? ShardState::done
            : !s.failed.empty()   ? ShardState::failed
            : begun               ? ShardState::unfinished
                                  : ShardState::not_started;
  return s;
}

}  // namespace

std::string_view shard_state_name(ShardState state) {
  switch (state) {
    case ShardState::not_started: return "not started";
    case ShardState::unfinished: return "unfinished";
    case ShardState::failed: return "failed";
    case ShardState::done: return "done";
  }
  return "?";
}

std::vector<int> CampaignStatus::unfinished() const {
  std::vector<int> out;
  for (const ShardStatus& s : shards) {
    if (s.state != ShardState::done) out.push_back(s.index);
  }
  return out;
}

CampaignStatus campaign_status(const CampaignPlan& plan) {
  CampaignStatus status;
  for (const Shard& shard : plan.shards) {
    ShardStatus& s = status.shards.emplace_back(shard_status(plan, shard));
    status.planned += s.planned;
    status.stored += s.stored;
    status.failed += static_cast<int>(s.failed.size());
    status.planned_s += s.planned_s;
    status.stored_s += s.stored_s;
  }
  return status;
}

std::string index_ranges(const std::vector<int>& sorted_indices) {
  std::string out;
  for (std::size_t i = 0; i < sorted_indices.size();) {
    std::size_t j = i;
    while (j + 1 < sorted_indices.size() && sorted_indices[j + 1] == sorted_indices[j] + 1) ++j;
    if (!out.empty()) out += ',';
    out += j == i ? fmt::format("{}", sorted_indices[i]) : fmt::format("{}-{}", sorted_indices[i], sorted_indices[j]);
    i = j + 1;
  }
  return out;
}

}  // namespace rcsim::replay::campaign
