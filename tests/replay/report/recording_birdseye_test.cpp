// The bird's-eye picture of a recording (replay/report/recording_birdseye.hpp, rcsim synth --svg):
// boxes and targets in the pictured cycle's vehicle frame, traces aged, a compared list, object
// ids escaped (the old writer of the reference's pictures wrote them raw), refusals naming the file.
#include "replay/report/recording_birdseye.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "common/input_error.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::svg {
namespace {

// The ego drives along +x at 10 m/s for 3 cycles; one sensor looks forward; one box 20 m ahead
// of the ego at the last cycle; one target per cycle straight ahead at 15 m.
Recording straight_drive(const std::string& object_id) {
  Recording rec;
  rec.name = "drive";
  rec.cycle_time_s = 0.1;
  rec.sensors.push_back({"front", "srr24", 3.0, 0.0, 0.0});
  rec.objects.push_back({object_id, "passenger_car", 4.5, 1.8});
  rec.boxes.emplace_back();
  for (int k = 0; k < 3; ++k) {
    const double t = 0.1 * k, x = 1.0 * k;
    rec.ego.push_back({t, x, 0.0, 0.0, 10.0, 0.0});
    rec.boxes[0].push_back({t, 22.0, 0.0, 0.0, 0.0, 0});
    rec.targets.push_back({t, k, 0, -1, 15.0, 0.0, -10.0, 20.0});
  }
  return rec;
}

TEST(RecordingBirdseye, BoxesAndTargetsInThePicturedCyclesVehicleFrame) {
  const BirdsEyeSpec spec = recording_birdseye(straight_drive("car1"), {});
  ASSERT_EQ(spec.boxes.size(), 1u);
  EXPECT_NEAR(spec.boxes[0].X_VO.x_m, 20.0, 1e-12);  // box at 22 m, ego at 2 m
  ASSERT_EQ(spec.sensors.size(), 1u);
  EXPECT_NEAR(spec.sensors[0].azimuth_half_rad, 35.0 * 3.141592653589793 / 180.0, 1e-12);  // srr24's view field
  ASSERT_EQ(spec.targets.size(), 3u);
  EXPECT_NEAR(spec.targets[2].p_V.x(), 18.0, 1e-12);  // 3 m mount + 15 m
  EXPECT_EQ(spec.targets[2].age, 0);
  EXPECT_NEAR(spec.targets[0].p_V.x(), 16.0, 1e-12);  // two cycles earlier the ego was 2 m behind
  EXPECT_EQ(spec.targets[0].age, 2);
  EXPECT_EQ(spec.trace_cycles, 2);
  RecordingPictureOptions earlier;
  earlier.time_s = 0.1;
  earlier.cycles = 1;
  EXPECT_EQ(recording_birdseye(straight_drive("car1"), earlier).targets.size(), 1u);
}

TEST(RecordingBirdseye, ObjectIdsAreEscapedAndTheSvgIsStandalone) {
  const std::string svg = recording_birdseye_svg(straight_drive("<x&\"y>"), {});
  EXPECT_EQ(svg.find("<x&"), std::string::npos);
  EXPECT_NE(svg.find("&lt;x&amp;&quot;y&gt;"), std::string::npos);
  EXPECT_NE(svg.find("<style>"), std::string::npos);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
}

TEST(RecordingBirdseye, AScriptTagAsObjectIdOrTitleIsDrawnEscapedNeverRaw) {
  RecordingPictureOptions options;
  options.title = "<script>&\"title";
  const std::string svg = recording_birdseye_svg(straight_drive("<script>&\""), options);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("&\""), std::string::npos);
  EXPECT_NE(svg.find(">&lt;script&gt;&amp;&quot;</text>"), std::string::npos);  // the box label
  EXPECT_NE(svg.find("class=\"title\">&lt;script&gt;&amp;&quot;title</text>"), std::string::npos);
}

TEST(RecordingBirdseye, ABoxAheadOfTheEgoIsDrawnAboveItsSensor) {
  const std::string svg = recording_birdseye_svg(straight_drive("car1"), {});
  std::smatch box, sensor;
  // The box's four corners, on screen.
  ASSERT_TRUE(std::regex_search(svg, box, std::regex(R"re(<polygon class="box" points="([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+))re")));
  ASSERT_TRUE(std::regex_search(svg, sensor, std::regex(R"re(class="sensor" points="([-0-9.]+),([-0-9.]+))re")));
  EXPECT_LT(std::stod(box[2]), std::stod(sensor[2]) - 50.0);  // 17 m ahead of the sensor's tip
  const double centre_x = (std::stod(box[1]) + std::stod(box[3]) + std::stod(box[5]) + std::stod(box[7])) / 4.0;
  EXPECT_NEAR(centre_x, std::stod(sensor[1]), 1.0);  // straight ahead
}

TEST(RecordingBirdseye, AnEmptyRecordingGivesAnEmptyValidPicture) {
  const Recording empty;
  const BirdsEyeSpec spec = recording_birdseye(empty, {});
  EXPECT_TRUE(spec.boxes.empty());
  EXPECT_TRUE(spec.targets.empty());
  const std::string svg = recording_birdseye_svg(empty, {});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 6), "</svg>");
}

class RecordingBirdseyeCompare : public rcsim::testing::ScratchDirTest {
 protected:
  RecordingBirdseyeCompare() : ScratchDirTest("recording_birdseye") {}
};

TEST_F(RecordingBirdseyeCompare, ACompareListIsDrawnAndAnUnknownSensorRefused) {
  const auto csv = dir_ / "sim.csv";
  std::ofstream(csv) << "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n0.2,2,front,1,14.0,0.0,-10.0,20.0\n";
  RecordingPictureOptions options;
  options.compare_path = csv.string();
  const BirdsEyeSpec spec = recording_birdseye(straight_drive("car1"), options);
  ASSERT_EQ(spec.targets.size(), 4u);
  EXPECT_TRUE(spec.targets[3].simulated);
  EXPECT_NEAR(spec.targets[3].p_V.x(), 17.0, 1e-12);
  std::ofstream(csv) << "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n0.2,2,rear,1,14.0,0.0,-10.0,20.0\n";
  try {
    recording_birdseye(straight_drive("car1"), options);
    FAIL() << "an unknown sensor was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sim.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rear"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsim::replay::svg
