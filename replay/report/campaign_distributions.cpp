// The figures' distributions over a campaign: a quantile table and per figure a histogram of the
// runs' values with the criteria's thresholds drawn as lines (campaign_section.hpp).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "replay/report/campaign_section.hpp"
#include "replay/report/html_cells.hpp"
#include "replay/report/svg_plot.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

namespace {

using verdict::Bound;
using verdict::Criterion;
using verdict::Scope;
using svg::escape;

constexpr const char* kStatisticNames[] = {"value", "mean", "median", "p95", "min", "max"};

std::vector<const Criterion*> criteria_on(const CampaignData& data, const std::string& figure) {
  std::vector<const Criterion*> out;
  for (const Criterion& c : data.verdicts.criteria) {
    if (c.figure == figure) out.push_back(&c);
  }
  return out;
}

// "<= 1.5", or "p95 <= 1.2" for a campaign criterion.
std::string threshold_text(const Criterion& c) {
  const std::string bound = fmt::format("{} {}", c.bound == Bound::max ? "\u2264" : "\u2265", figure_value(c.threshold));
  if (c.scope == Scope::recording) return bound;
  return fmt::format("{} {}", kStatisticNames[static_cast<int>(c.statistic)], bound);
}

std::string x_label(const verdict::FigureInfo& info) {
  return info.unit.empty() || info.unit == "1" ? info.name : info.name + " / " + info.unit;
}

// The histogram of one figure's values (ascending). The axis covers the values, or, when a few lie
// far out, the 1st to 99th percentiles widened by half their span (the rest counted in the end
// bins), and every threshold.
svg::HistogramSpec figure_histogram(const verdict::FigureInfo& info, const std::vector<double>& sorted,
                                    std::size_t missing, const std::vector<const Criterion*>& criteria, int max_bins) {
  svg::HistogramSpec spec;
  spec.title = info.name;
  spec.x_label = x_label(info);
  spec.y_label = "runs";
  spec.zero_line = false;
  spec.width_px = 410;
  spec.height_px = 210;
  spec.note = fmt::format("{} runs", sorted.size());
  if (missing > 0) spec.note += fmt::format(", {} without the figure", missing);
  for (const Criterion* c : criteria) {
    spec.markers.push_back({c->threshold, threshold_text(*c), c->scope == Scope::campaign ? "#e8590c" : "#c92a2a",
                            c->scope == Scope::campaign});
  }
  if (sorted.empty()) {
    spec.counts.assign(1, 0);
    return spec;
  }
  double lo = sorted.front(), hi = sorted.back();
  const double p1 = quantile_of_sorted(sorted, 0.01), p99 = quantile_of_sorted(sorted, 0.99);
  const double span = p99 - p1;
  if (span > 0.0 && (lo < p1 - span || hi > p99 + span)) {
    lo = std::max(lo, p1 - 0.5 * span);
    hi = std::min(hi, p99 + 0.5 * span);
  }
  // The axis reaches a threshold within the values' span, or half their magnitude, of them; one
  // farther out is named in the note instead of squeezing every run into one bin.
  const double reach = std::max({hi - lo, 0.5 * std::max(std::abs(lo), std::abs(hi)), 1e-9});
  std::string beyond;
  for (const Criterion* c : criteria) {
    if (c->threshold < lo - reach || c->threshold > hi + reach) {
      beyond += fmt::format("{}{} {}", beyond.empty() ? "" : ", ", threshold_text(*c),
                            c->threshold < lo ? "left of the axis" : "right of the axis");
      continue;
    }
    lo = std::min(lo, c->threshold);
    hi = std::max(hi, c->threshold);
  }
  if (!beyond.empty()) spec.note += "; " + beyond;
  svg::widen(lo, hi, std::max(1e-9, 0.1 * std::abs(lo)), 0.0);
  const int bins = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(sorted.size())))), 5, max_bins);
  spec.lo = lo;
  spec.bin_width = (hi - lo) / bins;
  spec.counts.assign(static_cast<std::size_t>(bins), 0);
  for (const double v : sorted) {
    const double k = std::floor((v - lo) / spec.bin_width);
    if (v < lo) ++spec.below;
    if (v > hi) ++spec.above;
    ++spec.counts[static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(bins - 1)))];
  }
  return spec;
}

}  // namespace

std::string campaign_distributions(const CampaignData& data, int histogram_bins) {
  std::string out = R"(<h3 id="campaign-distributions">Distributions over the campaign</h3>)"
                    R"(<p class="hint">Over the runs that have each figure: quantiles interpolated between order )"
                    "statistics (as the criteria's median and p95), and a histogram with the criteria's thresholds "
                    "(per recording: solid red; over the campaign: dashed orange, its statistic named); none of a "
                    "figure alike in every run.</p>";
  std::string table = R"(<div class="scroll"><table class="quantiles">)" +
                      header_row({"figure", "unit", "runs", "without it", "min", "median", "p95", "max", "mean", "criteria"});
  std::string pictures = R"(<div class="figs">)";
  for (std::size_t f = 0; f < data.figures.size(); ++f) {
    const verdict::FigureInfo& info = data.figures[f];
    const std::vector<double> sorted = data.sorted_values(f);
    const std::vector<const Criterion*> criteria = criteria_on(data, info.name);
    double sum = 0.0;
    for (const double v : sorted) sum += v;
    std::string criteria_text;
    for (const Criterion* c : criteria) criteria_text += (criteria_text.empty() ? "" : ", ") + threshold_text(*c);
    const auto q = [&](double p) { return figure_value(quantile_of_sorted(sorted, p)); };
    table += fmt::format(
        R"(<tr data-figure="{0}"><th title="{1}">{0}</th><td>{2}</td><td class="num">{3}</td><td class="num">{4}</td>)"
        R"(<td class="num" data-key="min">{5}</td><td class="num" data-key="median">{6}</td><td class="num" data-key="p95">{7}</td>)"
        R"(<td class="num" data-key="max">{8}</td><td class="num" data-key="mean">{9}</td><td>{10}</td></tr>)",
        escape(info.name), escape(info.meaning), escape(info.unit), sorted.size(), data.runs.size() - sorted.size(),
        q(0.0), q(0.5), q(0.95), q(1.0),
        figure_value(sorted.empty() ? std::nan("") : sum / static_cast<double>(sorted.size())), escape(criteria_text));
    // A figure alike in every run has no distribution to draw, unless a criterion bounds it.
    const bool constant = sorted.size() > 1 && sorted.front() == sorted.back();
    if (!constant || !criteria.empty()) {
      pictures += svg::histogram_svg(
          figure_histogram(info, sorted, data.runs.size() - sorted.size(), criteria, std::max(5, histogram_bins)));
    }
  }
  return out + table + "</table></div>" + pictures + "</div>";
}

}  // namespace rcsim::replay::report
