// rcsim report REPORT.sqlite -o REPORT.html [--run ID ...] [--bench ID] [--campaign WHEN] [--runs-dir DIR]:
// the validation report a person reads, a campaign's overview first (docs/report.md).
#include <iostream>
#include <map>

#include "cli/commands.hpp"
#include "replay/report/html_report.hpp"

namespace rcsim::cli {

namespace {

struct ReportArgs {
  std::string db_path;
  std::string html_path;
  replay::HtmlReportOptions options;
};

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
  const std::map<std::string, replay::CampaignOverview> when = {{"auto", replay::CampaignOverview::automatic},
                                                                 {"always", replay::CampaignOverview::always},
                                                                 {"never", replay::CampaignOverview::never},
                                                                 {"only", replay::CampaignOverview::only}};
  cmd->add_option("--campaign", args->options.campaign,
                  "the campaign overview (verdicts, worst runs by each figure, distributions): auto (without --run, "
                  "when the database has criteria, a campaign or more than 20 runs), always, never, or only (no run "
                  "sections)")
      ->transform(CLI::CheckedTransformer(when, CLI::ignore_case))
      ->default_str("auto");
  cmd->add_option("--runs-dir", args->options.runs_dir,
                  "also write the page of each run the campaign overview lists (worst and failed runs) into DIR as "
                  "run-ID.html, and link them from the overview");
  cmd->add_option("--campaign-rows", args->options.campaign_failed_rows,
                  "failed runs listed in the overview's table before the rest is folded")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->callback([args] {
    const int pages = replay::write_html_report_file(args->db_path, args->html_path, args->options);
    std::cerr << "rcsim report: wrote " << args->html_path;
    if (!args->options.runs_dir.empty()) std::cerr << " and " << pages << " run pages in " << args->options.runs_dir;
    std::cerr << '\n';
  });
}

}  // namespace rcsim::cli
