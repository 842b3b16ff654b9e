#pragma once
// rcsim report: one self-contained HTML page (inline SVG and CSS, no scripts, no external
// files) that a validation engineer reads: per run the summary tables, bird's-eye pictures of
// chosen cycles, time series, residual histograms, merge-artefact and latency tables, the
// parameters with their sources, and a side-by-side table when several runs are selected; and,
// when the database holds a bench of `rcsim bench`, its speed against error (Pareto plot, tables).
// Every text that came from a recording is HTML-escaped.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace rcsim::replay {

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
};

// Writes the page for the runs and the bench selected by `options` (unknown ids: InputError
// naming `db_label`). A database with a bench but no runs gives the bench section alone.
void write_html_report(SQLite::Database& db, const std::string& db_label, const HtmlReportOptions& options,
                       std::ostream& out);

// Opens the report database at `db_path` (refusing other files), writes the page to `html_path`
// atomically.
void write_html_report_file(const std::string& db_path, const std::string& html_path, const HtmlReportOptions& options);

}  // namespace rcsim::replay
