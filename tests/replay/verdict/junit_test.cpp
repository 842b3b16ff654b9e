// Verdicts as JUnit XML (replay/verdict/junit.hpp), from verdicts made by hand: the counts and the
// time summed over the runs, one property per criterion, a passing run as an empty testcase, a
// failing one with every failed criterion in its failure, one testcase per campaign criterion,
// every text escaped; and the file written validates against the schema CI tools read.
#include "replay/verdict/junit.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <iostream>
#include <string>

#include "replay/replay_fixtures.hpp"
#include "scratch_dir.hpp"

namespace rcsim::junit_test {

using namespace replay::verdict;

// Two per-recording criteria and two over the campaign; run 1 passes, run 2 fails both of its
// criteria (one on a missing figure); the campaign passes its mean and fails its p95.
Verdicts hand_verdicts() {
  Verdicts v;
  v.criteria = {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 1.5, false},
                {"latency_difference_mean_s", Scope::recording, Statistic::value, Bound::max, 0.2, false},
                {"gospa_mean_m", Scope::campaign, Statistic::mean, Bound::max, 1.2, false},
                {"matched_fraction", Scope::campaign, Statistic::p95, Bound::min, 0.5, false}};
  RunVerdict passed;
  passed.run_id = 1;
  passed.recording_name = "a<b>";
  passed.recording_dir = "/rec/a&b";
  passed.seed = 1;
  passed.wall_s = 1.25;
  passed.results = {{0, 1.0, true}, {1, 0.1, true}};
  RunVerdict failed;
  failed.run_id = 2;
  failed.recording_name = "c";
  failed.recording_dir = "/rec/c";
  failed.seed = 2;
  failed.wall_s = 0.5;
  failed.passed = false;
  failed.results = {{0, 1.73, false}, {1, std::nullopt, false}};
  v.runs = {passed, failed};
  v.runs_failed = 1;
  v.campaign = {{2, 1.1, true}, {3, 0.4, false}};
  return v;
}

TEST(Junit, CountsTimesAndOneTestcasePerRunAndCampaignCriterion) {
  const std::string xml = junit_xml(hand_verdicts(), "q3");
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", 0), 0u);
  // 2 runs + 2 campaign criteria; 1 run and 1 campaign criterion failed; 1.25 + 0.5 s.
  EXPECT_NE(xml.find(R"(<testsuites name="q3" tests="4" failures="2" errors="0" time="1.750">)"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find(R"(<testsuite name="q3" tests="4" failures="2" errors="0" skipped="0" time="1.750" timestamp=")"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find(R"(<property name="criterion.0" value="gospa_mean_m &lt;= 1.5"/>)"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(<property name="criterion.3" value="p95 matched_fraction over the campaign &gt;= 0.5"/>)"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find(R"x(<testcase classname="q3" name="a&lt;b&gt; (seed 1, run 1)" time="1.250"/>)x"), std::string::npos)
      << xml;
  // The failure's message is the first failed criterion; its text lists them all and the recording.
  EXPECT_NE(xml.find("<testcase classname=\"q3\" name=\"c (seed 2, run 2)\" time=\"0.500\">\n"
                     "      <failure message=\"gospa_mean_m = 1.73 &gt; 1.5\" type=\"criterion\">gospa_mean_m = 1.73 "
                     "&gt; 1.5\nlatency_difference_mean_s missing (criterion latency_difference_mean_s &lt;= 0.2)\n"
                     "recording: /rec/c</failure>\n    </testcase>\n"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"q3.campaign\" name=\"mean gospa_mean_m over the campaign &lt;= 1.2\" "
                     "time=\"0\"/>\n"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"q3.campaign\" name=\"p95 matched_fraction over the campaign &gt;= 0.5\" "
                     "time=\"0\">\n      <failure message=\"p95 matched_fraction = 0.4 &lt; 0.5\" type=\"criterion\">"
                     "p95 matched_fraction = 0.4 &lt; 0.5</failure>\n    </testcase>\n"),
            std::string::npos)
      << xml;
  EXPECT_EQ(testing::count_occurrences(xml, "<testcase "), 4u);
  EXPECT_EQ(testing::count_occurrences(xml, "<failure "), 2u);
  EXPECT_NE(xml.find("  </testsuite>\n</testsuites>\n"), std::string::npos);
}

TEST(Junit, NoRunsAndNoCriteriaIsAnEmptyPassingSuite) {
  const std::string xml = junit_xml(Verdicts{}, "empty");
  EXPECT_NE(xml.find(R"(<testsuites name="empty" tests="0" failures="0" errors="0" time="0.000">)"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("    <properties>\n    </properties>\n  </testsuite>"), std::string::npos) << xml;
  EXPECT_EQ(xml.find("<testcase"), std::string::npos);
}

class JunitFile : public testing::ScratchDirTest {
 protected:
  JunitFile() : ScratchDirTest("junit") {}
};

// Moved from criteria_test.cpp, with verdicts made by hand instead of judged from replays.
TEST_F(JunitFile, JunitValidatesAgainstTheSchemaCiToolsRead) {
  Verdicts v = hand_verdicts();
  v.runs[1].recording_name = "c\x01\"quoted\"";  // a control character XML cannot hold: U+FFFD
  const std::string xml = junit_xml(v, "campaign <&> \"quoted\"");
  EXPECT_NE(xml.find(R"(<testsuite name="campaign &lt;&amp;&gt; &quot;quoted&quot;" tests="4" failures="2")"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("name=\"c\uFFFD&quot;quoted&quot; (seed 2, run 2)\""), std::string::npos) << xml;
  const auto path = dir_ / "junit.xml";
  write_junit(path.string(), v, "campaign");
  EXPECT_NE(testing::read_file(path).find("<testsuites name=\"campaign\" tests=\"4\" failures=\"2\""), std::string::npos);
  // Written atomically: the file alone, no temporary left beside it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()), 1);
  if (std::system("command -v xmllint > /dev/null 2>&1") != 0) {
    std::cout << "xmllint (libxml2-utils) is not installed: the JUnit schema check is skipped\n";
    GTEST_SKIP();
  }
  const std::string command = "xmllint --noout --schema " + std::string(RCSIM_SOURCE_DIR) +
                              "/tests/end_to_end/junit.xsd " + path.string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

}  // namespace rcsim::junit_test
