// rcsim campaign plan|submit|run-local|run-shard: a campaign manifest sharded as a Slurm job array
// (or run on this machine), each shard into its own report, merged by rcsim merge (docs/campaigns.md).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <sys/wait.h>

#include "cli/child_process.hpp"
#include "cli/commands.hpp"
#include "common/input_error.hpp"
#include "common/safe_text.hpp"
#include "replay/campaign/plan.hpp"
#include "replay/campaign/shard_runner.hpp"
#include "replay/campaign/status.hpp"

namespace rcsim::cli {

namespace {

using replay::campaign::CampaignPlan;

struct PlanArgs {
  std::string manifest, dir;
  int shards = 1;
  std::string rcsim;
};

struct SubmitArgs {
  std::string dir, shards, sbatch = "sbatch";
};

struct RunLocalArgs {
  std::string dir;
  int jobs = 1;
};

struct StatusArgs {
  std::string dir;
};

struct RunShardArgs {
  std::string dir;
  int shard = 0;
};

// Slurm's default MaxArraySize is 1001: task ids 0 to 1000.
constexpr std::size_t kSlurmDefaultMaxArraySize = 1001;

// "42.0 min" or "3.25 h".
std::string duration_text(double s) {
  return s < 3600.0 ? fmt::format("{:.1f} min", s / 60.0) : fmt::format("{:.2f} h", s / 3600.0);
}

std::string merge_hint(const CampaignPlan& plan) {
  return fmt::format("rcsim merge {}/shards/shard-*.sqlite -o {}.sqlite", shell_quoted(plan.dir.string()),
                     plan.manifest.name);
}

void run_plan(const PlanArgs& args) {
  const auto manifest = replay::campaign::read_manifest(args.manifest);
  const std::filesystem::path rcsim = args.rcsim.empty() ? this_executable() : std::filesystem::absolute(args.rcsim);
  const CampaignPlan plan = replay::campaign::write_plan(manifest, args.shards, args.dir, rcsim);
  double total_s = 0.0, longest_s = 0.0;
  for (const auto& s : plan.shards) {
    total_s += s.duration_s;
    longest_s = std::max(longest_s, s.duration_s);
  }
  std::cout << fmt::format("campaign '{}': {} recordings, {} recorded, in {} shards (longest {}, {:.3f} x the even "
                           "share)\n",
                           manifest.name, manifest.recordings.size(), duration_text(total_s), plan.shards.size(),
                           duration_text(longest_s), longest_s / (total_s / static_cast<double>(plan.shards.size())));
  if (static_cast<std::size_t>(args.shards) > plan.shards.size()) {
    std::cout << fmt::format("  ({} shards asked for; {} recordings make {}: a shard holds one recording at least)\n", args.shards,
                             manifest.recordings.size(), plan.shards.size());
  }
  for (const auto& s : plan.shards) {
    std::cout << fmt::format("  shard {}: {} recordings, {}\n", s.index, s.recordings.size(), duration_text(s.duration_s));
  }
  if (plan.shards.size() > kSlurmDefaultMaxArraySize) {
    std::cout << fmt::format("  note: {} array tasks; Slurm's default MaxArraySize takes {} (see `scontrol show config`): "
                             "fewer --shards, or ask your administrator\n",
                             plan.shards.size(), kSlurmDefaultMaxArraySize);
  }
  const std::string dir = shell_quoted(plan.dir.string());
  std::cout << fmt::format("planned in {}\n  on Slurm:        rcsim campaign submit {}   (or: sbatch {}/campaign.sbatch)\n"
                           "  on this machine: rcsim campaign run-local {} -j {}\n  then:            {}\n",
                           plan.dir.string(), dir, dir, dir, std::min<std::size_t>(plan.shards.size(), 2),
                           merge_hint(plan));
}

void run_submit(const SubmitArgs& args) {
  const CampaignPlan plan = replay::campaign::read_plan(args.dir);
  std::vector<std::string> argv = {args.sbatch, "--parsable"};
  if (!args.shards.empty()) argv.push_back("--array=" + args.shards);  // overrides the script's #SBATCH --array
  argv.push_back((plan.dir / "campaign.sbatch").string());
  std::string out;
  const int status = run_captured(argv, out);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (status != 0) {
    throw std::runtime_error(fmt::format("{} failed (exit status {}){}", args.sbatch, status,
                                         out.empty() ? "; its message is above" : ": " + out));
  }
  const std::string job_id = out.substr(0, out.find(';'));  // --parsable: "id" or "id;cluster"
  if (job_id.empty() || job_id.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error(fmt::format("{} printed '{}', not a job id", args.sbatch, out));
  }
  std::cout << job_id << '\n';
  std::cerr << fmt::format("submitted campaign '{}' as job {} (array {}); when it has finished: {}\n", plan.manifest.name,
                           job_id, args.shards.empty() ? fmt::format("0-{}", plan.shards.size() - 1) : args.shards,
                           merge_hint(plan));
}

void run_local(const RunLocalArgs& args) {
  const CampaignPlan plan = replay::campaign::read_plan(args.dir);
  const std::filesystem::path self = this_executable();
  const int n = static_cast<int>(plan.shards.size());
  std::map<pid_t, int> running;  // pid -> shard
  std::vector<int> failed;
  int next = 0;
  const auto reap_one = [&] {
    int status = 0;
    const pid_t pid = ::wait(&status);
    if (pid < 0) throw std::runtime_error("wait failed");
    const auto it = running.find(pid);
    if (it == running.end()) return;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    std::cout << fmt::format("shard {}: {} (log {})\n", it->second, code == 0 ? "done" : fmt::format("FAILED, exit status {}", code),
                             plan.shard_log(it->second).string());
    if (code != 0) failed.push_back(it->second);
    running.erase(it);
  };
  while (next < n || !running.empty()) {
    if (next < n && static_cast<int>(running.size()) < args.jobs) {
      const pid_t pid = spawn_logged({self.string(), "campaign", "run-shard", plan.dir.string(), "--shard",
                                      std::to_string(next)},
                                     plan.shard_log(next));
      running[pid] = next++;
      continue;
    }
    reap_one();
  }
  if (!failed.empty()) {
    std::string list;
    for (const int s : failed) {
      if (!list.empty()) list += ',';
      list += std::to_string(s);
    }
    throw std::runtime_error(fmt::format("{} of {} shards failed ({}); run again to redo only what is missing", failed.size(),
                                         n, list));
  }
  std::cout << fmt::format("all {} shards done; next: {}\n", n, merge_hint(plan));
}

// Per shard: its state and stored share, the failed recordings with their errors (the first
// few), then the command that finishes the campaign or, when all is stored, the merge.
void run_status(const StatusArgs& args) {
  constexpr std::size_t kFailuresShown = 5;
  const CampaignPlan plan = replay::campaign::read_plan(args.dir);
  const auto status = replay::campaign::campaign_status(plan);
  std::cout << fmt::format("campaign '{}' (plan {}): {} of {} recordings stored ({} of {}), {} failed\n", plan.manifest.name,
                           plan.dir.string(), status.stored, status.planned, duration_text(status.stored_s),
                           duration_text(status.planned_s), status.failed);
  for (const auto& s : status.shards) {
    std::cout << fmt::format("  shard {}: {}, {} of {} stored ({} of {})", s.index, replay::campaign::shard_state_name(s.state),
                             s.stored, s.planned, duration_text(s.stored_s), duration_text(s.planned_s));
    if (!s.failed.empty()) std::cout << fmt::format("; {} failed", s.failed.size());
    std::cout << '\n';
    for (std::size_t i = 0; i < std::min(s.failed.size(), kFailuresShown); ++i) {
      std::cout << fmt::format("      {}: {}\n", s.failed[i].dir.string(), s.failed[i].message);
    }
    if (s.failed.size() > kFailuresShown) std::cout << fmt::format("      ... and {} more\n", s.failed.size() - kFailuresShown);
  }
  const std::vector<int> unfinished = status.unfinished();
  if (unfinished.empty()) {
    std::cout << fmt::format("all {} shards done; next: {}\n", plan.shards.size(), merge_hint(plan));
  } else {
    std::cout << fmt::format("to finish (only what is missing is replayed): rcsim campaign submit {} --shards {}\n"
                             "  or on this machine: rcsim campaign run-local {} -j {}\n",
                             shell_quoted(plan.dir.string()), replay::campaign::index_ranges(unfinished),
                             shell_quoted(plan.dir.string()), std::min<std::size_t>(unfinished.size(), 2));
    if (status.failed > 0) std::cout << "  (a failed recording fails again until its input is fixed; its error is above)\n";
  }
}

void run_one_shard(const RunShardArgs& args) {
  const CampaignPlan plan = replay::campaign::read_plan(args.dir);
  const auto outcome = replay::campaign::run_shard(plan, args.shard, std::cout);
  std::cout << fmt::format("shard {}: {} runs stored, {} stored before, {} failed; report {}\n", args.shard, outcome.stored,
                           outcome.skipped, outcome.failures.size(), plan.shard_report(args.shard).string());
  if (!outcome.failures.empty()) {
    throw std::runtime_error(fmt::format("shard {}: {} recordings failed; the first: {}", args.shard,
                                         outcome.failures.size(), outcome.failures.front()));
  }
}

}  // namespace

void add_campaign_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("campaign", "a campaign manifest sharded as a Slurm job array, or run on this machine");
  cmd->require_subcommand(1);

  auto plan = std::make_shared<PlanArgs>();
  auto* p = cmd->add_subcommand("plan", "split the manifest's recordings into shards balanced by recorded duration");
  p->add_option("MANIFEST", plan->manifest, "campaign manifest (rcsim-campaign, schemas/campaign.md)")
      ->required()
      ->check(CLI::ExistingFile);
  p->add_option("--shards", plan->shards, "number of shards (Slurm array tasks); at most one per recording")
      ->required()
      ->check(CLI::Range(1, 100000));
  p->add_option("-o,--output", plan->dir, "plan directory (created): plan.json, campaign.sbatch, shards/, logs/")->required();
  p->add_option("--rcsim", plan->rcsim, "the rcsim executable the batch script runs (default: this one)");
  p->callback([plan] { run_plan(*plan); });

  auto submit = std::make_shared<SubmitArgs>();
  auto* s = cmd->add_subcommand("submit", "submit the plan's job array with sbatch; prints the job id");
  s->add_option("PLAN_DIR", submit->dir, "plan directory")->required();
  s->add_option("--shards", submit->shards, "only these array indices, as sbatch --array takes them (e.g. 3,7-9)");
  s->add_option("--sbatch", submit->sbatch, "the sbatch command")->capture_default_str();
  s->callback([submit] { run_submit(*submit); });

  auto local = std::make_shared<RunLocalArgs>();
  auto* l = cmd->add_subcommand("run-local", "run every shard on this machine, at most -j at a time");
  l->add_option("PLAN_DIR", local->dir, "plan directory")->required();
  l->add_option("-j,--jobs", local->jobs, "shards run at once (one core each)")->check(CLI::Range(1, 1024))->capture_default_str();
  l->callback([local] { run_local(*local); });

  auto status = std::make_shared<StatusArgs>();
  auto* st = cmd->add_subcommand("status", "how many runs each shard has stored, which recordings failed, what to resubmit");
  st->add_option("PLAN_DIR", status->dir, "plan directory")->required();
  st->callback([status] { run_status(*status); });

  auto shard = std::make_shared<RunShardArgs>();
  auto* r = cmd->add_subcommand("run-shard", "replay one shard into its report (what each array task runs); restartable");
  r->add_option("PLAN_DIR", shard->dir, "plan directory")->required();
  r->add_option("--shard", shard->shard, "the shard (the array task id)")->required()->check(kNonNegative);
  r->callback([shard] { run_one_shard(*shard); });
}

}  // namespace rcsim::cli
