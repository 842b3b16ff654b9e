#pragma once
// --criteria FILE and --junit FILE (rcsim replay, rcsim merge): the runs judged by the criteria
// (replay/campaign/criteria.hpp), the failures printed, JUnit written, and the exit status 3 when
// anything failed (README, "Exit status").
#include <CLI/CLI.hpp>
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace rcsim::cli {

// Thrown when a criterion failed: rcsim exits with status 3.
class VerdictsFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
inline constexpr int kExitVerdictsFailed = 3;

struct VerdictArgs {
  std::string criteria_file;
  std::string junit_path;
};

void add_verdict_options(CLI::App& cmd, VerdictArgs& args);

// Judges the runs of `db` (all, or `only_run`) by the criteria: those of --criteria FILE, which
// then replace the database's, else the database's own. Prints the verdicts, writes --junit, and
// throws VerdictsFailed if a run or a campaign criterion failed. Without criteria nothing is
// judged (JUnit then lists every run as passed).
void conclude_with_verdicts(SQLite::Database& db, const VerdictArgs& args, std::optional<std::int64_t> only_run,
                            const std::string& suite, std::ostream& out);

}  // namespace rcsim::cli
