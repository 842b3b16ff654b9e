#include "cli/verdict_options.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "common/atomic_file.hpp"
#include "common/closest_name.hpp"
#include "replay/verdict/default_criteria.hpp"
#include "replay/verdict/junit.hpp"
#include "replay/store/campaign_store.hpp"

namespace rcsim::cli {

namespace {

using namespace replay::verdict;

constexpr std::size_t kMaxPrintedFailures = 50;

std::string plural(std::size_t n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

std::size_t campaign_failures(const Verdicts& v) {
  return static_cast<std::size_t>(std::count_if(v.campaign.begin(), v.campaign.end(), [](const auto& r) { return !r.passed; }));
}

std::string failed_criteria(const Verdicts& v, const RunVerdict& r) {
  std::string failed;
  for (const CriterionResult& c : r.results) {
    if (!c.passed) failed += (failed.empty() ? "" : "; ") + describe_failure(v.criteria[c.criterion], c);
  }
  return failed;
}

nlohmann::ordered_json result_json(const Verdicts& v, const CriterionResult& c) {
  return {{"criterion", c.criterion},
          {"figure", v.criteria[c.criterion].figure},
          {"value", c.value ? nlohmann::ordered_json(*c.value) : nlohmann::ordered_json()},
          {"passed", c.passed},
          {"text", describe_failure(v.criteria[c.criterion], c)}};
}

}  // namespace

void add_verdict_options(CLI::App& cmd, VerdictArgs& args) {
  cmd.add_option("--criteria", args.criteria_file,
                 "pass/fail criteria instead of the default tolerances (docs/verdicts.md): an rcsim-criteria or "
                 "rcsim-campaign file (schemas/campaign.md), read before any work and stored in a report of no "
                 "campaign, or 'defaults' for the default tolerances; exit status 3 if a criterion fails")
      ->check(CLI::Validator(
          [](const std::string& value) {
            if (value == kDefaultCriteriaArg || CLI::ExistingFile(value).empty()) return std::string();
            // Neither a file nor a name it knows (issue 53: "--criteria default" said only "File
            // does not exist"): the names it takes, the nearest first.
            const std::vector<std::string> names{std::string(kDefaultCriteriaArg)};
            const auto meant = closest_name(value, names);
            return fmt::format("'{}' is neither a file nor a criteria name{}; it takes a criteria file (rcsim-criteria or "
                               "rcsim-campaign) or a name: {} (the default tolerances)",
                               value, meant ? fmt::format(" (did you mean '{}'?)", *meant) : "", join_names(names));
          },
          "FILE|defaults"));
  cmd.add_option("--junit", args.junit_path, "write the verdicts as JUnit XML to this file");
}

void read_verdict_criteria(VerdictArgs& args) {
  if (!args.criteria_file.empty() && args.criteria_file != kDefaultCriteriaArg) {
    args.file_criteria = read_criteria_file(args.criteria_file);
  }
  // Before any work: a --junit path that is a directory, device or link fails now, not after the
  // replay or merge has written its output.
  if (!args.junit_path.empty()) check_output_file(args.junit_path);
}

std::optional<Verdicts> judge_runs(replay::ReportDatabase& db, const VerdictArgs& args, std::optional<std::int64_t> only_run,
                                   const std::string& suite, bool default_tolerances) {
  std::vector<Criterion> criteria;
  CriteriaSource source = CriteriaSource::report;
  const bool asked_for_defaults = args.criteria_file == kDefaultCriteriaArg;
  if (args.file_criteria) {
    criteria = *args.file_criteria;
    source = CriteriaSource::file;
    if (!replay::read_campaign_name(db)) store_criteria(db, criteria);
  } else if (!asked_for_defaults) {
    criteria = stored_criteria(db);
  }
  if (criteria.empty() && (default_tolerances || asked_for_defaults)) {
    criteria = default_criteria();
    source = CriteriaSource::defaults;
  }
  if (criteria.empty() && args.junit_path.empty()) return std::nullopt;  // nothing to judge or to write
  Verdicts verdicts = judge(db, criteria, only_run);
  verdicts.source = source;
  verdicts.gate = source != CriteriaSource::defaults || asked_for_defaults;
  if (!args.junit_path.empty()) write_junit(args.junit_path, verdicts, suite);
  if (criteria.empty()) return std::nullopt;
  return verdicts;
}

void print_run_verdict(std::ostream& out, const Verdicts& v, const RunVerdict& run) {
  const std::vector<FigureVerdict> figures = figure_verdicts(v, run);
  const auto met = std::count_if(figures.begin(), figures.end(), [](const FigureVerdict& f) { return f.passed; });
  const std::string what = v.source == CriteriaSource::defaults
                               ? fmt::format("the default tolerances for {} (docs/verdicts.md){}", list_level_name(run.kind),
                                             v.gate ? "" : "; --criteria defaults makes them a gate")
                               : (v.source == CriteriaSource::file ? "the criteria of --criteria" : "the report's criteria");
  out << fmt::format("verdict: {}, {} of {} figures within {}\n", run.passed ? "PASS" : "FAIL", met, figures.size(), what);
  for (const FigureVerdict& f : figures) {
    out << fmt::format("  {:<4}  {:<38} {:>10}  {}\n", f.passed ? "pass" : "FAIL", f.figure,
                       f.value ? fmt::format("{:.4g}", *f.value) : std::string("missing"), f.tolerance());
  }
}

void print_verdicts(std::ostream& out, const Verdicts& v) {
  const std::size_t per_run = static_cast<std::size_t>(std::count_if(
      v.criteria.begin(), v.criteria.end(), [](const Criterion& c) { return c.scope == Scope::recording; }));
  out << fmt::format("verdicts: {} of {} passed {} per recording; {} of {} passed\n",
                     v.runs.size() - static_cast<std::size_t>(v.runs_failed), plural(v.runs.size(), "run", "runs"),
                     plural(per_run, "criterion", "criteria"), v.campaign.size() - campaign_failures(v),
                     plural(v.campaign.size(), "campaign criterion", "campaign criteria"));
  std::size_t printed = 0;
  for (const RunVerdict& r : v.runs) {
    if (r.passed) continue;
    if (printed++ == kMaxPrintedFailures) {
      out << fmt::format("  ... {} more failed runs (rcsim report shows them all)\n",
                         static_cast<std::size_t>(v.runs_failed) - kMaxPrintedFailures);
      break;
    }
    out << fmt::format("  FAIL run {}: {} (seed {}): {}\n", r.run_id, r.recording_name, r.seed, failed_criteria(v, r));
  }
  for (const CriterionResult& c : v.campaign) {
    out << fmt::format("  {} campaign: {}\n", c.passed ? "pass" : "FAIL", describe_failure(v.criteria[c.criterion], c));
  }
}

nlohmann::ordered_json verdicts_json(const std::optional<Verdicts>& verdicts) {
  if (!verdicts) return nullptr;
  const Verdicts& v = *verdicts;
  nlohmann::ordered_json criteria = nlohmann::ordered_json::array(), failed = nlohmann::ordered_json::array(),
                         campaign = nlohmann::ordered_json::array();
  for (const Criterion& c : v.criteria) {
    criteria.push_back({{"figure", c.figure}, {"scope", c.scope == Scope::recording ? "recording" : "campaign"}, {"text", c.text()}});
  }
  for (const RunVerdict& r : v.runs) {
    if (r.passed) continue;
    nlohmann::ordered_json results = nlohmann::ordered_json::array();
    for (const CriterionResult& c : r.results) {
      if (!c.passed) results.push_back(result_json(v, c));
    }
    failed.push_back({{"run_id", r.run_id}, {"recording", r.recording_name}, {"seed", r.seed}, {"failed", results}});
  }
  for (const CriterionResult& c : v.campaign) campaign.push_back(result_json(v, c));
  constexpr const char* kSources[] = {"defaults", "file", "report"};
  return {{"passed", v.passed()},
          {"criteria_source", kSources[static_cast<int>(v.source)]},
          {"gate", v.gate},
          {"runs", v.runs.size()},
          {"runs_failed", v.runs_failed},
          {"criteria", criteria},
          {"failed_runs", failed},
          {"campaign", campaign}};
}

void throw_if_failed(const std::optional<Verdicts>& verdicts) {
  if (!verdicts || !verdicts->gate || verdicts->passed()) return;
  throw VerdictsFailed(fmt::format("{} of {} and {} failed", verdicts->runs_failed, plural(verdicts->runs.size(), "run", "runs"),
                                   plural(campaign_failures(*verdicts), "campaign criterion", "campaign criteria")));
}

}  // namespace rcsim::cli
