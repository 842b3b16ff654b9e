// `rcsim traffic` as a user runs it: the default scene simulates with targets; bad input is
// refused with exit status 2, a message naming the option, and no output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/cli/run_rcsim.hpp"

namespace {

namespace fs = std::filesystem;
using rcsim::testing::run_rcsim;

class TrafficCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rcsim_traffic_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TrafficCli, DefaultSceneSimulatesWithTargets) {
  const auto scene = dir_ / "s.json";
  const auto r = run_rcsim("traffic --seed 1 -o " + scene.string());  // seed 0 puts no vehicle in front_right's view
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto sim = run_rcsim("simulate " + scene.string(), false);
  ASSERT_EQ(sim.exit_code, 0);
  const auto rows = std::count(sim.output.begin(), sim.output.end(), '\n') - 1;
  EXPECT_GT(rows, 200) << "the ego's sensors see traffic";
  EXPECT_NE(sim.output.find(",front_left,"), std::string::npos);
  EXPECT_NE(sim.output.find(",front_right,"), std::string::npos);
  const auto inter = dir_ / "i.json";
  ASSERT_EQ(run_rcsim("traffic --layout intersection --duration-s 20 -o " + inter.string()).exit_code, 0);
  EXPECT_EQ(run_rcsim("simulate " + inter.string() + " --level ideal", false).exit_code, 0);
}

TEST_F(TrafficCli, SameSeedByteIdenticalFile) {
  const auto a = dir_ / "a.json", b = dir_ / "b.json", c = dir_ / "c.json";
  ASSERT_EQ(run_rcsim("traffic --duration-s 10 --seed 4 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rcsim("traffic --duration-s 10 --seed 4 -o " + b.string()).exit_code, 0);
  ASSERT_EQ(run_rcsim("traffic --duration-s 10 --seed 5 -o " + c.string()).exit_code, 0);
  EXPECT_EQ(rcsim::testing::read_file(a), rcsim::testing::read_file(b));
  EXPECT_NE(rcsim::testing::read_file(a), rcsim::testing::read_file(c));
}

TEST_F(TrafficCli, ImpossibleInputIsRefused) {
  const auto out = dir_ / "bad.json";
  const std::pair<std::string, std::string> cases[] = {
      {"--lanes 0", "--lanes: 0 lanes"},
      {"--lanes -2", "--lanes: -2 lanes"},
      {"--density-vpkm 200", "jam density"},
      {"--density-vpkm -1", "cannot be negative"},
      {"--inflow-vph -5", "--inflow-vph: -5 vehicles/h: cannot be negative"},
      {"--layout roundabout", "unknown layout \"roundabout\""},
      {"--length-m 500", "would leave the highway"},
      {"--truck-share 1.5", "between 0 and 1"},
      {"--sensor a,radar9,1,0,0", "--sensor 1"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_rcsim("traffic " + args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace
