#include "replay/report/verdict_section.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "replay/report/html_cells.hpp"
#include "replay/run/run_kind.hpp"

namespace rcsim::replay::report {

namespace {

std::string what_judged(const verdict::Verdicts& v, ListLevel kind) {
  switch (v.source) {
    case verdict::CriteriaSource::defaults:
      return fmt::format("the default tolerances for {} (docs/verdicts.md)", list_level_name(kind));
    case verdict::CriteriaSource::file: return "the criteria of --criteria";
    case verdict::CriteriaSource::report: return "the criteria stored in this report";
  }
  return "";
}

std::string value_text(const std::optional<double>& value) {
  return value ? fmt::format("{:.4g}", *value) : std::string("missing");
}

// Why all-target GOSPA is not judged where the background is a density.
std::string all_target_note(const RunData& run) {
  if (!run.summary) return "";
  return fmt::format(
      R"(<p class="hint">All-target GOSPA ({:.3f} m) is not judged on detections: the stationary background is )"
      "drawn from a density (paper VI), right on average but never point by point, so each background point counts "
      "as a miss and a false target at once and a faithful background raises it. The objects' GOSPA and the "
      "background's count and distributions measure the model (docs/verdicts.md).</p>",
      run.summary->gospa_mean_m);
}

}  // namespace

std::string verdict_mark(bool passed) {
  return fmt::format(R"(<span class="mark {}">{}</span>)", passed ? "pass" : "fail", passed ? "PASS" : "FAIL");
}

std::string run_verdict_block(const RunData& run, const verdict::Verdicts& verdicts, const verdict::RunVerdict& rv,
                              const RunLabel& label) {
  const std::vector<verdict::FigureVerdict> figures = verdict::figure_verdicts(verdicts, rv);
  const auto met = std::count_if(figures.begin(), figures.end(), [](const auto& f) { return f.passed; });
  std::string out = fmt::format(R"(<div class="verdict {}" data-key="run-verdict">)", rv.passed ? "pass" : "fail");
  out += fmt::format(R"(<p class="verdict-line">{} {} of {} figures within {}.</p>)", verdict_mark(rv.passed), met,
                     figures.size(), svg::escape(what_judged(verdicts, rv.kind)));
  out += R"(<table class="verdict"><tr><th>figure</th><th>meaning</th><th>value</th><th>tolerance</th><th></th></tr>)";
  for (const verdict::FigureVerdict& f : figures) {
    const auto info = verdict::find_figure(f.figure);
    out += fmt::format(R"(<tr class="{}"><td class="text">{}</td><td class="text">{}</td>)", f.passed ? "pass" : "fail",
                       svg::escape(f.figure), svg::escape(info ? info->meaning : std::string()));
    out += cell_num(value_text(f.value)) + cell_num(f.tolerance());
    out += fmt::format(R"(<td class="{}">{}</td></tr>)", f.passed ? "pass" : "fail", f.passed ? "pass" : "FAIL");
  }
  out += "</table>";
  out += fmt::format(R"(<p class="meta run-label">{}; {}</p>)", svg::escape(label.level), svg::escape(label.text()));
  if (rv.kind == ListLevel::detections) out += all_target_note(run);
  return out + "</div>";
}

}  // namespace rcsim::replay::report
