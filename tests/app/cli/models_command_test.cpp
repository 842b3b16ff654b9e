// `rcsim models` as a user runs it: the object models and the sensor profiles, as text and JSON.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::models_command_test {

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }

class ModelsCli : public rcsim::testing::ScratchDirTest {
 protected:
  ModelsCli() : ScratchDirTest("models_cli") {}
};

TEST_F(ModelsCli, ModelsListsTheLibrary) {
  const auto r = run("models --json");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* name : {"passenger_car", "truck_trailer", "guide_board", "pole"}) {
    EXPECT_NE(r.output.find(std::string("\"name\": \"") + name + "\""), std::string::npos) << name;
  }
}

TEST_F(ModelsCli, ModelsSensorsListsTheProfiles) {
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

}  // namespace rcsim::models_command_test
