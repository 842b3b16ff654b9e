// rcsim bench as a user runs it: the table, --json (rcsim-bench v2), storage in the report
// database, determinism of the error columns, and refusals that leave the database alone; the
// bench programs beside rcsim (--help, wrong command lines).
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <vector>
#include <nlohmann/json.hpp>

#include "scratch_dir.hpp"
#include "app/cli/run_rcsim.hpp"
#include "replay/replay_fixtures.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::run_rcsim;

class BenchCli : public testing::ScratchDirTest {
 protected:
  BenchCli() : ScratchDirTest("bench_cli") {}
  static std::string recording(const std::string& name) {
    return (fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / name).string();
  }
};

TEST_F(BenchCli, JsonRowsAndTheSameSeedRepeatsTheErrors) {
  const std::string args = "bench " + recording("standstill_1m") + " " + recording("two_in_one_cell") +
                           " --no-reference --levels full,no_monopulse --min-cpu-s 0 --json --seed 4";
  const auto first = run_rcsim(args, false);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto j = nlohmann::json::parse(first.output);
  EXPECT_EQ(j["format"], "rcsim-bench");
  EXPECT_EQ(j["version"], 2);  // v2: goal 3 against the reference row
  EXPECT_TRUE(j["bench_id"].is_null());  // not stored
  EXPECT_TRUE(j["goals"].is_null());     // no reference, no noise floor
  ASSERT_EQ(j["rows"].size(), 4u);
  EXPECT_EQ(j["rows"][0]["recording"], "standstill_1m");
  EXPECT_EQ(j["rows"][3]["recording"], "two_in_one_cell");
  EXPECT_EQ(j["rows"][3]["level"], "no_monopulse");
  // Fig. 10: the full model finds the recorded merge artefacts; without monopulse there are none.
  EXPECT_GT(j["rows"][2]["merge_artefacts"]["found"].get<int>(), 50);
  EXPECT_EQ(j["rows"][3]["merge_artefacts"]["found"].get<int>(), 0);
  EXPECT_EQ(j["rows"][3]["merge_artefacts"]["missed"], j["rows"][3]["merge_artefacts"]["recorded"]);
  ASSERT_EQ(j["levels"].size(), 2u);
  EXPECT_EQ(j["levels"][0]["sensor_cycles"].get<long long>(),
            j["rows"][0]["sensor_cycles"].get<long long>() + j["rows"][2]["sensor_cycles"].get<long long>());

  const auto second = nlohmann::json::parse(run_rcsim(args, false).output);
  for (std::size_t i = 0; i < 4; ++i) {
    for (const char* key : {"gospa_mean_m", "targets_simulated", "merge_artefacts", "latency_difference_s"}) {
      EXPECT_EQ(second["rows"][i][key], j["rows"][i][key]) << i << " " << key;
    }
  }
}

// What the import noticed reaches the user of bench as it does the user of replay (stderr), and
// --json stays parseable on stdout.
TEST_F(BenchCli, PrintsImportWarningsOnStderr) {
  Recording rec = testing::model_recording(testing::two_cars_scene(2.0), 2, 0.03, 0.01);
  rec.boxes[0].erase(rec.boxes[0].begin() + 10, rec.boxes[0].begin() + 30);  // 0.8 s unannotated
  const fs::path gap = dir_ / "gap";
  write_recording(gap, rec);
  const std::string args = "bench " + gap.string() + " --no-reference --levels full --min-cpu-s 0";
  const auto table = run_rcsim(args);
  ASSERT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("rcsim: warning: "), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("objects.csv: lines "), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("absent"), std::string::npos) << table.output;
  const auto json = run_rcsim(args + " --json", false);
  ASSERT_EQ(json.exit_code, 0) << json.output;
  EXPECT_EQ(json.output.find("warning"), std::string::npos) << "stdout holds the JSON only";
  EXPECT_EQ(nlohmann::json::parse(json.output)["rows"].size(), 1u);
  const auto clean = run_rcsim("bench " + recording("standstill_1m") + " --no-reference --levels full --min-cpu-s 0");
  ASSERT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_EQ(clean.output.find("warning"), std::string::npos) << clean.output;
}

TEST_F(BenchCli, TableWithReferenceGoalsAndStorage) {
  const std::string db = (dir_ / "report.sqlite").string();
  const auto r = run_rcsim("bench " + recording("standstill_1m") + " --levels full --min-cpu-s 0 --db " + db);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* text : {"reference", "noise_floor", "full", "all recordings", "goals", "x faster than the reference",
                           "bench 1 stored in"}) {
    EXPECT_NE(r.output.find(text), std::string::npos) << text << "\n" << r.output;
  }
  SQLite::Database d(db);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM bench_rows WHERE bench_id = 1").getInt(), 3);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM bench_rows WHERE level = 'noise_floor' AND cpu_s IS NULL").getInt(), 1);
  EXPECT_GT(d.execAndGet("SELECT sensor_cycles_per_cpu_s FROM bench_rows WHERE level = 'full'").getDouble(),
            100.0 * d.execAndGet("SELECT sensor_cycles_per_cpu_s FROM bench_rows WHERE level = 'reference'").getDouble());
}

TEST_F(BenchCli, RefusalsNameTheInputAndStoreNothing) {
  const std::string db = (dir_ / "report.sqlite").string();
  ASSERT_EQ(run_rcsim("bench " + recording("standstill_1m") + " --no-reference --levels full --min-cpu-s 0 --db " + db).exit_code, 0);

  auto r = run_rcsim("bench " + recording("standstill_1m") + " --levels full,fast --db " + db);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--levels"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fast"), std::string::npos) << r.output;

  r = run_rcsim("bench " + recording("standstill_1m") + " " + (dir_ / "missing").string() + " --db " + db);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find((dir_ / "missing").string()), std::string::npos) << r.output;

  r = run_rcsim("bench " + recording("standstill_1m") + " --no-reference --levels none");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("nothing to bench"), std::string::npos) << r.output;

  // No recording named, in a directory without recordings_synthetic/.
  const fs::path out = dir_ / "out.txt";
  const int status = std::system(("cd " + dir_.string() + " && " + RCSIM_BINARY + " bench --no-reference > " +
                                  out.string() + " 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(testing::read_file(out).find("name RECORDING_DIRs"), std::string::npos) << testing::read_file(out);

  SQLite::Database d(db);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM bench_runs").getInt(), 1);
  EXPECT_EQ(d.execAndGet("PRAGMA integrity_check").getString(), "ok");
}

}  // namespace
}  // namespace rcsim

namespace {

// The programs built from bench/ beside rcsim in build/bin: --help and -h print the usage and end
// with 0, an unknown option or a wrong number of arguments ends with 2, and neither writes
// anything (`rcsim_make_long_recording --help` once wrote 52 MB into a directory named --help).

namespace fs = std::filesystem;
using rcsim::testing::CommandResult;

fs::path bench_tool_path(const std::string& name) { return fs::path(RCSIM_BINARY).parent_path() / name; }

// TOOL ARGS run in `dir`, stderr joined; ended after 60 s should it start real work.
CommandResult run_bench_tool(const fs::path& dir, const std::string& name, const std::string& args) {
  return rcsim::testing::run_shell_command("cd " + dir.string() + " && timeout 60 " + bench_tool_path(name).string() + " " + args);
}

class BenchToolsCli : public rcsim::testing::ScratchDirTest {
 protected:
  BenchToolsCli() : ScratchDirTest("bench_tools_cli") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    if (!fs::exists(bench_tool_path("rcsim_make_long_recording"))) {
      GTEST_SKIP() << "the bench programs are not built here (RCSIM_BUILD_BENCHMARKS=OFF)";
    }
  }
  bool dir_is_empty() const { return fs::is_empty(dir_); }
};

const std::vector<std::string> kArgumentTools = {"rcsim_make_long_recording", "rcsim_make_campaign_db", "rcsim_bench_campaign",
                                                  "rcsim_bench_pointcloud"};
const std::vector<std::string> kGoogleBenchmarks = {"rcsim_bench_sensor_cycle", "rcsim_bench_synth", "rcsim_bench_traffic",
                                                    "rcsim_bench_gospa"};

TEST_F(BenchToolsCli, EveryProgramPrintsItsUsageForHelp) {
  std::vector<std::string> all = kArgumentTools;
  all.insert(all.end(), kGoogleBenchmarks.begin(), kGoogleBenchmarks.end());
  for (const std::string& tool : all) {
    for (const char* help : {"--help", "-h"}) {
      const auto r = run_bench_tool(dir_, tool, help);
      EXPECT_EQ(r.exit_code, 0) << tool << " " << help << ": " << r.output;
      EXPECT_EQ(r.output.rfind("usage: " + tool + " ", 0), 0u) << tool << " " << help << ": " << r.output;
    }
    const auto after_argument = run_bench_tool(dir_, tool, "out --help");
    EXPECT_EQ(after_argument.exit_code, 0) << tool << ": " << after_argument.output;
    EXPECT_TRUE(dir_is_empty()) << tool << " --help wrote into " << dir_;
  }
}

TEST_F(BenchToolsCli, WrongCommandLinesEndWithStatusTwoAndWriteNothing) {
  for (const std::string& tool : kArgumentTools) {
    for (const std::string args : {"", "out --bogus", "-x", "a 1 2 3 4 5"}) {
      const auto r = run_bench_tool(dir_, tool, args);
      EXPECT_EQ(r.exit_code, 2) << tool << " " << args << ": " << r.output;
      EXPECT_NE(r.output.find("usage: " + tool), std::string::npos) << tool << " " << args << ": " << r.output;
    }
  }
  for (const std::string args : {"out abc", "out 0", "out 10 -3", "out 10 1.5"}) {
    const auto r = run_bench_tool(dir_, "rcsim_make_long_recording", args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
  }
  EXPECT_EQ(run_bench_tool(dir_, "rcsim_make_campaign_db", "out.sqlite 0").exit_code, 2);
  EXPECT_EQ(run_bench_tool(dir_, "rcsim_bench_campaign", "work 10 x").exit_code, 2);
  for (const std::string& tool : kGoogleBenchmarks) {
    const auto r = run_bench_tool(dir_, tool, "--benchmark_filter=none --bogus");
    EXPECT_EQ(r.exit_code, 2) << tool << ": " << r.output;
    EXPECT_NE(r.output.find("--bogus"), std::string::npos) << tool << ": " << r.output;
  }
  EXPECT_TRUE(dir_is_empty());
}

}  // namespace
