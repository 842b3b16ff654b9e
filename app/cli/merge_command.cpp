// rcsim merge SHARD.sqlite... -o CAMPAIGN.sqlite: the runs of many report databases (a campaign's
// shards) in one, atomically, duplicates reported and not copied twice (docs/merge.md).
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/verdict_options.hpp"
#include "replay/store/report_merge.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::cli {

namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string output;
  bool json = false;
  VerdictArgs verdicts;
};

std::string plural(long long n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

std::string duplicate_line(const replay::MergeDuplicate& d) {
  return fmt::format("{} run {} duplicates run {} of {} (recording {}, seed {})", d.file, d.run_id, d.kept_run_id,
                     d.kept_file, d.recording_name, d.seed);
}

std::string differences_text(const replay::MergeDuplicate& d) {
  std::string text;
  for (const auto& difference : d.differences) {
    text += fmt::format("{}{} {} (kept) against {}", text.empty() ? "" : ", ", difference.figure, difference.kept,
                        difference.duplicate);
  }
  return text;
}

void print_text(const replay::MergeResult& r) {
  if (r.stale_temporaries_removed > 0) {
    std::cout << fmt::format("removed {} of merges into {} that were killed\n",
                             plural(r.stale_temporaries_removed, "temporary file", "temporary files"), r.output);
  }
  for (const auto& input : r.inputs) {
    std::string benches;
    if (input.benches > 0) {
      benches = fmt::format("; {} of {} added", input.benches_added, plural(input.benches, "bench", "benches"));
    }
    std::cout << fmt::format("{}: {}, {} added, {}{}\n", input.file, plural(input.runs, "run", "runs"), input.added,
                             plural(input.duplicates, "duplicate", "duplicates"), benches);
  }
  for (const auto& d : r.duplicates) {
    std::cout << duplicate_line(d) << (d.differences.empty() ? "; same figures" : "; FIGURES DIFFER") << '\n';
    if (!d.differences.empty()) {
      // The same run (same recording, seed, parameters) gave other figures: not expected of a
      // deterministic replay, so said where it cannot be missed.
      std::cerr << "rcsim: warning: " << duplicate_line(d) << " but its figures differ from the kept run's: "
                << differences_text(d) << '\n';
    }
  }
  if (!r.campaign.empty()) {
    std::cout << fmt::format("campaign {} with {}{}\n", r.campaign, plural(r.criteria, "criterion", "criteria"),
                             r.campaign_copied ? " (copied from the shards)" : "");
  }
  std::cout << fmt::format("merged {} from {} into {}: {} added, {}; {} now holds {}\n",
                           plural(r.runs_merged(), "run", "runs"), plural(static_cast<long long>(r.inputs.size()), "shard", "shards"),
                           r.output, r.added(), plural(static_cast<long long>(r.duplicates.size()), "duplicate", "duplicates"),
                           r.output, plural(r.runs_after, "run", "runs"));
  if (const long long n = r.inconsistent_duplicates(); n > 0) {
    std::cerr << fmt::format("rcsim: warning: {} of {} differ in their figures from the runs kept for them: the same "
                             "recording, seed and parameters gave other figures\n",
                             n, plural(static_cast<long long>(r.duplicates.size()), "duplicate", "duplicates"));
  }
}

nlohmann::ordered_json result_json(const replay::MergeResult& r) {
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const auto& input : r.inputs) {
    nlohmann::ordered_json run_ids = nlohmann::ordered_json::array();
    for (const auto& [from, to] : input.run_ids) run_ids.push_back({from, to});
    inputs.push_back({{"file", input.file},
                      {"runs", input.runs},
                      {"added", input.added},
                      {"duplicates", input.duplicates},
                      {"benches", input.benches},
                      {"benches_added", input.benches_added},
                      {"run_ids", run_ids}});
  }
  nlohmann::ordered_json duplicates = nlohmann::ordered_json::array();
  for (const auto& d : r.duplicates) {
    nlohmann::ordered_json differences = nlohmann::ordered_json::array();
    for (const auto& difference : d.differences) {
      differences.push_back({{"figure", difference.figure}, {"kept", difference.kept}, {"duplicate", difference.duplicate}});
    }
    duplicates.push_back({{"file", d.file},
                          {"run_id", d.run_id},
                          {"duplicate_of", {{"file", d.kept_file}, {"run_id", d.kept_run_id}}},
                          {"output_run_id", d.output_run_id},
                          {"recording", d.recording_name},
                          {"seed", d.seed},
                          {"identity", d.identity},
                          {"figures_differ", differences}});
  }
  return {{"output", r.output},
          {"output_existed", r.output_existed},
          {"runs_before", r.runs_before},
          {"runs_merged", r.runs_merged()},
          {"added", r.added()},
          {"duplicates", r.duplicates.size()},
          {"inconsistent_duplicates", r.inconsistent_duplicates()},
          {"runs_after", r.runs_after},
          {"campaign", r.campaign.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(r.campaign)},
          {"criteria", r.criteria},
          {"stale_temporaries_removed", r.stale_temporaries_removed},
          {"inputs", inputs},
          {"duplicate_runs", duplicates}};
}

// The criteria read first (a bad file merges nothing), the merge, then every run of the merged
// report judged by its criteria (or FILE's) and the campaign criteria over all of them: printed
// after the merge's lines, or as the JSON's "verdicts"; exit status 3 if anything failed.
void run_merge(MergeArgs& args) {
  read_verdict_criteria(args.verdicts);
  const replay::MergeResult result = replay::merge_reports(args.inputs, args.output);
  if (!args.json) print_text(result);
  const auto db = replay::open_report_database(result.output, false);
  const std::string suite = result.campaign.empty() ? std::filesystem::path(result.output).stem().string() : result.campaign;
  const auto verdicts = judge_runs(*db, args.verdicts, std::nullopt, suite);
  if (args.json) {
    auto json = result_json(result);
    json["verdicts"] = verdicts_json(verdicts);
    std::cout << json.dump(2) << '\n';
  } else if (verdicts) {
    print_verdicts(std::cout, *verdicts);
  }
  throw_if_failed(verdicts);
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  auto* cmd = app.add_subcommand("merge", "merge report databases (a campaign's shards) into one, atomically; "
                                          "duplicate runs are reported and kept once");
  cmd->add_option("SHARD", args->inputs, "report databases to merge (rcsim-report, read only)")->required();
  cmd->add_option("-o,--output", args->output, "the merged report database; created if missing, else its runs kept")
      ->required();
  cmd->add_flag("--json", args->json, "print the merge's summary and its verdicts as JSON");
  add_verdict_options(*cmd, args->verdicts);
  cmd->callback([args] { run_merge(*args); });
}

}  // namespace rcsim::cli
