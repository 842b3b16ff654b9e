#pragma once
// --criteria FILE and --junit FILE (rcsim replay, rcsim merge): the runs judged by the criteria
// (replay/verdict/criteria.hpp), the failures printed (or given as JSON), JUnit written, and
// the exit status 3 when anything failed (README, "Exit status").
#include <CLI/CLI.hpp>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "replay/verdict/criteria.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::cli {

// Thrown when a criterion failed: rcsim exits with status 3.
class VerdictsFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
inline constexpr int kExitVerdictsFailed = 3;

// --criteria defaults: the default tolerances (docs/verdicts.md), as a gate.
inline constexpr std::string_view kDefaultCriteriaArg = "defaults";

struct VerdictArgs {
  std::string criteria_file;  // a file, or kDefaultCriteriaArg
  std::string junit_path;
  std::optional<std::vector<replay::verdict::Criterion>> file_criteria;  // read by read_verdict_criteria
};

void add_verdict_options(CLI::App& cmd, VerdictArgs& args);

// Reads --criteria FILE before the command does its work: a bad file is refused (exit status
// 2, file and field named) before anything is replayed, merged or written.
void read_verdict_criteria(VerdictArgs& args);

// Judges the runs of `db` (all, or `only_run`) by the criteria of --criteria FILE, else by the
// database's own, else (with `default_tolerances`) by the default tolerances of each run's kind,
// and writes --junit. FILE's criteria are stored in a report that belongs to no campaign
// (replacing its criteria, so that rcsim report shows them); a campaign's report keeps its
// manifest's, and FILE judges this once. The default tolerances set the exit status only when
// asked for (--criteria defaults). Nothing to judge and no JUnit: nullopt.
std::optional<replay::verdict::Verdicts> judge_runs(replay::ReportDatabase& db, const VerdictArgs& args,
                                                     std::optional<std::int64_t> only_run, const std::string& suite,
                                                     bool default_tolerances = false);

// One run's verdict, the first thing rcsim replay prints: "verdict: PASS, 5 of 5 ..." and a line
// per figure with its value, its tolerance and pass or FAIL.
void print_run_verdict(std::ostream& out, const replay::verdict::Verdicts& verdicts,
                       const replay::verdict::RunVerdict& run);

// The verdicts as text (failed runs, at most 50, and every campaign criterion) and as JSON.
void print_verdicts(std::ostream& out, const replay::verdict::Verdicts& verdicts);
nlohmann::ordered_json verdicts_json(const std::optional<replay::verdict::Verdicts>& verdicts);

// Throws VerdictsFailed if a run or a campaign criterion failed, where the verdicts are a gate.
void throw_if_failed(const std::optional<replay::verdict::Verdicts>& verdicts);

}  // namespace rcsim::cli
