// The rcsim command line as a user meets it: every usage error is exit status 2 with a short
// message, a mistyped option or command is named with the nearest one, one seed option, readable choices.
#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scratch_dir.hpp"
#include "app/cli/run_rcsim.hpp"

namespace rcsim::command_line_test {

namespace fs = std::filesystem;

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }

const std::string kExamples = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/";

class Cli : public rcsim::testing::ScratchDirTest {
 protected:
  Cli() : ScratchDirTest("cli") {}
};

// README's exit statuses: a wrong option or value is bad input, 2, whatever CLI11 found (it
// numbers its errors 104 to 114); --help and --version are 0.
TEST_F(Cli, EveryCommandLineErrorIsExitStatusTwoWithAShortMessage) {
  const std::map<std::string, std::string> refused = {
      {"replay x --db y --seed -1", "--seed: must be a whole number in 0..9223372036854775807, got '-1'"},
      {"campaign run-local x -j abc", "--jobs"},
      {"campaign plan " + kExamples + "front_approach.json -o d", "--shards is required"},
      {"simulate " + kExamples + "front_approach.json -o a -o b", "--output"},
      {"listen --port 99999", "--port"},
      {"simulate " + kExamples + "front_approach.json --no-such-option", "--no-such-option"},
      {"no-such-command", "unknown command 'no-such-command'"}};
  for (const auto& [args, message] : refused) {
    const auto r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << ": " << r.output;
    EXPECT_LT(r.output.size(), 400u) << args << ": " << r.output;
  }
  // CLI11's messages in rcsim's form: the program first, then where the options are.
  // A bare `rcsim` (issue 53: said only "A subcommand is required"): the commands, each with what
  // it does, and how to go on.
  const auto bare = run("");
  EXPECT_EQ(bare.exit_code, 2);
  for (const char* command : {"simulate", "replay", "report", "calibrate", "bench", "campaign", "models"}) {
    EXPECT_NE(bare.output.find(fmt::format("\n  {} ", command)), std::string::npos) << command << "\n" << bare.output;
  }
  EXPECT_NE(bare.output.find("re-simulate a recording, compare it cycle by cycle"), std::string::npos) << bare.output;
  EXPECT_TRUE(bare.output.ends_with("\nrcsim: a command is required: rcsim COMMAND --help lists its options\n")) << bare.output;
  EXPECT_EQ(run("replay").output, "rcsim: RECORDING_DIR is required (--help lists the options)\n");
  EXPECT_EQ(run("--help").exit_code, 0);
  EXPECT_EQ(run("--version").exit_code, 0);
}

// A path the file system refuses to look up (a name of 300 bytes, beyond NAME_MAX) is bad input:
// status 2, its reason named, whichever command met it (replay, import, profile derive, calibrate
// and campaign status ended with status 1 and a bare "filesystem error", from look-ups that throw).
TEST_F(Cli, APathTheFileSystemRefusesIsAnInputError) {
  const std::string too_long = (dir_ / std::string(300, 'a')).string();
  for (const std::string& args : {"replay " + too_long + " --db " + (dir_ / "r.sqlite").string(),
                                  "profile derive " + too_long + " -o " + (dir_ / "p.json").string()}) {
    const auto r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("File name too long"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "r.sqlite"));
  EXPECT_FALSE(fs::exists(dir_ / "p.json"));
}

}  // namespace rcsim::command_line_test

namespace rcsim::command_line_test {

// The command line's rough edges (issue 31): a mistyped option or command named with what was
// probably meant, one seed option everywhere, readable choices in --help, exit status 2 for every
// usage and input error, and a hint when `listen --truth-output` received no ground truth.

using rcsim::testing::CommandResult;

const std::string kUsageScene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/front_approach.json";
const std::string kUsageRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/standstill_1m";

using rcsim::testing::output_has;
CommandResult run_usage(const std::string& args) { return rcsim::testing::run_rcsim_with_timeout(args); }

class CliUsage : public rcsim::testing::ScratchDirTest {
 protected:
  CliUsage() : ScratchDirTest("cli_usage") {}
};

TEST_F(CliUsage, AMistypedOptionIsNamedWithTheNearestOption) {
  const std::string db = (dir_ / "r.sqlite").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"replay x --db " + db + " --sed 1", "rcsim replay: unknown option '--sed'; did you mean '--seed'?"},
      {"replay x --sed 1", "rcsim replay: unknown option '--sed'; did you mean '--seed'?"},  // before "--db is required"
      {"replay x --db " + db + " --sed=1", "unknown option '--sed'; did you mean '--seed'?"},
      {"replay x --bd " + db, "unknown option '--bd'; did you mean '--db'?"},
      {"simulate " + kUsageScene + " --fidelty full", "rcsim simulate: unknown option '--fidelty'; did you mean '--fidelity'?"},
      {"campaign plan x --shard 2 -o d", "rcsim campaign plan: unknown option '--shard'; did you mean '--shards'?"},
      {"report x -o y --campagin never", "did you mean '--campaign'?"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_usage(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_TRUE(output_has(r, message)) << args << ": " << r.output;
    EXPECT_FALSE(output_has(r, "were not expected")) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(db));
  const auto far = run_usage("simulate " + kUsageScene + " --zzzzzz");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_TRUE(output_has(far, "unknown option '--zzzzzz' (rcsim simulate --help lists the options)")) << far.output;
  EXPECT_FALSE(output_has(far, "did you mean")) << far.output;
  const auto extra = run_usage("simulate " + kUsageScene + " second.json");
  EXPECT_EQ(extra.exit_code, 2);
  EXPECT_TRUE(output_has(extra, "rcsim simulate: unexpected argument 'second.json'")) << extra.output;
}

TEST_F(CliUsage, AMistypedCommandIsNamedWithTheNearestCommand) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"replya", "rcsim: unknown command 'replya'; did you mean 'replay'?"},
      {"replya x --seed 1", "rcsim: unknown command 'replya'; did you mean 'replay'?"},
      {"simulte x", "did you mean 'simulate'?"},
      {"campaign sttaus p", "rcsim campaign: unknown command 'sttaus'; did you mean 'status'?"},
      {"frobnicate", "rcsim: unknown command 'frobnicate' (commands: simulate, import, scene, replay"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_usage(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_TRUE(output_has(r, message)) << args << ": " << r.output;
  }
}

// One option: the same type and default in every command's --help, the same refusals.
TEST_F(CliUsage, EveryCommandTakesTheSameSeed) {
  const std::string out = (dir_ / "out").string(), db = (dir_ / "r.sqlite").string();
  const std::vector<std::string> commands = {"simulate " + kUsageScene,
                                             "replay " + kUsageRecording + " --db " + db,
                                             "stream " + kUsageScene + " --to 127.0.0.1:9 --speed max",
                                             "traffic -o " + out,
                                             "bench " + kUsageRecording + " --no-reference --db " + db,
                                             "calibrate " + kUsageRecording + " -o " + out};
  for (const std::string& command : commands) {
    const std::string name = command.substr(0, command.find(' '));
    const auto help = run_usage(name + " --help");
    EXPECT_EQ(help.exit_code, 0) << name;
    EXPECT_TRUE(output_has(help, "--seed UINT=0 ")) << name << ":\n" << help.output;
    for (const std::string bad : {"-1", "1.5", "9223372036854775808", "x"}) {
      const auto r = run_usage(command + " --seed " + bad);
      EXPECT_EQ(r.exit_code, 2) << command << " --seed " << bad << ": " << r.output;
      EXPECT_TRUE(output_has(r, "--seed: must be a whole number in 0..9223372036854775807, got '" + bad + "'"))
          << command << " --seed " << bad << ": " << r.output;
    }
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(db));
}

TEST_F(CliUsage, TheDefaultSeedIsZero) {
  const auto implicit = run_usage("simulate " + kUsageScene);
  const auto zero = run_usage("simulate " + kUsageScene + " --seed 0");
  const auto one = run_usage("simulate " + kUsageScene + " --seed 1");
  ASSERT_EQ(implicit.exit_code, 0) << implicit.output;
  EXPECT_EQ(implicit.output, zero.output);
  EXPECT_NE(implicit.output, one.output);
  // traffic drew with seed 1 when no seed was given.
  const fs::path a = dir_ / "a.json", b = dir_ / "b.json";
  ASSERT_EQ(run_usage("traffic --duration-s 5 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_usage("traffic --duration-s 5 --seed 0 -o " + b.string()).exit_code, 0);
  EXPECT_EQ(rcsim::testing::read_file(a), rcsim::testing::read_file(b));
}

// CLI11's transformers print their mapping ("{always->1,auto->0,...}"): no option shows one.
TEST_F(CliUsage, HelpShowsChoicesAsWordsNotAnEnumMapping) {
  const auto report = run_usage("report --help");
  EXPECT_TRUE(output_has(report, "--campaign TEXT:{auto,always,never,only}=auto")) << report.output;
  for (const char* command : {"simulate", "import", "replay", "report", "stream", "listen", "synth", "traffic", "bench",
                              "calibrate", "merge", "models", "campaign plan", "campaign submit", "campaign run-local",
                              "campaign status", "campaign run-shard"}) {
    const auto help = run_usage(std::string(command) + " --help");
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_FALSE(output_has(help, "->")) << command << ":\n" << help.output;
    EXPECT_FALSE(output_has(help, "ENUM")) << command << ":\n" << help.output;
  }
  const auto wrong = run_usage("report x.sqlite -o y.html --campaign sometimes");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_TRUE(output_has(wrong, "--campaign: sometimes not in {auto,always,never,only}")) << wrong.output;
  EXPECT_FALSE(output_has(wrong, "->")) << wrong.output;
}

// Issue 51: an error message quotes the input, and the input's control characters reached the
// terminal raw: an escape sequence could erase the error and a carriage return or newline forge
// "done" after it. Every message is printed with them written out (\xNN).
TEST_F(Cli, ControlCharactersOfTheInputAreWrittenOutInTheErrorMessage) {
  std::ifstream in(kExamples + "front_approach.json");
  auto scene = nlohmann::json::parse(in);
  scene["objects"][0]["model"] = "car\x1b[2K\r\nrcsim: wrote out.csv\x1b]0;x\x07";
  const fs::path path = dir_ / "escapes.json";
  std::ofstream(path) << scene.dump();
  const auto r = run("simulate " + path.string() + " -o " + (dir_ / "out.csv").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("car\\x1B[2K\\x0D\\x0Arcsim: wrote out.csv\\x1B]0;x\\x07"), std::string::npos) << r.output;
  for (const char c : r.output.substr(0, r.output.size() - 1)) {
    EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << "a raw control character in: " << r.output;
  }
  EXPECT_EQ(r.output.back(), '\n');
}

}  // namespace rcsim::command_line_test
