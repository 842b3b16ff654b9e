#pragma once
// rcsim report: one self-contained HTML page (inline SVG and CSS, no scripts, no external
// files) that a validation engineer reads: per run the summary tables, bird's-eye pictures of
// chosen cycles, time series, residual histograms, merge-artefact and latency tables, the
// parameters with their sources, and a side-by-side table when several runs are selected; and,
// when the database holds a bench of `rcsim bench`, its speed against error (Pareto plot, tables).
// A campaign's database (criteria, a campaign, or more runs than a page details) starts with the
// campaign overview: verdicts, the worst runs by each figure, the figures' distributions, links
// into each run's detail (campaign_section.hpp). Every text that came from a recording is
// HTML-escaped.

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>
#include "replay/store/report_database.hpp"

namespace rcsim::replay {

// When the page starts with the campaign overview (docs/report.md, "Campaign report").
enum class CampaignOverview {
  automatic,  // without --run: a named campaign, criteria over more than one run, or more than 20 runs
  always,
  never,
  only,  // the overview alone, no run sections
};

// The stylesheet of every HTML page rcsim writes (the report, the profile derivation's).
const char* report_stylesheet();

struct HtmlReportOptions {
  std::vector<std::int64_t> run_ids;  // empty: the last `last_runs` runs of the database
  int last_runs = 20;
  // Points per time series for up to four runs; with more runs the budget is shared
  // (4 * max_points / runs, at least 250) so that the page stays small.
  int max_points = 2000;
  int pictures = 5;      // bird's-eye pictures per run
  int trace_cycles = 5;  // earlier cycles drawn as fading traces
  int histogram_bins = 41;
  int object_pictures = 12;  // objects drawn in their own frame per run (the most targets first)
  std::optional<std::int64_t> bench_id;  // the bench shown as "Speed against error"; absent: the latest
  CampaignOverview campaign = CampaignOverview::automatic;
  int campaign_worst = 5;          // runs listed per figure
  int campaign_failed_rows = 50;   // failed runs listed before the rest is folded
  // write_html_report_file only: a directory into which the pages of the runs the overview lists
  // (and does not detail) are written, run-ID.html, linked from the overview. Empty: none.
  std::string runs_dir;
};

// Databases with more runs than this get the campaign overview by default.
inline constexpr std::size_t kCampaignOverviewRuns = 20;

// Writes the page for the runs and the bench selected by `options` (unknown ids: InputError
// naming `db_label`). A database with a bench but no runs gives the bench section alone.
void write_html_report(ReportDatabase& db, const std::string& db_label, const HtmlReportOptions& options,
                       std::ostream& out);

// Opens the report database at `db_path` (refusing other files), writes the page to `html_path`
// atomically; with options.runs_dir, first the pages of the runs the overview lists, each atomically.
// Returns how many run pages it wrote.
int write_html_report_file(const std::string& db_path, const std::string& html_path, const HtmlReportOptions& options);

}  // namespace rcsim::replay
