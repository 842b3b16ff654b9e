// The speed-against-error plot (replay/report/svg_pareto.hpp): the Pareto front by hand,
// superscript labels of the log axis, a plot with nothing to draw. The placed plot itself is
// checked in speed_error_section_test.cpp on a stored bench.
#include "replay/report/svg_pareto.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace rcsim::replay
