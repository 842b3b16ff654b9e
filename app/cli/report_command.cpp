// rcsim report REPORT.sqlite -o REPORT.html [--run ID ...] [--bench ID] [--campaign WHEN] [--runs-dir DIR]:
// the validation report a person reads, a campaign's overview first (docs/report.md).
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "replay/report/html_report.hpp"

namespace rcsim::cli {

namespace {

struct ReportArgs {
  std::string db_path;
  std::string html_path;
  std::string campaign = "auto";  // one of kCampaignOverviewNames, shown as such in --help
  replay::HtmlReportOptions options;
};

// --campaign's words, in the order --help shows them, and what each means.
const std::vector<std::string> kCampaignOverviewNames = {"auto", "always", "never", "only"};

replay::CampaignOverview campaign_overview_from_name(const std::string& name) {
  if (name == "always") return replay::CampaignOverview::always;
  if (name == "never") return replay::CampaignOverview::never;
  if (name == "only") return replay::CampaignOverview::only;
  return replay::CampaignOverview::automatic;
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand(
      "report", "write the HTML validation report of runs stored by rcsim replay and of a bench stored by rcsim bench");
  cmd->add_option("REPORT_DB", args->db_path, "report database (rcsim-report, SQLite)")->required();
  cmd->add_option("-o,--output", args->html_path, "HTML file to write (self-contained)")->required();
  cmd->add_option("--run", args->options.run_ids, "run id to report (repeatable); default: the last --last runs");
  cmd->add_option("--bench", args->options.bench_id,
                  "bench id (rcsim bench) shown as speed against error; default: the latest bench, if any");
  cmd->add_option("--last", args->options.last_runs, "without --run: how many of the latest runs to report")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-points", args->options.max_points, "points per time series (longer runs are thinned)")
      ->check(CLI::Range(100, 100000))
      ->capture_default_str();
  cmd->add_option("--pictures", args->options.pictures, "bird's-eye pictures per run")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  cmd->add_option("--trace-cycles", args->options.trace_cycles, "earlier cycles drawn as fading traces")
      ->check(CLI::Range(0, 50))
      ->capture_default_str();
  cmd->add_option("--campaign", args->campaign,
                  "the campaign overview (verdicts, worst runs by each figure, distributions): auto (without --run, "
                  "when the database has a campaign, criteria and several runs, or more than 20 runs), always, never, or only (no run "
                  "sections)")
      ->check(CLI::IsMember(kCampaignOverviewNames, CLI::ignore_case))
      ->capture_default_str();
  cmd->add_option("--runs-dir", args->options.runs_dir,
                  "also write the page of each run the campaign overview lists (worst and failed runs) into DIR as "
                  "run-ID.html, and link them from the overview");
  cmd->add_option("--campaign-rows", args->options.campaign_failed_rows,
                  "failed runs listed in the overview's table before the rest is folded")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->callback([args] {
    args->options.campaign = campaign_overview_from_name(args->campaign);
    const int pages = replay::write_html_report_file(args->db_path, args->html_path, args->options);
    std::cerr << "rcsim report: wrote " << args->html_path;
    if (!args->options.runs_dir.empty()) std::cerr << " and " << pages << " run pages in " << args->options.runs_dir;
    std::cerr << '\n';
  });
}

}  // namespace rcsim::cli
