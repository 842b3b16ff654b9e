#pragma once
// A run's verdict as the report shows it first under the run's title (docs/verdicts.md): PASS or
// FAIL, what it was judged by, and a row per figure with its meaning, value, tolerance and mark;
// then what tells the run from the others (profiles, fidelity, effects, calibration, seed).
#include <string>

#include "replay/verdict/criteria.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay::report {

// The verdict block of one run; `verdicts` judged it (verdict::judge_report), `run` is its entry.
std::string run_verdict_block(const RunData& run, const verdict::Verdicts& verdicts, const verdict::RunVerdict& run_verdict,
                              const RunLabel& label);

// "PASS" or "FAIL" with its colour, for titles and lists.
std::string verdict_mark(bool passed);

}  // namespace rcsim::replay::report
