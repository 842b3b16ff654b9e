#include "replay/campaign/plan.hpp"

#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <fstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/safe_text.hpp"
#include "common/text_file.hpp"
#include "io/recording_stream.hpp"

namespace rcsim::replay::campaign {

namespace {

constexpr int kMaxShards = 100000;

// The t_s (first field) of a CSV row; nullopt if it is not a number.
std::optional<double> first_field_s(std::string_view row) {
  const std::string_view field = row.substr(0, row.find(','));
  double t = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), t);
  if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return t;
}

}  // namespace

std::filesystem::path CampaignPlan::shard_report(int shard) const {
  return dir / "shards" / fmt::format("shard-{:04d}.sqlite", shard);
}

std::filesystem::path CampaignPlan::shard_log(int shard) const {
  return dir / "logs" / fmt::format("shard-{:04d}.log", shard);
}

double recorded_duration_s(const std::filesystem::path& dir) {
  const Recording header = read_recording_header(dir);
  const std::filesystem::path ego = dir / "ego.csv";
  LineReader lines(ego);
  std::string_view line;
  if (!lines.next(line) || !lines.next(line)) throw InputError(ego.string(), "", "no rows");
  const auto t_first = first_field_s(line);
  if (!t_first) throw InputError(ego.string(), "line 2", "t_s is not a number");
  // The last row, from the file's last 64 KiB.
  std::ifstream in(ego, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 65536);
  std::string buffer(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(buffer.data(), tail);
  while (!buffer.empty() && (buffer.back() == '\n' || buffer.back() == '\r')) buffer.pop_back();
  const std::string_view last = std::string_view(buffer).substr(buffer.rfind('\n') + 1);
  const auto t_last = first_field_s(last);
  if (!t_last || *t_last < *t_first) throw InputError(ego.string(), "last line", "t_s is not a number after the first row's");
  return *t_last - *t_first + header.cycle_time_s;
}

std::vector<Shard> balance_shards(std::vector<PlannedRecording> recordings, int n) {
  std::vector<Shard> shards(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) shards[static_cast<std::size_t>(i)].index = i;
  std::stable_sort(recordings.begin(), recordings.end(),
                   [](const auto& a, const auto& b) { return a.duration_s > b.duration_s; });
  for (PlannedRecording& r : recordings) {
    Shard& least = *std::min_element(shards.begin(), shards.end(),
                                     [](const Shard& a, const Shard& b) { return a.duration_s < b.duration_s; });
    least.duration_s += r.duration_s;
    least.recordings.push_back(std::move(r));
  }
  // Each shard replays its recordings in path order: a restarted shard finds them in one order.
  for (Shard& s : shards) {
    std::sort(s.recordings.begin(), s.recordings.end(), [](const auto& a, const auto& b) { return a.dir < b.dir; });
  }
  return shards;
}

std::string batch_script(const CampaignPlan& plan) {
  const SlurmRequest& slurm = plan.manifest.slurm;
  std::string s = "#!/bin/bash\n";
  s += fmt::format("# rcsim campaign '{}': one array task per shard (rcsim campaign plan; schemas/campaign.md).\n",
                   plan.manifest.name);
  s += "# A task run again (preempted, killed, resubmitted) skips the runs its shard stored completely.\n";
  s += fmt::format("#SBATCH --job-name=rcsim-{}\n", plan.manifest.name.substr(0, 40));
  s += fmt::format("#SBATCH --array=0-{}\n", plan.shards.size() - 1);
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  // Quoted: sbatch reads a double-quoted argument whole (write_plan refuses a '"' in the path).
  s += fmt::format("#SBATCH --output=\"{}\"\n", (plan.dir / "logs" / "slurm-%A_%a.out").string());
  s += "#SBATCH --open-mode=append\n";
  if (!slurm.partition.empty()) s += "#SBATCH --partition=" + slurm.partition + "\n";
  if (!slurm.account.empty()) s += "#SBATCH --account=" + slurm.account + "\n";
  if (!slurm.time_limit.empty()) s += "#SBATCH --time=" + slurm.time_limit + "\n";
  if (!slurm.memory.empty()) s += "#SBATCH --mem=" + slurm.memory + "\n";
  for (const std::string& extra : slurm.extra) s += "#SBATCH " + extra + "\n";
  s += "set -euo pipefail\n";
  s += fmt::format("exec {} campaign run-shard {} --shard \"$SLURM_ARRAY_TASK_ID\"\n", shell_quoted(plan.rcsim.string()),
                   shell_quoted(plan.dir.string()));
  return s;
}

CampaignPlan write_plan(const CampaignManifest& manifest, int n, const std::filesystem::path& dir,
                        const std::filesystem::path& rcsim) {
  if (n < 1 || n > kMaxShards) throw InputError("--shards", std::to_string(n), fmt::format("expected 1 to {}", kMaxShards));
  CampaignPlan plan;
  plan.dir = std::filesystem::absolute(dir).lexically_normal();
  plan.manifest = manifest;
  plan.rcsim = rcsim;
  // The plan's directory and rcsim's path go into the batch script's #SBATCH lines and commands.
  for (const std::filesystem::path& path : {plan.dir, plan.rcsim}) {
    const std::string text = path.string();
    if (const auto bad = find_control_character(text)) {
      throw InputError(text, "", fmt::format("the path holds {}; it cannot go into a batch script", *bad));
    }
    if (text.find('"') != std::string::npos) {
      throw InputError(text, "", "the path holds a '\"'; it cannot go into an #SBATCH line");
    }
  }
  if (std::filesystem::exists(plan.dir / "plan.json")) {
    throw InputError((plan.dir / "plan.json").string(), "",
                     "a campaign is planned here already; plan into a new directory (its shard reports stay valid)");
  }
  if (std::filesystem::exists(plan.dir) &&
      (!std::filesystem::is_directory(plan.dir) || !std::filesystem::is_empty(plan.dir))) {
    throw InputError(plan.dir.string(), "", "exists and is not an empty directory; plan into a new one");
  }
  std::vector<PlannedRecording> recordings;
  for (const auto& d : manifest.recordings) recordings.push_back({d, recorded_duration_s(d)});
  plan.shards = balance_shards(std::move(recordings), std::min<int>(n, static_cast<int>(manifest.recordings.size())));

  std::filesystem::create_directories(plan.dir / "shards");
  std::filesystem::create_directories(plan.dir / "logs");
  nlohmann::ordered_json shards = nlohmann::ordered_json::array();
  for (const Shard& s : plan.shards) {
    nlohmann::ordered_json recs = nlohmann::ordered_json::array();
    for (const auto& r : s.recordings) recs.push_back({{"dir", r.dir.string()}, {"duration_s", r.duration_s}});
    shards.push_back({{"shard", s.index}, {"duration_s", s.duration_s}, {"recordings", recs}});
  }
  const nlohmann::ordered_json doc = {{"format", "rcsim-campaign-plan"},
                                      {"version", 1},
                                      {"name", manifest.name},
                                      {"manifest_file", manifest.file.string()},
                                      {"manifest", manifest.document},
                                      {"rcsim", rcsim.string()},
                                      {"rcsim_version", RCSIM_VERSION},
                                      {"shards", shards}};
  AtomicFileWriter script((plan.dir / "campaign.sbatch").string());
  script.stream() << batch_script(plan);
  script.commit();
  std::filesystem::permissions(plan.dir / "campaign.sbatch", std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
  AtomicFileWriter out((plan.dir / "plan.json").string());  // last: a plan.json means a whole plan
  out.stream() << doc.dump(2) << '\n';
  out.commit();
  return plan;
}

CampaignPlan read_plan(const std::filesystem::path& dir) {
  CampaignPlan plan;
  plan.dir = std::filesystem::absolute(dir).lexically_normal();
  const std::string file = (plan.dir / "plan.json").string();
  if (!std::filesystem::exists(plan.dir)) throw InputError(plan.dir.string(), "", "no such plan directory");
  if (!std::filesystem::is_directory(plan.dir)) {
    throw InputError(plan.dir.string(), "", "not a directory: give the plan directory (rcsim campaign plan -o DIR)");
  }
  if (!std::filesystem::exists(file)) throw InputError(file, "", "no campaign plan here (rcsim campaign plan writes it)");
  const nlohmann::json doc = parse_json_file(file);
  const JsonField root(doc, file, "");
  root.expect_format("rcsim-campaign-plan", 1);
  root.expect_only({"format", "version", "name", "manifest_file", "manifest", "rcsim", "rcsim_version", "shards"});
  // The manifest as planned, checked again as if read from where it was (its relative paths).
  CampaignManifest& m = plan.manifest;
  m.file = root.string("manifest_file");
  m.document = doc.at("manifest");
  const JsonField manifest(m.document, file, "manifest");
  m.name = root.string("name");
  if (!is_plain_name(m.name)) root.fail("name", "expected a plain name, as the manifest's (rcsim campaign plan checks it)");
  if (manifest.has("replay")) m.replay = parse_campaign_replay(manifest.member("replay"), m.file.parent_path());
  if (manifest.has("criteria")) m.criteria = verdict::parse_criteria(manifest);
  plan.rcsim = root.string("rcsim");
  for (const JsonField& s : root.array("shards")) {
    Shard shard;
    shard.index = static_cast<int>(plan.shards.size());
    shard.duration_s = s.number("duration_s");
    for (const JsonField& r : s.array("recordings")) {
      shard.recordings.push_back({r.string("dir"), r.number("duration_s")});
      m.recordings.push_back(shard.recordings.back().dir);
    }
    plan.shards.push_back(std::move(shard));
  }
  if (plan.shards.empty()) root.fail("shards", "the plan has no shard");
  return plan;
}

}  // namespace rcsim::replay::campaign
