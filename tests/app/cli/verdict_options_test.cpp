// --criteria and --junit (app/cli/verdict_options.cpp): verdicts printed as text and JSON, the
// exit status 3 only where the verdicts are a gate, and a bad criteria file or JUnit path refused
// before any work. On verdicts built here by hand.
#include "app/cli/verdict_options.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::verdict_options_test {

using namespace replay::verdict;

// One criterion per recording, gospa_mean_m <= 1.5 m; run 1 at 1.2 m passes, run 2 at 1.73 m fails.
Verdicts two_runs_one_failed() {
  Verdicts v;
  v.source = CriteriaSource::file;
  Criterion gospa;
  gospa.figure = "gospa_mean_m";
  gospa.bound = Bound::max;
  gospa.threshold = 1.5;
  v.criteria = {gospa};
  RunVerdict passed;
  passed.run_id = 1;
  passed.recording_name = "a";
  passed.seed = 0;
  passed.results = {{0, 1.2, true}};
  RunVerdict failed;
  failed.run_id = 2;
  failed.recording_name = "b";
  failed.seed = 7;
  failed.passed = false;
  failed.results = {{0, 1.73, false}};
  v.runs = {passed, failed};
  v.runs_failed = 1;
  return v;
}

TEST(VerdictOptions, TheTextNamesEachFailedRunWithItsFigureAgainstTheBound) {
  std::ostringstream out;
  cli::print_verdicts(out, two_runs_one_failed());
  EXPECT_EQ(out.str(),
            "verdicts: 1 of 2 runs passed 1 criterion per recording; 0 of 0 campaign criteria passed\n"
            "  FAIL run 2: b (seed 7): gospa_mean_m = 1.73 > 1.5\n");
}

TEST(VerdictOptions, ARunsVerdictOpensWithPassOrFailAndListsEachFigure) {
  const Verdicts v = two_runs_one_failed();
  std::ostringstream failed, passed;
  cli::print_run_verdict(failed, v, v.runs[1]);
  cli::print_run_verdict(passed, v, v.runs[0]);
  EXPECT_EQ(failed.str().substr(0, failed.str().find('\n')), "verdict: FAIL, 0 of 1 figures within the criteria of --criteria");
  EXPECT_NE(failed.str().find("FAIL  gospa_mean_m"), std::string::npos) << failed.str();
  EXPECT_NE(failed.str().find("1.73"), std::string::npos) << failed.str();
  EXPECT_EQ(passed.str().substr(0, passed.str().find('\n')), "verdict: PASS, 1 of 1 figures within the criteria of --criteria");
}

TEST(VerdictOptions, TheJsonCarriesTheFailedRunsAndIsNullWithoutVerdicts) {
  EXPECT_TRUE(cli::verdicts_json(std::nullopt).is_null());
  const auto json = cli::verdicts_json(two_runs_one_failed());
  EXPECT_EQ(json.at("passed"), false);
  EXPECT_EQ(json.at("criteria_source"), "file");
  EXPECT_EQ(json.at("runs"), 2);
  EXPECT_EQ(json.at("runs_failed"), 1);
  ASSERT_EQ(json.at("failed_runs").size(), 1u);
  EXPECT_EQ(json.at("failed_runs")[0].at("run_id"), 2);
  EXPECT_EQ(json.at("failed_runs")[0].at("failed")[0].at("value"), 1.73);
  EXPECT_EQ(json.at("failed_runs")[0].at("failed")[0].at("figure"), "gospa_mean_m");
}

TEST(VerdictOptions, OnlyAFailedGateThrows) {
  EXPECT_NO_THROW(cli::throw_if_failed(std::nullopt));
  Verdicts v = two_runs_one_failed();
  try {
    cli::throw_if_failed(v);
    FAIL() << "a failed gate did not throw";
  } catch (const cli::VerdictsFailed& e) {
    EXPECT_STREQ(e.what(), "1 of 2 runs and 0 campaign criteria failed");
  }
  v.gate = false;  // the default tolerances, not asked for as a gate: reported, never an exit status
  EXPECT_NO_THROW(cli::throw_if_failed(v));
  Verdicts all_passed = two_runs_one_failed();
  all_passed.runs.pop_back();
  all_passed.runs_failed = 0;
  EXPECT_NO_THROW(cli::throw_if_failed(all_passed));
}

class VerdictFiles : public rcsim::testing::ScratchDirTest {
 protected:
  VerdictFiles() : ScratchDirTest("verdict_options") {}
};

TEST_F(VerdictFiles, ABadCriteriaFileOrAJunitPathThatIsADirectoryIsRefusedBeforeAnyWork) {
  const auto criteria = dir_ / "criteria.json";
  std::ofstream(criteria) << "{\"format\": \"rcsim-criteria\", \"version\": 1, \"criteria\": [{\"figure\": \"no_such_figure\"}]}\n";
  cli::VerdictArgs bad_file;
  bad_file.criteria_file = criteria.string();
  try {
    cli::read_verdict_criteria(bad_file);
    FAIL() << "a criterion of an unknown figure was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(criteria.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no_such_figure"), std::string::npos) << e.what();
  }
  cli::VerdictArgs directory_junit;
  directory_junit.junit_path = dir_.string();
  EXPECT_THROW(cli::read_verdict_criteria(directory_junit), std::exception);
  cli::VerdictArgs defaults;
  defaults.criteria_file = std::string(cli::kDefaultCriteriaArg);
  cli::read_verdict_criteria(defaults);
  EXPECT_FALSE(defaults.file_criteria.has_value());  // "defaults" names no file
}

// Issue 53: a mistyped criteria name ("default" for "defaults") said "File does not exist". Now
// the names it takes, the nearest one asked about; status 2, before any work (no report made).
TEST_F(VerdictFiles, AMistypedCriteriaNameIsAnsweredWithTheNamesItTakes) {
  const std::string recording = (std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "front_approach").string();
  const auto db = dir_ / "r.sqlite";
  const auto typo = rcsim::testing::run_rcsim("replay " + recording + " --db " + db.string() + " --criteria default");
  EXPECT_EQ(typo.exit_code, 2) << typo.output;
  EXPECT_EQ(typo.output.find("File does not exist"), std::string::npos) << typo.output;
  EXPECT_NE(typo.output.find("--criteria: 'default' is neither a file nor a criteria name (did you mean 'defaults'?); it "
                             "takes a criteria file (rcsim-criteria or rcsim-campaign) or a name: defaults"),
            std::string::npos)
      << typo.output;
  const auto far = rcsim::testing::run_rcsim("replay " + recording + " --db " + db.string() + " --criteria tolerances");
  EXPECT_EQ(far.exit_code, 2) << far.output;
  EXPECT_NE(far.output.find("'tolerances' is neither a file nor a criteria name; it takes"), std::string::npos) << far.output;
  EXPECT_FALSE(std::filesystem::exists(db));
}

}  // namespace rcsim::verdict_options_test
