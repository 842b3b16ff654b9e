#include "common/quantile.hpp"
#include "replay/verdict/criteria.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace rcsim::replay::verdict {

namespace {

constexpr std::string_view kStatisticNames[] = {"value", "mean", "median", "p95", "min", "max"};

std::string_view statistic_name(Statistic s) { return kStatisticNames[static_cast<int>(s)]; }

std::optional<Statistic> statistic_from_name(std::string_view name) {
  for (int i = 0; i < 6; ++i) {
    if (kStatisticNames[i] == name) return static_cast<Statistic>(i);
  }
  return std::nullopt;
}

// The statistic of the values present (nullopt if none): mean, median, the 95th percentile
// (linear interpolation between order statistics, Hyndman & Fan type 7), min or max.
std::optional<double> statistic_of(Statistic statistic, std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double q) { return quantile_of_sorted(values, q); };
  switch (statistic) {
    case Statistic::value:
    case Statistic::mean: {
      double sum = 0.0;
      for (const double v : values) sum += v;
      return sum / static_cast<double>(values.size());
    }
    case Statistic::median: return quantile(0.5);
    case Statistic::p95: return quantile(0.95);
    case Statistic::min: return values.front();
    case Statistic::max: return values.back();
  }
  return std::nullopt;
}

CriterionResult result_of(std::size_t index, const Criterion& c, std::optional<double> value) {
  CriterionResult r;
  r.criterion = index;
  r.value = value;
  if (!value) {
    r.passed = c.pass_if_missing;
  } else {
    r.passed = c.bound == Bound::max ? *value <= c.threshold : *value >= c.threshold;
  }
  return r;
}

}  // namespace

std::string Criterion::text() const {
  const std::string bound_text = fmt::format("{} {:g}", bound == Bound::max ? "<=" : ">=", threshold);
  if (scope == Scope::recording) return fmt::format("{} {}", figure, bound_text);
  return fmt::format("{} {} over the campaign {}", statistic_name(statistic), figure, bound_text);
}

std::vector<Criterion> parse_criteria(const JsonField& document) {
  std::vector<Criterion> out;
  for (const JsonField& entry : document.array("criteria")) {
    entry.expect_only({"figure", "scope", "statistic", "min", "max", "if_missing"});
    Criterion c;
    c.figure = entry.string("figure");
    if (!find_figure(c.figure)) {
      entry.fail("figure", fmt::format("unknown figure '{}' (known: {})", c.figure, figure_names()));
    }
    const std::string scope = entry.has("scope") ? entry.string("scope") : "recording";
    if (scope == "recording") {
      c.scope = Scope::recording;
    } else if (scope == "campaign") {
      c.scope = Scope::campaign;
    } else {
      entry.fail("scope", "'" + scope + "' is neither recording nor campaign");
    }
    if (entry.has("statistic")) {
      const std::string name = entry.string("statistic");
      const auto statistic = statistic_from_name(name);
      if (!statistic || *statistic == Statistic::value) {
        entry.fail("statistic", "'" + name + "' is not one of mean, median, p95, min, max");
      }
      if (c.scope != Scope::campaign) entry.fail("statistic", "a statistic needs \"scope\": \"campaign\"");
      c.statistic = *statistic;
    } else {
      c.statistic = c.scope == Scope::campaign ? Statistic::mean : Statistic::value;
    }
    const std::string missing = entry.has("if_missing") ? entry.string("if_missing") : "fail";
    if (missing != "fail" && missing != "pass") entry.fail("if_missing", "'" + missing + "' is neither fail nor pass");
    c.pass_if_missing = missing == "pass";
    if (!entry.has("min") && !entry.has("max")) entry.fail("a criterion needs \"max\", \"min\" or both");
    for (const auto& [key, bound] : {std::pair{"min", Bound::min}, std::pair{"max", Bound::max}}) {
      if (!entry.has(key)) continue;
      c.bound = bound;
      c.threshold = entry.number(key);
      // A floor above a ceiling of the same figure and statistic, in this entry or an earlier one,
      // can never pass: a typo, refused rather than failing every run.
      for (const Criterion& other : out) {
        if (other.figure != c.figure || other.scope != c.scope || other.statistic != c.statistic || other.bound == c.bound) {
          continue;
        }
        const double floor = c.bound == Bound::min ? c.threshold : other.threshold;
        const double ceiling = c.bound == Bound::max ? c.threshold : other.threshold;
        if (floor > ceiling) {
          entry.fail(key, fmt::format("\"{}\": min {:g} above max {:g}: no value can pass both", c.text(), floor, ceiling));
        }
      }
      out.push_back(c);
    }
  }
  return out;
}

std::vector<Criterion> read_criteria_file(const std::filesystem::path& path) {
  const nlohmann::json doc = parse_json_file(path.string());
  const JsonField root(doc, path.string(), "");
  const std::string format = root.has("format") ? root.string("format") : "";
  if (format == "rcsim-campaign") return root.has("criteria") ? parse_criteria(root) : std::vector<Criterion>{};
  root.expect_format("rcsim-criteria", 1);
  root.expect_only({"format", "version", "criteria"});
  return parse_criteria(root);
}

std::vector<CriterionRow> criterion_rows(const std::vector<Criterion>& criteria) {
  std::vector<CriterionRow> rows;
  rows.reserve(criteria.size());
  for (const Criterion& c : criteria) {
    rows.push_back({c.figure, c.scope == Scope::campaign ? "campaign" : "recording",
                    std::string(statistic_name(c.statistic)), c.bound == Bound::min ? "min" : "max", c.threshold,
                    c.pass_if_missing ? "pass" : "fail"});
  }
  return rows;
}

std::vector<Criterion> criteria_from_rows(const std::vector<CriterionRow>& rows) {
  std::vector<Criterion> out;
  for (const CriterionRow& row : rows) {
    Criterion c;
    c.figure = row.figure;
    c.scope = row.scope == "campaign" ? Scope::campaign : Scope::recording;
    c.statistic = statistic_from_name(row.statistic).value_or(Statistic::value);
    c.bound = row.bound == "min" ? Bound::min : Bound::max;
    c.threshold = row.threshold;
    c.pass_if_missing = row.if_missing == "pass";
    out.push_back(c);
  }
  return out;
}

std::vector<Criterion> stored_criteria(ReportDatabase& db) { return criteria_from_rows(read_criterion_rows(db)); }

void store_criteria(ReportDatabase& db, const std::vector<Criterion>& criteria) {
  replace_criterion_rows(db, criterion_rows(criteria));
}

bool Verdicts::passed() const {
  return runs_failed == 0 && std::all_of(campaign.begin(), campaign.end(), [](const auto& r) { return r.passed; });
}

Verdicts judge(ReportDatabase& db, const std::vector<Criterion>& criteria, std::optional<std::int64_t> only_run) {
  Verdicts out;
  out.criteria = criteria;
  std::vector<std::string> figures;
  for (const Criterion& c : criteria) figures.push_back(c.figure);
  figures.push_back("replay_wall_s");
  const std::size_t wall = figures.size() - 1;
  std::vector<RunFigureRow> rows = read_run_figures(db, figures);
  if (only_run) std::erase_if(rows, [&](const RunFigureRow& r) { return r.run_id != *only_run; });

  for (const RunFigureRow& row : rows) {
    RunVerdict v;
    v.run_id = row.run_id;
    v.recording_name = row.recording_name;
    v.recording_dir = row.recording_dir;
    v.kind = row.kind;
    v.seed = row.seed;
    v.duration_s = row.duration_s;
    v.wall_s = row.values[wall].value_or(0.0);
    for (std::size_t i = 0; i < criteria.size(); ++i) {
      if (criteria[i].scope != Scope::recording) continue;
      if (criteria[i].kind && *criteria[i].kind != row.kind) continue;
      v.results.push_back(result_of(i, criteria[i], row.values[i]));
      v.passed = v.passed && v.results.back().passed;
    }
    out.runs_failed += v.passed ? 0 : 1;
    out.runs.push_back(std::move(v));
  }
  for (std::size_t i = 0; i < criteria.size() && !only_run; ++i) {
    if (criteria[i].scope != Scope::campaign) continue;
    std::vector<double> values;
    for (const RunFigureRow& row : rows) {
      if (row.values[i]) values.push_back(*row.values[i]);
    }
    out.campaign.push_back(result_of(i, criteria[i], statistic_of(criteria[i].statistic, std::move(values))));
  }
  return out;
}

std::string FigureVerdict::tolerance() const {
  if (min && max) return fmt::format("{:g} .. {:g}", *min, *max);
  if (max) return fmt::format("<= {:g}", *max);
  return fmt::format(">= {:g}", min.value_or(0.0));
}

std::vector<FigureVerdict> figure_verdicts(const Verdicts& verdicts, const RunVerdict& run) {
  std::vector<FigureVerdict> out;
  for (const CriterionResult& r : run.results) {
    const Criterion& c = verdicts.criteria[r.criterion];
    auto row = std::find_if(out.begin(), out.end(), [&](const FigureVerdict& f) { return f.figure == c.figure; });
    if (row == out.end()) {
      out.push_back({c.figure, r.value, std::nullopt, std::nullopt, true});
      row = out.end() - 1;
    }
    (c.bound == Bound::min ? row->min : row->max) = c.threshold;
    row->passed = row->passed && r.passed;
  }
  return out;
}

std::string describe_failure(const Criterion& c, const CriterionResult& r) {
  const std::string name =
      c.scope == Scope::recording ? c.figure : fmt::format("{} {}", statistic_name(c.statistic), c.figure);
  if (!r.value) return fmt::format("{} missing (criterion {})", name, c.text());
  return fmt::format("{} = {:.6g} {} {:g}", name, *r.value,
                     r.passed ? (c.bound == Bound::max ? "<=" : ">=") : (c.bound == Bound::max ? ">" : "<"), c.threshold);
}

}  // namespace rcsim::replay::verdict
