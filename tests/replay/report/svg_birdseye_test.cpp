// The bird's-eye renderer (replay/report/svg_birdseye.hpp): every element drawn, x forward up and y left to the left.
#include "replay/report/svg_birdseye.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <stdexcept>
#include <utility>

#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {


TEST(SvgBirdseye, BirdsEyeDrawsBoxesSensorsTargetsAndLinks) {
  svg::BirdsEyeSpec spec;
  spec.title = "cycle";
  spec.trace_cycles = 2;
  spec.sensors.push_back({"s", {3.7, 0.0, 0.0}, 1.0, 40.0});
  spec.boxes.push_back({"car", {15.0, 0.0, 3.14}, 4.5, 1.8, false});
  spec.targets.push_back({{13.0, 0.5}, false, 0, false, ""});
  spec.targets.push_back({{13.1, 0.4}, true, 0, true, ""});
  spec.targets.push_back({{13.5, 0.4}, true, 2, false, ""});
  spec.links.push_back({{13.0, 0.5}, {13.1, 0.4}});
  const std::string out = svg::birdseye_svg(spec);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"box\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"fov\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"sensor\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<circle class=\"t rec current\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"t sim current\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"t sim trace\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<circle class=\"merge\""), 1u);
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

// The screen position (x, y in pixels) of the first element matched by `re`'s two groups.
std::pair<double, double> screen_xy(const std::string& svg, const std::string& re) {
  std::smatch m;
  if (!std::regex_search(svg, m, std::regex(re))) throw std::runtime_error("not drawn: " + re);
  return {std::stod(m[1]), std::stod(m[2])};
}

std::pair<double, double> box_label_xy(const std::string& svg, const std::string& label) {
  return screen_xy(svg, "class=\"box-label\" x=\"([-0-9.]+)\" y=\"([-0-9.]+)\">" + label + "<");
}

// The centre on screen of the `index`-th box drawn: the mean of its four corners.
std::pair<double, double> box_centre_xy(const std::string& svg, std::size_t index) {
  const std::regex box_re(R"re(<polygon class="box" points="([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+)")re");
  auto it = std::sregex_iterator(svg.begin(), svg.end(), box_re);
  for (std::size_t i = 0; i < index && it != std::sregex_iterator(); ++i) ++it;
  if (it == std::sregex_iterator()) throw std::runtime_error("box not drawn");
  const std::smatch& m = *it;
  return {(std::stod(m[1]) + std::stod(m[3]) + std::stod(m[5]) + std::stod(m[7])) / 4.0,
          (std::stod(m[2]) + std::stod(m[4]) + std::stod(m[6]) + std::stod(m[8])) / 4.0};
}

TEST(SvgBirdseye, EmptySpecRendersAValidSvg) {
  const std::string out = svg::birdseye_svg({});
  EXPECT_EQ(out.rfind("<svg class=\"birdseye\"", 0), 0u);
  EXPECT_EQ(out.substr(out.size() - 6), "</svg>");
  EXPECT_EQ(testing::count_occurrences(out, "<svg"), 2u);  // the picture and its clipping viewport
  EXPECT_EQ(testing::count_occurrences(out, "</svg>"), 2u);
  EXPECT_EQ(testing::count_occurrences(out, "<g"), testing::count_occurrences(out, "</g>"));
  EXPECT_EQ(out.find("nan"), std::string::npos);
  EXPECT_EQ(out.find("inf"), std::string::npos);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"box\""), 0u);
  EXPECT_EQ(testing::count_occurrences(out, "class=\"t "), 0u);
  EXPECT_EQ(out.find("<style>"), std::string::npos);  // only a standalone picture carries styles
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, std::regex(R"re(width="([0-9]+)" height="([0-9]+)")re")));
  EXPECT_GT(std::stoi(m[1]), 500);
  EXPECT_GT(std::stoi(m[2]), 500);
}

TEST(SvgBirdseye, ABoxAheadIsAboveTheSensorAndABoxToTheLeftIsLeftOfIt) {
  svg::BirdsEyeSpec spec;
  spec.sensors.push_back({"front", {0.0, 0.0, 0.0}, 0.5, 30.0});
  spec.boxes.push_back({"ahead", {10.0, 0.0, 0.0}, 4.0, 2.0, false});
  spec.boxes.push_back({"left", {0.0, 8.0, 0.0}, 4.0, 2.0, false});
  const std::string out = svg::birdseye_svg(spec);
  // The sensor marker's first point is its tip, 9 px ahead of the sensor on its axis.
  const auto [sensor_x, sensor_y] = screen_xy(out, R"re(class="sensor" points="([-0-9.]+),([-0-9.]+))re");
  const auto [ahead_x, ahead_y] = box_centre_xy(out, 0);
  const auto [left_x, left_y] = box_centre_xy(out, 1);
  EXPECT_LT(ahead_y, sensor_y - 100.0);  // 10 m forward: well above the sensor
  EXPECT_NEAR(ahead_x, sensor_x, 0.5);   // and straight above it
  EXPECT_LT(left_x, sensor_x - 100.0);   // 8 m left: well left of it
  EXPECT_NEAR(left_y, sensor_y, 15.0);   // at the sensor's height (the tip is 9 px ahead of it)
  // Each label beside its box, on its right on screen.
  EXPECT_GT(box_label_xy(out, "ahead").first, ahead_x);
  EXPECT_NEAR(box_label_xy(out, "ahead").second, ahead_y, 12.0);
  // Equal scale: pixels per metre up and to the left agree.
  EXPECT_NEAR((sensor_y - ahead_y) / 10.0, (sensor_x - left_x) / 8.0, 2.0);
}

// A real drive's background reaches 170 m ahead: it must not shrink the annotated cars to a few
// pixels. Targets of no annotated object widen the view only within the near field (40 m).
TEST(SvgBirdseye, FarBackgroundDoesNotWidenTheViewAnObjectTargetDoes) {
  const auto label_to_ego_px = [](const std::string& target_class) {
    svg::BirdsEyeSpec spec;
    spec.sensors.push_back({"s", {3.7, 0.0, 0.0}, 1.0, 200.0});
    spec.boxes.push_back({"car", {15.0, 0.0, 0.0}, 4.5, 1.8, false});
    spec.targets.push_back({{150.0, 2.0}, false, 0, false, target_class});
    spec.targets.push_back({{30.0, -3.0}, false, 0, false, "background"});  // in the near field
    const std::string out = svg::birdseye_svg(spec);
    const auto label = box_centre_xy(out, 0);
    const auto ego = screen_xy(out, "<g class=\"ego\"[^>]*><line x1=\"([-0-9.]+)\" y1=\"([-0-9.]+)\"");
    return ego.second - label.second;  // pixels from the ego up to the car
  };
  const double fitted = label_to_ego_px("background"), wide = label_to_ego_px("object");
  EXPECT_GT(fitted, 3.0 * wide) << fitted << " px against " << wide << " px";
}

// A road 200 m long and 20 m wide (a real drive's front and rear radars): the plot grows taller,
// up to twice its width, at one scale for both axes, rather than drawing the cars 2 px wide.
TEST(SvgBirdseye, ALongViewGetsATallerPlotAtOneScale) {
  svg::BirdsEyeSpec spec;
  spec.size_px = 400;
  spec.sensors.push_back({"front", {3.7, 0.0, 0.0}, 0.3, 200.0});
  spec.sensors.push_back({"rear", {-1.0, 0.0, 3.14159}, 0.3, 200.0});
  spec.boxes.push_back({"ahead", {100.0, 3.0, 0.0}, 4.5, 1.8, false});
  spec.boxes.push_back({"behind", {-100.0, -3.0, 0.0}, 4.5, 1.8, false});
  const std::string out = svg::birdseye_svg(spec);
  std::smatch plot;
  ASSERT_TRUE(std::regex_search(out, plot, std::regex(R"re(<svg x="[-0-9.]+" y="[-0-9.]+" width="([0-9.]+)" height="([0-9.]+)")re")));
  EXPECT_DOUBLE_EQ(std::stod(plot[1]), 400.0);
  EXPECT_DOUBLE_EQ(std::stod(plot[2]), 800.0);  // 2 x, the most
  // One scale: 200 m between the boxes' centres up and 6 m across give the same pixels per metre.
  const auto ahead = box_centre_xy(out, 0), behind = box_centre_xy(out, 1);
  const double px_per_m_up = (behind.second - ahead.second) / 200.0, px_per_m_across = (behind.first - ahead.first) / 6.0;  // left is left
  EXPECT_NEAR(px_per_m_up, px_per_m_across, 0.05);
  EXPECT_GT(px_per_m_up, 3.0);  // about 3.4 px/m where a 400 px square held 1.7
  // A short, wide view stays square.
  svg::BirdsEyeSpec wide;
  wide.size_px = 400;
  wide.sensors.push_back({"front", {0.0, 0.0, 0.0}, 1.0, 30.0});
  wide.boxes.push_back({"left", {10.0, 20.0, 0.0}, 4.5, 1.8, false});
  wide.boxes.push_back({"right", {10.0, -20.0, 0.0}, 4.5, 1.8, false});
  const std::string square = svg::birdseye_svg(wide);
  ASSERT_TRUE(std::regex_search(square, plot, std::regex(R"re(<svg x="[-0-9.]+" y="[-0-9.]+" width="([0-9.]+)" height="([0-9.]+)")re")));
  EXPECT_DOUBLE_EQ(std::stod(plot[2]), 400.0);
}

// Three cars side by side and nose to tail: each label beside its box, no two on top of each other.
TEST(SvgBirdseye, LabelsOfNeighbouringBoxesDoNotOverlap) {
  svg::BirdsEyeSpec spec;
  spec.sensors.push_back({"front", {0.0, 0.0, 0.0}, 1.0, 150.0});
  spec.boxes.push_back({"car_long_name_0", {50.0, 0.0, 0.0}, 4.5, 1.8, false});
  spec.boxes.push_back({"car_long_name_1", {50.5, -1.0, 0.0}, 4.5, 1.8, false});
  spec.boxes.push_back({"car_long_name_2", {51.0, 0.5, 0.0}, 4.5, 1.8, false});
  const std::string out = svg::birdseye_svg(spec);
  std::vector<std::pair<double, double>> at;
  for (const char* label : {"car_long_name_0", "car_long_name_1", "car_long_name_2"}) at.push_back(box_label_xy(out, label));
  for (std::size_t i = 0; i < at.size(); ++i) {
    for (std::size_t j = i + 1; j < at.size(); ++j) {
      // 10 px text, 15 characters of about 5.6 px: apart by a line or by their width.
      const bool apart = std::abs(at[i].second - at[j].second) >= 10.0 || std::abs(at[i].first - at[j].first) >= 84.0;
      EXPECT_TRUE(apart) << i << " at (" << at[i].first << ", " << at[i].second << "), " << j << " at (" << at[j].first
                         << ", " << at[j].second << ")";
    }
  }
}

TEST(SvgBirdseye, EveryTextFromDataIsEscaped) {
  const std::string hostile = "<script>&\"";
  svg::BirdsEyeSpec spec;
  spec.title = hostile;
  spec.notes = {hostile};
  spec.sensors.push_back({hostile, {0.0, 0.0, 0.0}, 0.5, 30.0});
  spec.boxes.push_back({hostile, {10.0, 0.0, 0.0}, 4.0, 2.0, false});
  spec.recorded_label = hostile;
  spec.simulated_label = hostile;
  const std::string out = svg::birdseye_svg(spec);
  EXPECT_EQ(out.find("<script"), std::string::npos);
  EXPECT_EQ(out.find("&\""), std::string::npos);
  // aria-label and title, note, sensor tooltip, box label, two legend entries
  EXPECT_EQ(testing::count_occurrences(out, "&lt;script&gt;&amp;&quot;"), 7u);
}


// A point cloud's marks that would land on one another are drawn once (issue 52): 10,000 targets
// of the pictured cycle on one spot and 10,000 on another give one mark each (and a merge
// artefact is always ringed); 50,000 background traces spread over the picture keep at most the
// trace budget, the objects' traces their path.
TEST(SvgBirdseye, MarksOnOnePixelAreDrawnOnceAndTracesKeepABudget) {
  svg::BirdsEyeSpec spec;
  spec.trace_cycles = 5;
  spec.sensors.push_back({"s", {0.0, 0.0, 0.0}, 1.0, 60.0});
  for (int i = 0; i < 10000; ++i) {
    spec.targets.push_back({{20.0, 1.0}, false, 0, i == 0, ""});
    spec.targets.push_back({{30.0, -1.0}, true, 0, false, ""});
  }
  for (int i = 0; i < 50000; ++i) {
    const double x_m = 1.0 + 0.001 * i, y_m = -20.0 + 0.0008 * static_cast<double>((i * 7919) % 50000);
    spec.targets.push_back({{x_m, y_m}, i % 2 == 0, 1 + i % 5, false, "background"});
  }
  for (int i = 0; i < 50; ++i) spec.targets.push_back({{5.0 + i, 0.0}, false, 1, false, ""});  // a path 50 m long
  const std::string out = svg::birdseye_svg(spec);
  EXPECT_EQ(testing::count_occurrences(out, "<circle class=\"t rec current\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<polygon class=\"t sim current\""), 1u);
  EXPECT_EQ(testing::count_occurrences(out, "<circle class=\"merge\""), 1u);
  const std::size_t traces = testing::count_occurrences(out, "<circle class=\"t rec trace\"") +
                             testing::count_occurrences(out, "<polygon class=\"t sim trace\"");
  EXPECT_LE(traces, 1500u);
  EXPECT_GE(traces, 500u);  // the background still covers the picture
  // The path's 50 targets at least a metre (several pixels) apart: each kept.
  EXPECT_GE(testing::count_occurrences(out, "<circle class=\"t rec trace\" cx=\""), 50u);
}

}  // namespace

}  // namespace rcsim::replay
