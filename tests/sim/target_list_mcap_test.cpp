// A scene's simulated target lists as MCAP (src/sim/target_list_mcap.cpp): per cycle the ego, the
// boxes of the objects present and each sensor's targets at the chosen level, the same rows the
// CSV writer writes; the mountings and view fields once.
#include "sim/target_list_mcap.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <map>
#include <sstream>
#include <string>

#include "io/foxglove_json.hpp"
#include "io/mcap_reader.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::target_list_mcap_test {

using Json = nlohmann::json;

class TargetListMcap : public rcsim::testing::ScratchDirTest {
 protected:
  TargetListMcap() : ScratchDirTest("target_list_mcap") {}
};

TEST_F(TargetListMcap, EachCycleHoldsTheRowsOfTheCsvWriterAndTheBoxesPresent) {
  Scene scene = testing::four_cars_scene();  // 2 s, one srr24 "s"; one car gone after 0.5 s
  SimulationOptions options;
  options.level = ListLevel::detections;
  options.noise = false;
  const auto path = dir_ / "s.mcap";
  std::map<int, std::size_t> csv_rows;  // cycle -> rows the CSV writer's selection gives
  {
    std::ofstream out(path, std::ios::binary);
    McapTargetListWriter writer(out, scene, options.level);
    Simulation simulation(scene, options);
    for (int cycle = 0; cycle < simulation.cycle_count(); ++cycle) {
      simulation.run_cycle(cycle);
      std::size_t rows = 0;
      for_each_target_list_row(scene, simulation.sensor_state(0), options.level, [&](const TargetListRow&) { ++rows; });
      csv_rows[cycle] = rows;
      writer.write_cycle(scene, cycle, scene.cycle_time_at(cycle), {&simulation.sensor_state(0)});
    }
    writer.finish();
  }
  mcap::Reader reader(path);
  std::map<std::string, int> per_topic;
  std::map<std::uint64_t, std::size_t> spheres_at, boxes_at;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema*) {
    ++per_topic[c.topic];
    const Json body = Json::parse(m.data);
    if (c.topic == "/rcsim/s/simulated") spheres_at[m.log_time_ns] = body["entities"][0]["spheres"].size();
    if (c.topic == "/rcsim/boxes") boxes_at[m.log_time_ns] = body["entities"][0]["cubes"].size();
    EXPECT_EQ(c.metadata.at("source"), "simulate");
  });
  const int cycles = scene.cycle_count();
  EXPECT_EQ(per_topic["/rcsim/s/simulated"], cycles);
  EXPECT_EQ(per_topic["/rcsim/s/view_field"], 1);
  EXPECT_EQ(per_topic["/rcsim/boxes"], cycles);
  EXPECT_EQ(per_topic["/tf"], cycles + 1);  // the ego a cycle, the mounting once
  std::size_t targets = 0;
  for (const auto& [cycle, rows] : csv_rows) {
    const std::uint64_t ns = foxglove::time_ns(scene.cycle_time_at(cycle));
    EXPECT_EQ(spheres_at[ns], rows) << "cycle " << cycle;
    targets += rows;
  }
  EXPECT_GT(targets, 0u);
  // Four cars at first, three once "gone" has left (presence [0, 0.5] s).
  EXPECT_EQ(boxes_at[0], 4u);
  EXPECT_EQ(boxes_at[foxglove::time_ns(scene.cycle_time_at(cycles - 1))], 3u);
}

}  // namespace rcsim::target_list_mcap_test
