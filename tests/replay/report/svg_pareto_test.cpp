// The speed-against-error plot (replay/report/svg_pareto.hpp): the Pareto front by hand,
// superscript labels of the log axis, a plot with nothing to draw. The placed plot itself is
// checked in bench_section_test.cpp on a stored bench.
#include "replay/report/svg_pareto.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <utility>

namespace rcsim::replay {
namespace {

TEST(SvgPareto, FrontKeepsTiesAndSkipsWhatCannotBeDrawn) {
  std::vector<svg::ParetoPoint> points{{"slow_exact", 100.0, 0.5, false},     {"fast_rough", 1e6, 2.0, false},
                                       {"twin_a", 1e4, 1.0, false},           {"twin_b", 1e4, 1.0, false},
                                       {"same_speed_worse", 1e4, 1.5, false}, {"no_time", std::nan(""), 0.1, false},
                                       {"zero_speed", 0.0, 0.1, false}};
  const std::vector<bool> front = svg::pareto_front(points);
  EXPECT_EQ(front, (std::vector<bool>{true, true, true, true, false, false, false}));
  EXPECT_EQ(svg::pareto_front({}), std::vector<bool>{});
}

TEST(SvgPareto, PowerOfTenLabelsUseSuperscripts) {
  EXPECT_EQ(svg::power_of_ten_label(5), "10\u2075");
  EXPECT_EQ(svg::power_of_ten_label(12), "10\u00b9\u00b2");
  EXPECT_EQ(svg::power_of_ten_label(-3), "10\u207b\u00b3");
}

TEST(SvgPareto, PlotWithoutDrawablePointsSaysSo) {
  svg::ParetoSpec spec;
  spec.title = "t <1>";
  spec.points = {{"noise", std::nan(""), 1.0, false}};
  const std::string out = svg::pareto_svg(spec);
  EXPECT_NE(out.find("no level with a CPU time"), std::string::npos);
  EXPECT_NE(out.find("t &lt;1&gt;"), std::string::npos);
  EXPECT_EQ(out.find("<g class=\"point"), std::string::npos);
}

TEST(SvgPareto, FasterPointsAreRightAndMoreAccurateOnesLowerAndLabelsAreEscaped) {
  svg::ParetoSpec spec;
  spec.title = "speed <&>";
  spec.note = "note \"1\"";
  spec.x_label = "cycles / CPU s <log>";
  spec.y_label = "GOSPA / m <mean>";
  spec.points = {{"<slow>", 1e3, 0.5, true}, {"fast&rough", 1e5, 2.0, false}};
  spec.noise_floor_m = 0.3;
  const std::string out = svg::pareto_svg(spec);
  EXPECT_EQ(out.rfind("<svg", 0), 0u);
  EXPECT_EQ(out.substr(out.size() - 6), "</svg>");
  for (const char* raw : {"<slow>", "fast&rough", "speed <&>", "note \"1\"", "<log>", "<mean>"}) {
    EXPECT_EQ(out.find(raw), std::string::npos) << raw;
  }
  for (const char* escaped : {"&lt;slow&gt;", "fast&amp;rough", "speed &lt;&amp;&gt;", "note &quot;1&quot;",
                              "cycles / CPU s &lt;log&gt;", "GOSPA / m &lt;mean&gt;"}) {
    EXPECT_NE(out.find(escaped), std::string::npos) << escaped;
  }
  EXPECT_NE(out.find("class=\"point front default\" data-level=\"&lt;slow&gt;\""), std::string::npos);
  // Both points are on the front; the first marker after each point's group opens at its screen position.
  const std::regex marker_re(R"re(data-level="([^"]*)"><title>[^<]*</title><circle cx="([-0-9.]+)" cy="([-0-9.]+)")re");
  std::map<std::string, std::pair<double, double>> at;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), marker_re); it != std::sregex_iterator(); ++it) {
    at[(*it)[1]] = {std::stod((*it)[2]), std::stod((*it)[3])};
  }
  ASSERT_EQ(at.size(), 2u) << out;
  EXPECT_LT(at["&lt;slow&gt;"].first, at["fast&amp;rough"].first);   // slower: further left
  EXPECT_GT(at["&lt;slow&gt;"].second, at["fast&amp;rough"].second);  // smaller error: lower on screen
}

}  // namespace
}  // namespace rcsim::replay
