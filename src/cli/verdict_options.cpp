#include "cli/verdict_options.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "replay/campaign/criteria.hpp"
#include "replay/campaign/junit.hpp"

namespace rcsim::cli {

namespace {

constexpr std::size_t kMaxPrintedFailures = 50;

}  // namespace

void add_verdict_options(CLI::App& cmd, VerdictArgs& args) {
  cmd.add_option("--criteria", args.criteria_file,
                 "pass/fail criteria (rcsim-criteria or rcsim-campaign file, schemas/campaign.md); stored in the "
                 "report, replacing its criteria; exit status 3 if a criterion fails")
      ->check(CLI::ExistingFile);
  cmd.add_option("--junit", args.junit_path, "write the verdicts as JUnit XML to this file");
}

void conclude_with_verdicts(SQLite::Database& db, const VerdictArgs& args, std::optional<std::int64_t> only_run,
                            const std::string& suite, std::ostream& out) {
  using namespace replay::campaign;
  std::vector<Criterion> criteria;
  if (!args.criteria_file.empty()) {
    criteria = read_criteria_file(args.criteria_file);
    store_criteria(db, criteria);
  } else {
    criteria = stored_criteria(db);
  }
  if (criteria.empty() && args.junit_path.empty()) return;  // nothing to judge or to write
  const Verdicts verdicts = judge(db, criteria, only_run);
  if (!args.junit_path.empty()) write_junit(args.junit_path, verdicts, suite);
  if (criteria.empty()) return;

  const std::size_t per_run = static_cast<std::size_t>(std::count_if(
      criteria.begin(), criteria.end(), [](const Criterion& c) { return c.scope == Scope::recording; }));
  out << fmt::format("verdicts: {} of {} runs passed {} criteria per recording; {} of {} campaign criteria passed\n",
                     verdicts.runs.size() - static_cast<std::size_t>(verdicts.runs_failed), verdicts.runs.size(), per_run,
                     std::count_if(verdicts.campaign.begin(), verdicts.campaign.end(), [](const auto& r) { return r.passed; }),
                     verdicts.campaign.size());
  std::size_t printed = 0;
  for (const RunVerdict& r : verdicts.runs) {
    if (r.passed) continue;
    if (printed++ == kMaxPrintedFailures) {
      out << fmt::format("  ... {} more failed runs (rcsim report shows them all)\n",
                         static_cast<std::size_t>(verdicts.runs_failed) - kMaxPrintedFailures);
      break;
    }
    std::string failed;
    for (const CriterionResult& c : r.results) {
      if (!c.passed) failed += (failed.empty() ? "" : "; ") + describe_failure(criteria[c.criterion], c);
    }
    out << fmt::format("  FAIL run {}: {} (seed {}): {}\n", r.run_id, r.recording_name, r.seed, failed);
  }
  for (const CriterionResult& c : verdicts.campaign) {
    out << fmt::format("  {} campaign: {}\n", c.passed ? "pass" : "FAIL", describe_failure(criteria[c.criterion], c));
  }
  if (!verdicts.passed()) {
    throw VerdictsFailed(fmt::format("{} of {} runs and {} campaign criteria failed", verdicts.runs_failed,
                                     verdicts.runs.size(),
                                     std::count_if(verdicts.campaign.begin(), verdicts.campaign.end(),
                                                   [](const auto& r) { return !r.passed; })));
  }
}

}  // namespace rcsim::cli
