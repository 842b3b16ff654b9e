// The rcsim command as a user runs it: determinism, output files, refusals; suggestions for a
// mistyped option or command, the one seed option, readable choices, exit statuses.
#include <gtest/gtest.h>
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

namespace {

namespace fs = std::filesystem;

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }
std::string read(const fs::path& p) { return rcsim::testing::read_file(p); }

const std::string kExamples = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/";

class Cli : public rcsim::testing::ScratchDirTest {
 protected:
  Cli() : ScratchDirTest("cli") {}
};

TEST_F(Cli, SameSeedByteIdenticalOtherSeedDifferent) {
  for (const char* level : {"detections", "tracks"}) {
    const auto a = dir_ / "a.csv", b = dir_ / "b.csv", c = dir_ / "c.csv";
    const std::string scene = kExamples + "front_approach.json --level " + level;
    ASSERT_EQ(run("simulate " + scene + " --seed 7 -o " + a.string()).exit_code, 0);
    ASSERT_EQ(run("simulate " + scene + " --seed 7 -o " + b.string()).exit_code, 0);
    ASSERT_EQ(run("simulate " + scene + " --seed 8 -o " + c.string()).exit_code, 0);
    EXPECT_GT(read(a).size(), 1000u);
    EXPECT_EQ(read(a), read(b)) << level;
    EXPECT_NE(read(a), read(c)) << level;
  }
}

TEST_F(Cli, NoNoiseIgnoresTheSeed) {
  const std::string scene = kExamples + "front_approach.json --no-noise --level detections";
  EXPECT_EQ(run("simulate " + scene + " --seed 1").output, run("simulate " + scene + " --seed 2").output);
}

TEST_F(Cli, CsvAndJsonlCarryTheSameRows) {
  const auto csv = run("simulate " + kExamples + "front_approach.json --level ideal");
  const auto jsonl = run("simulate " + kExamples + "front_approach.json --level ideal --format jsonl");
  ASSERT_EQ(csv.exit_code, 0);
  ASSERT_EQ(jsonl.exit_code, 0);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_EQ(lines(csv.output), lines(jsonl.output) + 1);  // + the CSV header
  EXPECT_EQ(csv.output.rfind("t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,object,reflector\n", 0), 0u);
  EXPECT_NE(jsonl.output.find("\"reflector\":\"front\""), std::string::npos);
}

TEST_F(Cli, BadSceneNamesFileAndFieldAndLeavesNoOutput) {
  const auto scene = dir_ / "bad.json";
  std::string text = read(kExamples + "front_approach.json");
  text.replace(text.find("\"passenger_car\""), 15, "\"hovercraft\"");
  std::ofstream(scene) << text;
  const auto out = dir_ / "out.csv";
  const auto r = run("simulate " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.json: objects[0].model: unknown object model \"hovercraft\""), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(dir_)) EXPECT_NE(entry.path().extension(), ".csv") << entry.path();
}

TEST_F(Cli, EarlierOutputSurvivesAFailedRun) {
  const auto out = dir_ / "out.csv";
  ASSERT_EQ(run("simulate " + kExamples + "front_approach.json -o " + out.string()).exit_code, 0);
  const std::string before = read(out);
  const auto scene = dir_ / "truncated.json";
  const std::string text = read(kExamples + "front_approach.json");
  std::ofstream(scene) << text.substr(0, text.size() / 2);
  const auto r = run("simulate " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("truncated.json: line"), std::string::npos) << r.output;
  EXPECT_EQ(read(out), before);
}

TEST_F(Cli, ModelsListsTheLibrary) {
  const auto r = run("models --json");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* name : {"passenger_car", "truck_trailer", "guide_board", "pole"}) {
    EXPECT_NE(r.output.find(std::string("\"name\": \"") + name + "\""), std::string::npos) << name;
  }
}

TEST_F(Cli, UnknownLevelIsRefused) {
  const auto r = run("simulate " + kExamples + "front_approach.json --level raw");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--level"), std::string::npos) << r.output;
}

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
  EXPECT_EQ(run("--help").exit_code, 0);
  EXPECT_EQ(run("--version").exit_code, 0);
}


TEST_F(Cli, ModelsSensorsListsTheProfiles) {
  const auto text = run("models --sensors");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* name : {"aimotive_lrr", "srr24"}) {
    EXPECT_NE(text.output.find(name), std::string::npos) << name << " in\n" << text.output;
  }
  EXPECT_EQ(text.output.find("passenger_car"), std::string::npos) << "object models listed too";
  const auto json = rcsim::testing::run_rcsim("models --sensors --json", false);
  ASSERT_EQ(json.exit_code, 0);
  const nlohmann::json all = nlohmann::json::parse(json.output);  // throws (and fails) unless JSON
  ASSERT_TRUE(all.is_array());
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& profile : all) by_name[profile.at("name").get<std::string>()] = profile;
  ASSERT_EQ(by_name.count("aimotive_lrr"), 1u);
  ASSERT_EQ(by_name.count("srr24"), 1u);
  EXPECT_EQ(by_name["aimotive_lrr"].at("reports"), "detections");
  EXPECT_EQ(by_name["srr24"].at("reports"), "tracks");
  EXPECT_EQ(by_name["aimotive_lrr"].at("amplitude").at("law"), "radar_equation");
  EXPECT_EQ(by_name["srr24"].at("amplitude").at("law"), "paper_eq1");
  EXPECT_EQ(by_name["aimotive_lrr"].at("carrier_frequency_hz"), 77.0e9);
}

}  // namespace

namespace {

// The command line's rough edges (issue 31): a mistyped option or command named with what was
// probably meant, one seed option everywhere, readable choices in --help, exit status 2 for every
// usage and input error, and a hint when `listen --truth-output` received no ground truth.

using rcsim::testing::CommandResult;

const std::string kUsageScene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/front_approach.json";
const std::string kUsageRecording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/standstill_1m";

// `rcsim ARGS` with stderr joined, ended after 60 s should it wait for something (a socket).
CommandResult run_usage(const std::string& args) {
  return rcsim::testing::run_shell_command("timeout 60 " + std::string(RCSIM_BINARY) + " " + args);
}

bool output_has(const CommandResult& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

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

// README's exit statuses: what the user typed wrong is 2, whichever layer finds it (the stream's
// and listener's own checks threw errors that ended with 1).
TEST_F(CliUsage, StreamAndListenRefuseBadArgumentsWithStatusTwo) {
  const std::string stream = "stream " + kUsageScene + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {stream + "--to 127.0.0.1:5000 --speed fast", "--speed 'fast'"},
      {stream + "--to 127.0.0.1:5000 --messages simulated,lies", "--messages: message type 'lies'"},
      {stream, "nothing to stream to"},
      {stream + "--to 127.0.0.1", "'127.0.0.1': no port"},
      {stream + "--to 127.0.0.1:0", "port 0 is not a destination"},
      {stream + "--to 127.0.0.1:5000 --from-cycle 101", "--from-cycle: cycle 101 is not in 0..100"},
      {stream + "--to 239.1.2.3:5000 --multicast-interface lo", "--multicast-interface: 'lo' is not an IPv4 address"},
      {"listen --sensors 0,x", "--sensors: 0,x: expected sensor indices 0..31"},
      {"listen --messages lies", "--messages: message type 'lies'"},
      {"listen --group 10.1.2.3", "--group: 10.1.2.3: not a multicast group"},
      {"listen --bind 300.1.1.1", "--bind: 300.1.1.1: not an IP address"},
      {"listen --group 239.1.2.3 --interface eth0", "--interface: eth0: not an IP address"},
      {"listen --subscribe 127.0.0.1:x", "--subscribe: '127.0.0.1:x'"},
  };
  for (const auto& [args, message] : cases) {
    const bool listen = args.rfind("listen ", 0) == 0;  // and the capture it would write
    const auto r = run_usage(args + (listen ? " -o " + (dir_ / "out.csv").string() : std::string()));
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_TRUE(output_has(r, message)) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out.csv"));
}

TEST_F(CliUsage, ListenSaysWhyTheTruthOutputHoldsOnlyItsHeader) {
  const fs::path truth = dir_ / "truth.csv";
  const auto idle = run_usage("listen --port 0 --idle-timeout-s 0.2 --truth-output " + truth.string());
  EXPECT_EQ(idle.exit_code, 0) << idle.output;
  EXPECT_TRUE(output_has(idle, "no ground truth arrived, so " + truth.string() + " holds the header only")) << idle.output;
  EXPECT_TRUE(output_has(idle, "--messages simulated,truth")) << idle.output;
  const std::string header = rcsim::testing::read_file(truth);
  EXPECT_EQ(std::count(header.begin(), header.end(), '\n'), 1) << header;

  // With the truth streamed, no hint. The listener's port is read from its log.
  const std::string bin = RCSIM_BINARY, dir = dir_.string();
  const std::string script =
      "cd " + dir + " && (timeout 60 " + bin + " listen --port 0 --idle-timeout-s 10 -o out.csv --truth-output truth.csv "
      "> listen.out 2> listen.err &) && for i in $(seq 200); do grep -q 'listening on' listen.err && break; sleep 0.05; done && "
      "port=$(sed -n 's/.*listening on 127.0.0.1:\\([0-9]*\\).*/\\1/p' listen.err) && timeout 60 " + bin + " stream " +
      kUsageScene + " --to 127.0.0.1:$port --messages simulated,truth --speed 10 2> stream.err && "
      "for i in $(seq 200); do grep -q 'rcsim listen: .*datagrams' listen.err && break; sleep 0.05; done";
  const auto streamed = rcsim::testing::run_shell_command(script);
  ASSERT_EQ(streamed.exit_code, 0) << streamed.output << rcsim::testing::read_file(dir_ / "stream.err");
  const std::string log = rcsim::testing::read_file(dir_ / "listen.err");
  EXPECT_FALSE(log.find("no ground truth arrived") != std::string::npos) << log;
  const std::string rows = rcsim::testing::read_file(truth);
  EXPECT_GT(std::count(rows.begin(), rows.end(), '\n'), 50) << log;
}

}  // namespace
