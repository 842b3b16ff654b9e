#include "replay/report/campaign_section.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "replay/report/html_cells.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

namespace {

using verdict::Criterion;
using verdict::CriterionResult;
using verdict::Scope;
using verdict::Worse;
using svg::escape;

// How bad a value is by the figure's direction: larger is worse.
double badness(Worse worse, double value) {
  switch (worse) {
    case Worse::higher: return value;
    case Worse::lower: return -value;
    case Worse::away_from_zero: return std::abs(value);
    case Worse::away_from_one: return std::abs(value - 1.0);
  }
  return value;
}

std::string_view worse_text(Worse worse) {
  switch (worse) {
    case Worse::higher: return "higher";
    case Worse::lower: return "lower";
    case Worse::away_from_zero: return "away from 0";
    case Worse::away_from_one: return "away from 1";
  }
  return "";
}

// The recording's name, shortened for a table cell, the whole name as its tooltip.
std::string recording_cell(const std::string& name, std::size_t max_chars = 40) {
  return fmt::format(R"(<span class="rec" title="{}">{}</span>)", escape(name), escape(svg::shorten(name, max_chars)));
}

std::string failures_text(const verdict::Verdicts& v, const verdict::RunVerdict& run) {
  std::string out;
  for (const CriterionResult& r : run.results) {
    if (r.passed) continue;
    out += (out.empty() ? "" : "; ") + verdict::describe_failure(v.criteria[r.criterion], r);
  }
  return out;
}

std::string failed_run_row(const verdict::Verdicts& v, const verdict::RunVerdict& run, const RunLinks& links,
                           bool with_hint) {
  return fmt::format(R"(<tr class="fail"><td>{}</td><td>{}</td><td class="num">{}</td><td>{}</td></tr>)",
                     links.link(run.run_id, with_hint), recording_cell(run.recording_name), run.seed,
                     escape(failures_text(v, run)));
}

// Runs passed and failed, the campaign criteria, the verdict.
std::string verdict_counts(const CampaignData& data) {
  const verdict::Verdicts& v = data.verdicts;
  std::set<std::string> recordings;
  double duration_s = 0.0;
  for (const auto& run : data.runs) {
    recordings.insert(run.recording_dir);
    duration_s += run.duration_s;
  }
  const auto judged = static_cast<std::size_t>(
      std::count_if(v.criteria.begin(), v.criteria.end(), [](const Criterion& c) { return c.scope == Scope::recording; }));
  const auto campaign_failed = std::count_if(v.campaign.begin(), v.campaign.end(), [](const auto& r) { return !r.passed; });
  const std::size_t runs = v.runs.size();
  std::string out = R"(<table class="kv verdicts">)";
  out += kv("runs", "Runs", std::to_string(runs), fmt::format("of {} recordings, {} h recorded", recordings.size(),
                                                               svg::fixed(duration_s / 3600.0, 2)));
  if (judged > 0) {
    out += kv("runs_passed", "Runs passed", std::to_string(runs - static_cast<std::size_t>(v.runs_failed)),
              percent(static_cast<std::int64_t>(runs) - v.runs_failed, static_cast<std::int64_t>(runs)));
    out += kv("runs_failed", "Runs failed", std::to_string(v.runs_failed),
              fmt::format("{}, by {} per-recording criteria", percent(v.runs_failed, static_cast<std::int64_t>(runs)),
                          judged));
  }
  if (!v.campaign.empty()) {
    out += kv("campaign_passed", "Campaign criteria passed",
              std::to_string(v.campaign.size() - static_cast<std::size_t>(campaign_failed)),
              fmt::format("of {}", v.campaign.size()));
  }
  if (!v.criteria.empty()) {
    out += fmt::format(R"(<tr><th>Verdict</th><td class="{0}" data-key="verdict">{1}</td><td>{2}</td></tr>)",
                       v.passed() ? "pass" : "fail", v.passed() ? "PASS" : "FAIL",
                       v.passed() ? "every criterion passed"
                                  : (data.name.empty() ? "a criterion failed" : "a criterion failed (rcsim merge exits with status 3)"));
  }
  return out + "</table>";
}

// One row per criterion: what it says, and how the runs or the campaign fared.
std::string criteria_table(const CampaignData& data) {
  const verdict::Verdicts& v = data.verdicts;
  std::vector<std::size_t> failed(v.criteria.size(), 0), missing(v.criteria.size(), 0);
  for (const auto& run : v.runs) {
    for (const CriterionResult& r : run.results) {
      failed[r.criterion] += r.passed ? 0 : 1;
      missing[r.criterion] += r.value ? 0 : 1;
    }
  }
  std::vector<const CriterionResult*> campaign_result(v.criteria.size(), nullptr);
  for (const CriterionResult& r : v.campaign) campaign_result[r.criterion] = &r;

  std::string out = R"(<div class="scroll"><table class="criteria">)";
  out += header_row({"#", "criterion", "scope", "if missing", "value", "runs failed", "runs missing the figure", "verdict"});
  for (std::size_t i = 0; i < v.criteria.size(); ++i) {
    const Criterion& c = v.criteria[i];
    bool passed = true;
    std::string value = "\u2013", runs_failed = "\u2013", runs_missing = "\u2013";
    if (c.scope == Scope::campaign && campaign_result[i] != nullptr) {
      passed = campaign_result[i]->passed;
      value = campaign_result[i]->value ? figure_value(*campaign_result[i]->value) : "missing";
    } else if (c.scope == Scope::recording) {
      passed = failed[i] == 0;
      runs_failed = fmt::format("{} of {}", failed[i], v.runs.size());
      runs_missing = std::to_string(missing[i]);
    }
    out += fmt::format(
        R"(<tr class="{0}" data-criterion="{1}"><td class="num">{1}</td>{2}{3}{4}<td class="num" data-key="value">{5}</td>)"
        R"(<td class="num" data-key="runs_failed">{6}</td><td class="num">{7}</td><td class="{0}">{8}</td></tr>)",
        passed ? "pass" : "fail", i, cell(c.text()), cell(c.scope == Scope::campaign ? "campaign" : "recording"),
        cell(c.pass_if_missing ? "pass" : "fail"), escape(value), runs_failed, runs_missing, passed ? "pass" : "FAIL");
  }
  return out + "</table></div>";
}

// The failed runs in run order: the first `rows` in a table, the others folded below it.
std::string failed_runs(const CampaignData& data, const RunLinks& links, int rows) {
  const verdict::Verdicts& v = data.verdicts;
  if (v.runs_failed == 0) return R"(<p class="hint">No run failed a per-recording criterion.</p>)";
  const std::string header = header_row({"run", "recording", "seed", "failed criteria (value against threshold)"});
  std::string out = R"(<div class="scroll"><table class="failed-runs">)" + header;
  int shown = 0;
  std::string rest;
  for (const auto& run : v.runs) {
    if (run.passed) continue;
    if (shown < rows) {
      out += failed_run_row(v, run, links, true);
      ++shown;
    } else {
      rest += failed_run_row(v, run, links, false);
    }
  }
  out += "</table></div>";
  const int more = v.runs_failed - shown;
  if (more > 0) {
    out += fmt::format(R"(<p class="hint">{} more failed runs.</p><details class="failed-rest"><summary>The other {} )"
                       R"(failed runs</summary><div class="scroll"><table class="failed-runs">{}{}</table></div></details>)",
                       more, more, header, rest);
  }
  return out;
}

// One row per figure: the `n` worst runs by it, each with its value.
std::string worst_table(const CampaignData& data, const RunLinks& links, int n) {
  std::string out = R"(<div class="scroll"><table class="worst"><tr><th>figure</th><th>unit</th><th>worse</th>)";
  for (int k = 1; k <= n; ++k) out += fmt::format("<th>{}.</th>", k);
  out += "</tr>";
  for (std::size_t f = 0; f < data.figures.size(); ++f) {
    const verdict::FigureInfo& info = data.figures[f];
    out += fmt::format(R"(<tr data-figure="{0}"><th title="{1}">{0}</th><td>{2}</td><td>{3}</td>)", escape(info.name),
                       escape(info.meaning), escape(info.unit), worse_text(info.worse));
    const std::vector<std::size_t> worst = worst_runs(data, f, n);
    if (worst.empty()) {
      out += fmt::format(R"(<td colspan="{}" class="hint">no run has this figure</td></tr>)", n);
      continue;
    }
    // A figure every run has alike ranks nothing.
    const std::vector<double> sorted = data.sorted_values(f);
    if (sorted.size() > 1 && sorted.front() == sorted.back()) {
      out += fmt::format(R"(<td colspan="{}" class="hint">the same in every run that has it ({} of {}): )"
                         R"(<span class="num">{}</span></td></tr>)",
                         n, sorted.size(), data.runs.size(), figure_value(sorted.front()));
      continue;
    }
    for (const std::size_t r : worst) {
      const auto& run = data.runs[r];
      out += fmt::format(R"(<td><span class="num">{}</span> {}<br>{}</td>)", figure_value(*run.values[f]),
                         links.link(run.run_id, true), recording_cell(run.recording_name, 24));
    }
    for (std::size_t k = worst.size(); k < static_cast<std::size_t>(n); ++k) out += "<td></td>";
    out += "</tr>";
  }
  return out + "</table></div>";
}

bool contains(const std::vector<std::int64_t>& sorted, std::int64_t id) {
  return std::binary_search(sorted.begin(), sorted.end(), id);
}

}  // namespace

std::string figure_value(double value) {
  if (!std::isfinite(value)) return "\u2013";
  std::string text = fmt::format("{:.4g}", value);
  if (text == "-0") text = "0";
  return text;
}

std::string RunLinks::link(std::int64_t run_id, bool with_hint) const {
  if (contains(on_page, run_id)) return fmt::format(R"(<a href="#run-{0}">run {0}</a>)", run_id);
  if (!pages_href.empty() && contains(pages, run_id)) {
    return fmt::format(R"(<a href="{0}run-{1}.html">run {1}</a>)", escape(pages_href), run_id);
  }
  if (!with_hint) return fmt::format("run {}", run_id);
  return fmt::format(R"(<span class="norun" title="rcsim report {0} --run {1} -o run-{1}.html">run {1}</span>)",
                     escape(db_label), run_id);
}

std::vector<std::size_t> worst_runs(const CampaignData& data, std::size_t figure, int n) {
  const Worse worse = data.figures[figure].worse;
  std::vector<std::pair<double, std::size_t>> ranked;  // (-badness, index): ascending is worst first
  ranked.reserve(data.runs.size());
  for (std::size_t r = 0; r < data.runs.size(); ++r) {
    if (const auto& v = data.runs[r].values[figure]) ranked.emplace_back(-badness(worse, *v), r);
  }
  const std::size_t k = std::min(ranked.size(), static_cast<std::size_t>(std::max(0, n)));
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(k), ranked.end());
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < k; ++i) out.push_back(ranked[i].second);
  return out;
}

std::vector<std::int64_t> overview_linked_runs(const CampaignData& data, const CampaignOverviewOptions& options) {
  std::set<std::int64_t> ids;
  for (std::size_t f = 0; f < data.figures.size(); ++f) {
    for (const std::size_t r : worst_runs(data, f, options.worst)) ids.insert(data.runs[r].run_id);
  }
  int listed = 0;
  for (const auto& run : data.verdicts.runs) {
    if (listed >= options.failed_rows) break;
    if (!run.passed) {
      ids.insert(run.run_id);
      ++listed;
    }
  }
  return {ids.begin(), ids.end()};
}

std::string campaign_overview(const CampaignData& data, const RunLinks& links, const CampaignOverviewOptions& options) {
  const verdict::Verdicts& v = data.verdicts;
  std::string out = R"(<section class="campaign" id="campaign">)";
  // A report of no campaign (many replays into one database) gets the same overview, not called a campaign.
  out += data.name.empty() ? std::string("<h2>Verdicts of all runs</h2>")
                           : fmt::format("<h2>Campaign overview: {}</h2>", escape(data.name));
  out += R"(<p class="hint">Every run of the database, judged by the criteria stored in it (schemas/campaign.md), )"
         "ranked and summarised by the figures campaigns are judged by. ";
  if (!links.on_page.empty()) out += "Runs detailed on this page link to their section below. ";
  if (!links.pages.empty()) {
    out += fmt::format("The other runs listed link to their own page in <code>{}</code>. ", escape(links.pages_href));
  } else {
    out += fmt::format("For any other run, <code>rcsim report {} --run ID -o run-ID.html</code> writes its page "
                       "(the command is each run's tooltip); <code>--runs-dir DIR</code> writes the pages of every run "
                       "listed here and links them.",
                       escape(links.db_label));
  }
  out += "</p>";
  out += R"(<nav><ul class="campaign-nav"><li><a href="#campaign-verdicts">Verdicts</a></li>)"
         R"(<li><a href="#campaign-worst">Worst runs by each figure</a></li>)"
         R"(<li><a href="#campaign-distributions">Distributions over the campaign</a></li></ul></nav>)";

  out += R"(<h3 id="campaign-verdicts">Verdicts</h3>)" + verdict_counts(data);
  if (v.criteria.empty()) {
    out += R"(<p class="hint">The database holds no criteria, so no run is judged. <code>rcsim merge --criteria FILE</code> )"
           "or <code>rcsim replay --criteria FILE</code> stores them (schemas/campaign.md).</p>";
  } else {
    out += "<h4>Criteria</h4>" + criteria_table(data);
    if (std::any_of(v.criteria.begin(), v.criteria.end(), [](const Criterion& c) { return c.scope == Scope::recording; })) {
      out += "<h4>Failed runs</h4>" + failed_runs(data, links, options.failed_rows);
    }
  }

  out += fmt::format(R"(<h3 id="campaign-worst">Worst runs by each figure</h3><p class="hint">The {} worst runs by )"
                     "each figure that some run has, by the direction in which it gets worse (schemas/campaign.md, "
                     "\"Figures\"); hover over a figure for its meaning.</p>",
                     options.worst);
  out += worst_table(data, links, options.worst);
  out += campaign_distributions(data, options.histogram_bins);
  return out + "</section>\n";
}

}  // namespace rcsim::replay::report
