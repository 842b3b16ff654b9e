// A run's verdict block of the report (replay/report/verdict_section.hpp), from verdicts made by
// hand: the mark, the figures within their tolerances counted per figure (a figure bounded from
// both sides is one row), what judged it, the run's label, the note on all-target GOSPA for
// detections only, and the escaping.
#include "replay/report/verdict_section.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rcsim::verdict_section_test {

using replay::RunLabel;
using replay::report::RunData;
using replay::report::run_verdict_block;
using replay::report::verdict_mark;
using namespace replay::verdict;

// Four criteria on three figures: GOSPA on objects <= 0.5 (met: 0.25), the target count ratio
// within 0.8 .. 1.25 (1.5: above), the latency difference <= 0.2 (missing).
Verdicts hand_verdicts(CriteriaSource source) {
  Verdicts v;
  v.source = source;
  v.criteria = {{"gospa_object_mean_m", Scope::recording, Statistic::value, Bound::max, 0.5, false},
                {"target_count_ratio", Scope::recording, Statistic::value, Bound::min, 0.8, false},
                {"target_count_ratio", Scope::recording, Statistic::value, Bound::max, 1.25, false},
                {"latency_difference_mean_s", Scope::recording, Statistic::value, Bound::max, 0.2, false}};
  RunVerdict run;
  run.run_id = 7;
  run.kind = ListLevel::detections;
  run.passed = false;
  run.results = {{0, 0.25, true}, {1, 1.5, true}, {2, 1.5, false}, {3, std::nullopt, false}};
  v.runs = {run};
  v.runs_failed = 1;
  return v;
}

RunLabel hand_label() {
  RunLabel label;
  label.sensors = "srr24 x2";
  label.level = "detections";
  label.fidelity = "full";
  label.effects = "all effects";
  label.seed = 3;
  return label;
}

RunData run_with_gospa(double gospa_mean_m) {
  RunData run;
  run.summary.emplace();
  run.summary->gospa_mean_m = gospa_mean_m;
  return run;
}

TEST(VerdictSection, OneRowPerFigureWithItsValueAndTolerance) {
  const Verdicts v = hand_verdicts(CriteriaSource::defaults);
  const std::string html = run_verdict_block(run_with_gospa(1.2345), v, v.runs[0], hand_label());
  EXPECT_EQ(html.rfind(R"(<div class="verdict fail" data-key="run-verdict">)", 0), 0u) << html;
  // Three figures, one within its tolerance.
  EXPECT_NE(html.find(R"(<p class="verdict-line"><span class="mark fail">FAIL</span> 1 of 3 figures within the )"
                      R"(default tolerances for detections (docs/verdicts.md).</p>)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find(R"(<tr class="pass"><td class="text">gospa_object_mean_m</td><td class="text">GOSPA on the )"
                      R"(targets of annotated objects only</td><td class="num">0.25</td><td class="num">&lt;= 0.5</td>)"
                      R"(<td class="pass">pass</td></tr>)"),
            std::string::npos)
      << html;
  // The two bounds of the ratio make one row, failed by the upper one.
  EXPECT_NE(html.find(R"(<td class="text">target_count_ratio</td>)"), std::string::npos);
  EXPECT_NE(html.find(R"(<td class="num">1.5</td><td class="num">0.8 .. 1.25</td><td class="fail">FAIL</td>)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find(R"(<td class="num">missing</td><td class="num">&lt;= 0.2</td><td class="fail">FAIL</td>)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find(R"(<p class="meta run-label">detections; srr24 x2, fidelity full, all effects, no calibration, )"
                      R"(seed 3</p>)"),
            std::string::npos)
      << html;
  // A run of detections: all-target GOSPA (3 decimals) is named as not judged.
  EXPECT_NE(html.find("All-target GOSPA (1.234 m) is not judged on detections"), std::string::npos) << html;
}

TEST(VerdictSection, WhatJudgedTheRunAndTheNoteOnlyForDetectionsWithASummary) {
  Verdicts v = hand_verdicts(CriteriaSource::file);
  EXPECT_NE(run_verdict_block(run_with_gospa(1.0), v, v.runs[0], hand_label()).find("within the criteria of --criteria."),
            std::string::npos);
  v.source = CriteriaSource::report;
  v.runs[0].kind = ListLevel::tracks;
  const std::string tracks = run_verdict_block(run_with_gospa(1.0), v, v.runs[0], hand_label());
  EXPECT_NE(tracks.find("within the criteria stored in this report."), std::string::npos) << tracks;
  EXPECT_EQ(tracks.find("All-target GOSPA"), std::string::npos) << "tracks: all-target GOSPA is judged";
  v.runs[0].kind = ListLevel::detections;
  EXPECT_EQ(run_verdict_block(RunData{}, v, v.runs[0], hand_label()).find("All-target GOSPA"), std::string::npos)
      << "no summary, no value to name";
}

TEST(VerdictSection, APassingRunAndTheEscapedLabel) {
  Verdicts v = hand_verdicts(CriteriaSource::report);
  v.runs[0].results = {{0, 0.25, true}};
  v.runs[0].passed = true;
  RunLabel label = hand_label();
  label.level = "<tracks>";
  label.calibration = "cal <1>";
  label.calibration_checksum = "0123456789abcdef";
  const std::string html = run_verdict_block(run_with_gospa(1.0), v, v.runs[0], label);
  EXPECT_EQ(html.rfind(R"(<div class="verdict pass")", 0), 0u) << html;
  EXPECT_NE(html.find(R"(<span class="mark pass">PASS</span> 1 of 1 figures within)"), std::string::npos) << html;
  EXPECT_NE(html.find("&lt;tracks&gt;; srr24 x2, fidelity full, all effects, calibration cal &lt;1&gt; #01234567, seed 3"),
            std::string::npos)
      << html;
  EXPECT_EQ(html.find("<1>"), std::string::npos);
  EXPECT_EQ(verdict_mark(true), R"(<span class="mark pass">PASS</span>)");
  EXPECT_EQ(verdict_mark(false), R"(<span class="mark fail">FAIL</span>)");
}

}  // namespace rcsim::verdict_section_test
