#include "replay/report/html_report.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <fmt/format.h>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "replay/verdict/default_criteria.hpp"
#include "replay/report/campaign_section.hpp"
#include "replay/report/verdict_section.hpp"
#include "replay/report/bench_section.hpp"
#include "replay/store/campaign_store.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/report/html_cells.hpp"
#include "replay/report/html_report_figures.hpp"
#include "replay/report/html_report_tables.hpp"
#include "replay/report/real_drive_sections.hpp"
#include "replay/store/report_store.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay {

namespace {

using svg::escape;

constexpr const char* kStyle = R"CSS(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #212529; margin: 24px auto;
       max-width: 1320px; padding: 0 16px; }
h1 { font-size: 24px; margin-bottom: 4px; }
h2 { font-size: 20px; border-bottom: 2px solid #343a40; padding-bottom: 3px; margin-top: 40px; }
h3 { font-size: 16px; margin: 22px 0 6px; }
h4 { font-size: 14px; margin: 16px 0 6px; }
p.meta, p.hint { color: #555; font-size: 13px; }
table { border-collapse: collapse; margin: 6px 0 14px; font-size: 13px; }
th, td { border: 1px solid #ced4da; padding: 3px 8px; vertical-align: top; }
th { background: #f1f3f5; text-align: left; font-weight: 600; white-space: pre; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.kv th { min-width: 200px; }
table.kv td.text { text-align: left; }
.scroll { overflow-x: auto; }
.cols { display: flex; flex-wrap: wrap; gap: 24px; align-items: flex-start; }
.figs { display: flex; flex-wrap: wrap; gap: 14px; }
.figs svg { border: 1px solid #dee2e6; }
svg text { font-family: system-ui, sans-serif; }
svg .title { font-size: 13px; font-weight: 600; fill: #212529; }
svg .note { font-size: 11px; fill: #666; }
svg .axis-label { font-size: 12px; fill: #333; }
svg .legend { font-size: 12px; fill: #333; }
svg .box-label { font-size: 10px; fill: #343a40; }
pre { background: #f8f9fa; border: 1px solid #e9ecef; padding: 8px; overflow: auto; max-height: 320px; font-size: 12px; }
details { margin: 4px 0; }
.swatch { display: inline-block; width: 10px; height: 10px; border-radius: 5px; margin: 0 4px 0 10px; }
nav ul { columns: 2; }
tr.default td { background: #fff4e6; }
td.pass { color: #2b8a3e; font-weight: 600; }
.mark { display: inline-block; padding: 1px 8px; border-radius: 3px; color: #fff; font-weight: 700; }
.mark.pass { background: #2b8a3e; }
.mark.fail { background: #c92a2a; }
div.verdict { border-left: 5px solid #2b8a3e; padding: 2px 12px; margin: 8px 0 16px; background: #f4fbf5; }
div.verdict.fail { border-left-color: #c92a2a; background: #fdf3f3; }
p.verdict-line { font-size: 1.1em; }
td.fail, tr.fail td.fail { color: #c92a2a; font-weight: 600; }
tr.fail td:first-child { border-left: 3px solid #c92a2a; }
table.worst td { font-size: 12px; }
table.worst td .num { font-variant-numeric: tabular-nums; font-weight: 600; }
table.worst td .num, table.worst td a, table.worst td .norun { white-space: nowrap; }
.rec { color: #495057; }
.norun { border-bottom: 1px dotted #868e96; cursor: help; }
section.campaign .figs svg { border: 1px solid #dee2e6; }
ul.campaign-nav { columns: 1; }
)CSS";

// The chosen cycles, each with the cycles before it faded.
void write_birdseye_pictures(std::ostream& out, ReportDatabase& db, const report::RunData& run,
                             const HtmlReportOptions& options) {
  out << R"(<div class="figs">)";
  const auto chosen_cycles = report::choose_cycles(report::read_cycle_highlights(db, run.info.run_id), run,
                                                   static_cast<std::size_t>(std::max(0, options.pictures)));
  for (const auto& chosen : chosen_cycles) {
    const int first_cycle = std::max(0, chosen.cycle - std::max(0, options.trace_cycles));
    out << svg::birdseye_svg(report::birdseye_of_cycle(
        run, chosen, report::read_cycle_window(db, run.info.run_id, first_cycle, chosen.cycle)));
  }
  out << "</div>";
}

// What the run sections open with: every run's verdict and label.
struct RunVerdicts {
  verdict::Verdicts verdicts;
  std::map<std::int64_t, RunLabel> labels;
  const verdict::RunVerdict* of(std::int64_t run_id) const {
    const auto it = std::find_if(verdicts.runs.begin(), verdicts.runs.end(),
                                 [&](const verdict::RunVerdict& r) { return r.run_id == run_id; });
    return it == verdicts.runs.end() ? nullptr : &*it;
  }
};

// Where the report shows a run's rows thinned or summarised, the command that gives them all.
std::string every_row_line(const std::string& db_label, std::int64_t run_id) {
  const bool plain = db_label.find_first_of(" '\"$`\\") == std::string::npos;
  const std::string db = plain ? db_label : "'" + db_label + "'";
  return fmt::format(R"(<p class="hint rows-query">The plots and pictures show what a screen can: series thinned, marks on one )"
                     R"(another drawn once. Every row is a query away: each cycle's figures <code>rcsim export {0} --run {1} )"
                     R"(--table cycles</code>, every target <code>rcsim export {0} --run {1} --table targets</code>, the boxes )"
                     R"(<code>--table objects</code> (CSV; <code>--format jsonl</code>), or in SQL (docs/sql.md).</p>)",
                     escape(db), run_id);
}

void write_run_section(std::ostream& out, ReportDatabase& db, const std::string& db_label, const report::RunData& run,
                       const HtmlReportOptions& options, int max_points, const RunVerdicts& judged) {
  const report::RunInfo& i = run.info;
  const verdict::RunVerdict* verdict = judged.of(i.run_id);
  out << fmt::format(R"(<section class="run" id="run-{}"><h2>Run {}: {}{}</h2>)", i.run_id, i.run_id,
                     escape(i.recording_name), verdict == nullptr ? "" : " " + report::verdict_mark(verdict->passed));
  if (verdict != nullptr && judged.labels.count(i.run_id) != 0) {
    out << report::run_verdict_block(run, judged.verdicts, *verdict, judged.labels.at(i.run_id));
  }
  out << R"(<div class="cols"><div><h3>Run</h3>)" << report::run_information_table(run)
      << "</div><div><h3>Summary</h3>" << report::summary_table(run) << "</div></div>";
  out << R"(<h3>Sensors</h3><div class="scroll">)" << report::sensor_table(run) << "</div>";
  out << R"(<div class="cols"><div><h3>Objects</h3>)" << report::object_table(run)
      << "</div><div><h3>Distribution distances, recorded against simulated</h3>" << report::distance_table(run)
      << "</div></div>";

  out << fmt::format(R"(<h3 id="run-{}-pictures">Bird's-eye view of chosen cycles</h3>)", i.run_id)
      << R"(<p class="hint">Ego vehicle frame of the pictured cycle, x forward (up), y left. Cycles chosen )"
         "automatically: the largest GOSPA, the most merge artefacts, the first recorded target, the middle of the "
         "run, the first simulated target, the largest difference in target counts, then the last cycle and the "
         "quarters.</p>";
  if (!i.has_targets()) {
    out << report::needs_full_store("The bird's-eye pictures");
  } else {
    write_birdseye_pictures(out, db, run, options);
  }

  out << fmt::format(R"(<h3 id="run-{}-series">Time series</h3>)", i.run_id);
  if (!i.has_targets()) out << report::needs_full_store("The plots of the nearest object target's range and lateral position");
  out << R"(<div class="figs">)";
  const int stride = report::series_stride(run, max_points);
  const auto nearest = i.has_targets() ? report::read_nearest_targets(db, i.run_id, stride)
                                       : std::vector<report::NearestTargetRow>{};
  for (const auto& plot : report::time_series(run, stride, nearest, report::read_cycle_buckets(db, i.run_id, stride))) {
    out << svg::plot_svg(plot);
  }
  out << "</div>" << every_row_line(db_label, i.run_id);

  out << fmt::format(R"(<h3 id="run-{}-residuals">Residuals of assigned pairs</h3>)", i.run_id);
  if (!i.has_targets()) {
    out << report::needs_full_store("The residual histograms");
  } else {
    out << R"(<div class="figs">)";
    report::ResidualHistograms histograms(
        report::read_residual_sample_stats(db, i.run_id, report::residual_sample_stride(run)), options.histogram_bins);
    report::for_each_residual(db, i.run_id, [&](const report::Residuals& r) { histograms.add(r); });
    for (const auto& h : histograms.specs()) out << svg::histogram_svg(h);
    out << "</div>";
  }

  out << fmt::format(R"(<h3 id="run-{}-objects">Annotated objects</h3>)", i.run_id)
      << report::object_section(db, run, options.object_pictures);
  out << fmt::format(R"(<h3 id="run-{}-background">Stationary background</h3>)", i.run_id)
      << report::background_section(db, run);

  out << fmt::format(R"(<h3 id="run-{}-merge">Merge artefacts per object pair and sensor</h3>)", i.run_id)
      << report::merge_artefact_table(run);
  out << "<h3>Confirmation latency per object and sensor</h3>" << report::latency_table(run);
  out << "<h3>Parameters and sources</h3>" << report::parameter_table(run);
  out << "<h3>Provenance</h3>" << report::provenance_blocks(run);
  out << "</section>\n";
}

// What a page shows: the bench, the runs detailed, whether the campaign overview comes first.
struct PageSelection {
  std::optional<std::int64_t> bench_id;
  std::size_t all_runs = 0;
  std::vector<std::int64_t> ids;  // detailed, ascending as selected
  bool overview = false;
};

PageSelection select_page(ReportDatabase& db, const std::string& db_label, const HtmlReportOptions& options) {
  PageSelection s;
  const bool only = options.campaign == CampaignOverview::only;
  s.bench_id = only ? std::nullopt : report::select_bench(db, db_label, options.bench_id);
  s.all_runs = report::run_ids(db).size();
  // A bench alone makes a page; with neither runs nor a bench, select_runs says there are no runs.
  const bool bench_alone = s.bench_id && s.all_runs == 0 && options.run_ids.empty();
  if (!bench_alone && (!only || s.all_runs == 0 || !options.run_ids.empty())) {
    s.ids = report::select_runs(db, db_label, options.run_ids, options.last_runs);
  }
  if (only) s.ids.clear();
  switch (options.campaign) {
    case CampaignOverview::always:
    case CampaignOverview::only: s.overview = true; break;
    case CampaignOverview::never: s.overview = false; break;
    case CampaignOverview::automatic:
      // A named campaign always; criteria alone (a replay --criteria) only over several runs: one
      // run's own section opens with its verdict, which an overview would repeat.
      s.overview = options.run_ids.empty() && s.all_runs > 0 &&
                   (s.all_runs > kCampaignOverviewRuns || !read_campaign_name(db).value_or("").empty() ||
                    (s.all_runs > 1 && report::is_campaign_database(db)));
      break;
  }
  return s;
}

// How the page links: to the campaign overview's data and run pages, back to an overview.
struct PageContext {
  const report::CampaignData* campaign = nullptr;  // null: no overview
  std::string pages_href;                          // run pages written beside the page ("c-runs/")
  std::vector<std::int64_t> pages;
  std::string back_href;  // a run page's link back to its overview
};

report::CampaignOverviewOptions overview_options(const HtmlReportOptions& options) {
  report::CampaignOverviewOptions o;
  o.worst = std::max(1, options.campaign_worst);
  o.failed_rows = std::max(0, options.campaign_failed_rows);
  return o;
}

void write_page(ReportDatabase& db, const std::string& db_label, const HtmlReportOptions& options,
                const PageSelection& selection, const PageContext& context, std::ostream& out) {
  const std::optional<report::BenchData> bench =
      selection.bench_id ? std::optional<report::BenchData>(report::load_bench(db, *selection.bench_id)) : std::nullopt;
  std::vector<report::RunData> runs;
  for (const std::int64_t id : selection.ids) runs.push_back(report::load_run(db, id));
  RunVerdicts judged;
  if (!runs.empty()) {
    judged.verdicts = verdict::judge_report(db);
    judged.labels = read_run_labels(db);
  }
  const int n = static_cast<int>(runs.size());
  const int max_points = n <= 4 ? options.max_points : std::max(250, 4 * options.max_points / n);
  const report::CampaignData* campaign = context.campaign;

  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">";
  if (campaign != nullptr && !campaign->name.empty()) {
    out << "<title>rcsim campaign report: " << escape(campaign->name) << "</title>";
  } else {
    out << "<title>rcsim validation report: " << escape(db_label) << "</title>";
  }
  out << "<style>" << kStyle << "</style></head><body>\n";
  if (campaign != nullptr && !campaign->name.empty()) {
    out << "<h1>rcsim campaign report: " << escape(campaign->name) << "</h1>";
  } else {
    out << "<h1>rcsim validation report</h1>";
  }
  if (!context.back_href.empty()) {
    out << fmt::format(R"(<p class="meta"><a href="{}#campaign">&larr; The campaign overview</a></p>)",
                       escape(context.back_href));
  }
  out << "<p class=\"meta\">Report database <code>" << escape(db_label) << "</code>; "
      << fmt::format("{} of its {} runs shown", n, selection.all_runs);
  if (campaign != nullptr) out << " in detail, all of them in the campaign overview";
  if (bench) out << fmt::format(", and bench {} of its {} benches", bench->info.bench_id, report::bench_ids(db).size());
  out << fmt::format("; written by rcsim {}.", RCSIM_VERSION) << "</p>";
  if (!runs.empty()) {
    out << "<p class=\"hint\">Recorded targets are drawn as dots, simulated targets as diamonds; targets of "
           "annotated objects in"
        << fmt::format(R"(<span class="swatch" style="background:{}"></span>blue (recorded) and)", svg::kRecordedColour)
        << fmt::format(R"(<span class="swatch" style="background:{}"></span>orange (simulated),)", svg::kSimulatedColour)
        << " the stationary background grey, other targets teal."
        << " GOSPA (&alpha; = 2) and OSPA are computed per cycle and sensor in the sensor's Cartesian frame; the "
           "localisation, missed and false parts are in mᵖ and add up to GOSPAᵖ. Residuals are simulated minus "
           "recorded of the assigned pairs. Latency is the time from when an object becomes detectable to its "
           "first reported target.</p>\n";
  }
  out << "<nav><ul>";
  if (campaign != nullptr) {
    out << fmt::format(R"(<li><a href="#campaign">{}</a>: {} runs{}</li>)",
                       campaign->name.empty() ? "Verdicts of all runs" : "Campaign overview", campaign->runs.size(),
                       campaign->verdicts.criteria.empty()
                           ? std::string()
                           : fmt::format(", {} failed, {}", campaign->verdicts.runs_failed,
                                         campaign->verdicts.passed() ? "PASS" : "FAIL"));
  }
  for (const auto& r : runs) {
    const verdict::RunVerdict* verdict = judged.of(r.info.run_id);
    const auto label = judged.labels.find(r.info.run_id);
    out << fmt::format(R"(<li>{}<a href="#run-{}">Run {}</a>: {}{}</li>)",
                       verdict == nullptr ? "" : report::verdict_mark(verdict->passed) + " ", r.info.run_id,
                       r.info.run_id, escape(r.info.recording_name),
                       label == judged.labels.end() ? fmt::format(", seed {}", r.info.seed)
                                                    : ", " + escape(label->second.text()));
  }
  if (bench) {
    out << fmt::format(R"(<li><a href="#bench-{0}">Speed against error</a> (after the runs): bench {0}, {1} recordings</li>)",
                       bench->info.bench_id, bench->recordings().size());
  }
  out << "</ul></nav>\n";
  if (campaign != nullptr) {
    report::RunLinks links;
    links.db_label = db_label;
    links.on_page = selection.ids;
    std::sort(links.on_page.begin(), links.on_page.end());
    links.pages_href = context.pages_href;
    links.pages = context.pages;
    out << report::campaign_overview(*campaign, links, overview_options(options));
  }
  if (runs.size() > 1) {
    out << "<h2>Runs side by side</h2>" << report::comparison_table(runs, judged.labels) << "\n";
  }
  for (const auto& run : runs) write_run_section(out, db, db_label, run, options, max_points, judged);
  // The bench measures rcsim, not the model against a recording: after the runs.
  if (bench) out << report::bench_section(*bench);
  out << "</body></html>\n";
}

// `to` relative to the directory `from_dir`, with '/' separators, as a URL path: the characters
// that would end or bend it (space, '#', '?', '%', quotes, and anything not ASCII) percent-encoded.
std::string relative_href(const std::filesystem::path& to, const std::filesystem::path& from_dir) {
  const auto absolute = [](const std::filesystem::path& p) { return std::filesystem::absolute(p).lexically_normal(); };
  std::filesystem::path rel = absolute(to).lexically_relative(absolute(from_dir));
  if (rel.empty()) rel = absolute(to);
  std::string href;
  for (const char c : rel.generic_string()) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 0x20 || u >= 0x7f || c == '#' || c == '?' || c == '%' || c == '"' || c == '\'' || c == '<' || c == '>') {
      href += fmt::format("%{:02X}", u);
    } else {
      href += c;
    }
  }
  return href;
}

}  // namespace

void write_html_report(ReportDatabase& db, const std::string& db_label, const HtmlReportOptions& options,
                       std::ostream& out) {
  const PageSelection selection = select_page(db, db_label, options);
  std::optional<report::CampaignData> campaign;
  if (selection.overview) campaign = report::read_campaign_data(db);
  PageContext context;
  context.campaign = campaign ? &*campaign : nullptr;
  write_page(db, db_label, options, selection, context, out);
}

namespace {

int write_report_pages(const std::string& db_path, const std::string& html_path, const HtmlReportOptions& options) {
  const auto db = open_report_database_for_reading(db_path);
  const PageSelection selection = select_page(*db, db_path, options);
  std::optional<report::CampaignData> campaign;
  if (selection.overview) campaign = report::read_campaign_data(*db);
  PageContext context;
  context.campaign = campaign ? &*campaign : nullptr;

  // The run pages first, so that the overview never links to a page not yet written.
  int pages_written = 0;
  if (campaign && !options.runs_dir.empty()) {
    const std::filesystem::path dir = options.runs_dir;
    std::filesystem::create_directories(dir);
    const std::filesystem::path html_dir = std::filesystem::path(html_path).parent_path();
    context.pages_href = relative_href(dir, html_dir.empty() ? "." : html_dir) + "/";
    std::vector<std::int64_t> on_page = selection.ids;
    std::sort(on_page.begin(), on_page.end());
    HtmlReportOptions run_options = options;
    run_options.campaign = CampaignOverview::never;
    run_options.runs_dir.clear();
    PageContext run_context;
    run_context.back_href = relative_href(html_path, dir);
    for (const std::int64_t id : report::overview_linked_runs(*campaign, overview_options(options))) {
      if (std::binary_search(on_page.begin(), on_page.end(), id)) continue;
      run_options.run_ids = {id};
      PageSelection run_selection;
      run_selection.all_runs = selection.all_runs;
      run_selection.ids = {id};
      AtomicFileWriter writer((dir / fmt::format("run-{}.html", id)).string());
      write_page(*db, db_path, run_options, run_selection, run_context, writer.stream());
      writer.commit();
      context.pages.push_back(id);
      ++pages_written;
    }
  }
  AtomicFileWriter writer(html_path);
  write_page(*db, db_path, options, selection, context, writer.stream());
  writer.commit();
  return pages_written;
}

}  // namespace

int write_html_report_file(const std::string& db_path, const std::string& html_path, const HtmlReportOptions& options) {
  try {
    return write_report_pages(db_path, html_path, options);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // SQLite's "malformed" and a damaged block's message: bad input, named (exit status 2).
    throw InputError(db_path, "", e.what());
  }
}

const char* report_stylesheet() { return kStyle; }

}  // namespace rcsim::replay
