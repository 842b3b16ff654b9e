// The campaign goal of issue 20 (docs/campaigns.md): a campaign of generated drives replayed
// serially (one shard) and as a Slurm job array of N shards on a one-node cluster started here
// (tests/end_to_end/slurm_cluster.hpp), then merged. Prints the serial time, the ideal (serial / N),
// the array's wall time from sbatch to the last task's end and its ratio to the ideal, the merge
// time, and whether the merged report equals the serial one figure for figure.
//   usage: rcsim_bench_campaign WORK_DIR [DRIVES=200] [DURATION_S=600] [SHARDS=2]
#include <chrono>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <iostream>

#include "end_to_end/campaign_figures.hpp"
#include "end_to_end/slurm_cluster.hpp"
#include "tool_arguments.hpp"

namespace {

namespace fs = std::filesystem;
using rcsim::testing::run_rcsim;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void must(const rcsim::testing::CommandResult& r, const std::string& what) {
  if (r.exit_code != 0) throw std::runtime_error(what + " failed:\n" + r.output);
}

// A plan of the drives in `work/name` with `shards` shards.
fs::path plan(const fs::path& work, const std::string& name, int shards) {
  const fs::path dir = work / name;
  fs::remove_all(dir);
  must(run_rcsim(fmt::format("campaign plan {} --shards {} -o {}", (work / "campaign.json").string(), shards, dir.string())),
       "plan");
  return dir;
}

const rcsim::bench_tools::ToolUsage kCampaignBenchUsage{
    "rcsim_bench_campaign", "WORK_DIR [DRIVES=200] [DURATION_S=600] [SHARDS=2]",
    "The campaign goal (docs/campaigns.md): DRIVES generated drives of DURATION_S seconds replayed\n"
    "serially and as a Slurm job array of SHARDS shards on a one-node cluster started here, then merged;\n"
    "prints the times and whether the merged report equals the serial one. Works in WORK_DIR.",
    1, 4};

}  // namespace

int main(int argc, char** argv) {
  int exit_status = 0;
  const auto arguments = rcsim::bench_tools::tool_arguments(argc, argv, kCampaignBenchUsage, exit_status);
  if (!arguments) return exit_status;
  // DRIVES, DURATION_S and SHARDS: whole numbers of at least 1, else the usage.
  const auto count_argument = [&](std::size_t index, int fallback) -> std::optional<int> {
    if (arguments->size() <= index) return fallback;
    const auto value = rcsim::bench_tools::number_argument<int>((*arguments)[index]);
    return value && *value >= 1 ? value : std::nullopt;
  };
  const auto drives_arg = count_argument(1, 200), duration_arg = count_argument(2, 600), shards_arg = count_argument(3, 2);
  if (!drives_arg || !duration_arg || !shards_arg) {
    return rcsim::bench_tools::refuse_command_line(kCampaignBenchUsage, "DRIVES, DURATION_S and SHARDS must be whole numbers >= 1");
  }
  const int drives = *drives_arg, duration_s = *duration_arg, shards = *shards_arg;
  const fs::path work = fs::absolute(arguments->front());
  try {
    fs::create_directories(work / "drives");
    const fs::path generator = fs::path(RCSIM_BINARY).parent_path() / "rcsim_make_long_recording";
    for (int i = 0; i < drives; ++i) {
      const fs::path drive = work / "drives" / fmt::format("drive_{:04d}", i);
      if (fs::exists(drive / "targets.csv")) continue;
      const std::string command = fmt::format("{} {} {} {} > /dev/null", generator.string(), drive.string(), duration_s, i + 1);
      if (std::system(command.c_str()) != 0) throw std::runtime_error("cannot generate " + drive.string());
    }
    std::ofstream(work / "campaign.json") << fmt::format(
        R"({{"format": "rcsim-campaign", "version": 1, "name": "bench", "recordings": ["{}/drives/drive_*"],
            "replay": {{"store": "summary"}}}})",
        work.string());

    // Serial: the whole campaign as one shard.
    const fs::path serial = plan(work, "serial", 1);
    auto start = std::chrono::steady_clock::now();
    must(run_rcsim(fmt::format("campaign run-shard {} --shard 0 > /dev/null", serial.string())), "serial shard");
    const double serial_s = seconds_since(start);

    // The array on Slurm.
    std::string why_not;
    auto cluster = rcsim::testing::SlurmCluster::start(work / "cluster", &why_not);
    if (!cluster) throw std::runtime_error("no Slurm here: " + why_not);
    const fs::path array = plan(work, "array", shards);
    start = std::chrono::steady_clock::now();
    const auto submitted = cluster->run(fmt::format("{} campaign submit {} 2>/dev/null", RCSIM_BINARY, array.string()));
    must(submitted, "submit");
    const std::string job = submitted.output.substr(0, submitted.output.find('\n'));
    const auto states = cluster->wait(job, std::chrono::seconds(3600));
    const double array_s = seconds_since(start);
    for (const auto& [task, state] : states) {
      if (state != "COMPLETED") throw std::runtime_error(fmt::format("task {}: {}", task, state));
    }

    std::string inputs;
    for (int s = 0; s < shards; ++s) inputs += " " + (array / "shards" / fmt::format("shard-{:04d}.sqlite", s)).string();
    fs::remove(work / "campaign.sqlite");
    start = std::chrono::steady_clock::now();
    must(run_rcsim(fmt::format("merge{} -o {} > /dev/null", inputs, (work / "campaign.sqlite").string())), "merge");
    const double merge_s = seconds_since(start);
    const bool equal = rcsim::testing::figures_by_recording(work / "campaign.sqlite") ==
                       rcsim::testing::figures_by_recording(serial / "shards" / "shard-0000.sqlite");

    const double ideal_s = serial_s / shards;
    std::cout << fmt::format(
        "campaign: {} drives x {} s ({:.1f} h), {} shards, {} cores\n"
        "serial (1 shard):          {:8.1f} s\n"
        "ideal (serial / {}):        {:8.1f} s\n"
        "Slurm array, sbatch to end: {:7.1f} s  = {:.3f} x ideal\n"
        "merge of {} shards:          {:7.2f} s  ({:.1f} MB)\n"
        "merged equals serial, figure for figure: {}\n",
        drives, duration_s, drives * duration_s / 3600.0, shards, cluster->cpus(), serial_s, shards, ideal_s, array_s,
        array_s / ideal_s, shards, merge_s, static_cast<double>(fs::file_size(work / "campaign.sqlite")) / 1e6,
        equal ? "yes" : "NO");
    return equal ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "rcsim_bench_campaign: " << e.what() << '\n';
    return 1;
  }
}
