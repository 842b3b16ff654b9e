// The bird's-eye renderer (replay/report/svg_birdseye.hpp): every element drawn, x forward up and y left to the left.
#include "replay/report/svg_birdseye.hpp"

#include <gtest/gtest.h>

#include <regex>

#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

std::size_t count(const std::string& text, const std::string& needle) { return testing::count_occurrences(text, needle); }

TEST(SvgBirdseye, BirdsEyeDrawsBoxesSensorsTargetsAndLinks) {
  svg::BirdsEyeSpec spec;
  spec.title = "cycle";
  spec.trace_cycles = 2;
  spec.sensors.push_back({"s", {3.7, 0.0, 0.0}, 1.0, 40.0});
  spec.boxes.push_back({"car", {15.0, 0.0, 3.14}, 4.5, 1.8, false});
  spec.targets.push_back({{13.0, 0.5}, false, 0, false});
  spec.targets.push_back({{13.1, 0.4}, true, 0, true});
  spec.targets.push_back({{13.5, 0.4}, true, 2, false});
  spec.links.push_back({{13.0, 0.5}, {13.1, 0.4}});
  const std::string out = svg::birdseye_svg(spec);
  EXPECT_EQ(count(out, "<polygon class=\"box\""), 1u);
  EXPECT_EQ(count(out, "<polygon class=\"fov\""), 1u);
  EXPECT_EQ(count(out, "<polygon class=\"sensor\""), 1u);
  EXPECT_EQ(count(out, "<circle class=\"t rec current\""), 1u);
  EXPECT_EQ(count(out, "<polygon class=\"t sim current\""), 1u);
  EXPECT_EQ(count(out, "<polygon class=\"t sim trace\""), 1u);
  EXPECT_EQ(count(out, "<circle class=\"merge\""), 1u);
  EXPECT_NE(out.find("x / m (vehicle frame, forward)"), std::string::npos);
  // x forward is up: the target at x = 13 m is drawn above the vehicle origin.
  const std::regex cy_re("class=\"t rec current\" cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, cy_re));
  const std::regex ego_re("<g class=\"ego\"[^>]*><line x1=\"([-0-9.]+)\" y1=\"([-0-9.]+)\" x2=\"[-0-9.]+\" y2=\"([-0-9.]+)\"");
  std::smatch e;
  ASSERT_TRUE(std::regex_search(out, e, ego_re));
  EXPECT_LT(std::stod(m[2]), std::stod(e[2]));
  EXPECT_LT(std::stod(m[1]), std::stod(e[1]));  // y = +0.5 m (left) is drawn left of the origin
}

}  // namespace
}  // namespace rcsim::replay
