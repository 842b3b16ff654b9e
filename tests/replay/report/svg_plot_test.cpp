// Time series and histograms as SVG (replay/report/svg_plot.hpp): gaps break lines, labels are escaped, outliers are clamped into the end bins.
#include "replay/report/svg_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {


TEST(SvgPlot, PlotBreaksLinesAtGapsAndLabelsItsAxes) {
  svg::PlotSpec spec;
  spec.title = "T <1>";
  spec.x_label = "t / s";
  spec.y_label = "range / m";
  spec.series.push_back({"a", "#000", false, false, {{0, 1}, {1, 2}, {2, std::nan("")}, {3, 1}, {4, 2}}});
  const std::string out = svg::plot_svg(spec);
  const std::regex line_re("class=\"series line\" d=\"([^\"]*)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, line_re));
  EXPECT_EQ(testing::count_occurrences(m[1], "M"), 2u);
  EXPECT_EQ(testing::count_occurrences(m[1], "L"), 2u);
  EXPECT_NE(out.find("T &lt;1&gt;"), std::string::npos);
  EXPECT_NE(out.find(">range / m<"), std::string::npos);
  EXPECT_NE(out.find(">t / s<"), std::string::npos);
}

TEST(SvgPlot, HistogramClampsOutliersIntoTheEndBins) {
  svg::HistogramSpec h;
  h.title = std::string("r");  // not = "r": GCC 12's false -Wrestrict (bug 105329) in some unity batches
  h.x_label = "range / m";
  h.lo = -1.0;
  h.bin_width = 0.5;
  h.counts = {3, 1, 0, 2};
  h.below = 2;
  h.above = 1;
  const std::string out = svg::histogram_svg(h);
  EXPECT_EQ(testing::count_occurrences(out, "<rect class=\"bar\""), 3u);
  EXPECT_NE(out.find("2 below / 1 above"), std::string::npos);
}

TEST(SvgPlot, EmptyPlotSaysNoDataAndIsAValidSvg) {
  svg::PlotSpec spec;
  spec.title = "empty";
  const std::string out = svg::plot_svg(spec);
  EXPECT_EQ(out.rfind("<svg class=\"plot\"", 0), 0u);
  EXPECT_EQ(out.substr(out.size() - 6), "</svg>");
  EXPECT_EQ(testing::count_occurrences(out, "<g"), testing::count_occurrences(out, "</g>"));
  EXPECT_NE(out.find(">no data</text>"), std::string::npos);
  EXPECT_EQ(testing::count_occurrences(out, "class=\"series"), 0u);
  EXPECT_EQ(out.find("nan"), std::string::npos);
}

TEST(SvgPlot, LargerValuesAreHigherAndLaterOnesFurtherRight) {
  svg::PlotSpec spec;
  spec.series.push_back({"d", "#000", true, false, {{0.0, 1.0}, {10.0, 5.0}}});
  const std::string out = svg::plot_svg(spec);
  std::smatch m;
  const std::regex dots_re(R"re(class="series dots" d="M([-0-9.]+) ([-0-9.]+)h0M([-0-9.]+) ([-0-9.]+)h0")re");
  ASSERT_TRUE(std::regex_search(out, m, dots_re)) << out;
  EXPECT_LT(std::stod(m[1]), std::stod(m[3]));  // t = 0 left of t = 10
  EXPECT_GT(std::stod(m[2]), std::stod(m[4]));  // 1 below 5 (screen y grows downwards)
  EXPECT_NE(out.find("<circle cx="), std::string::npos);  // a dot series has a dot in the legend
  EXPECT_EQ(testing::count_occurrences(out, "no data"), 0u);
}

TEST(SvgPlot, LegendNotesAndHistogramLabelsAreEscaped) {
  svg::PlotSpec spec;
  spec.note = "n <1>";
  spec.series.push_back({"s&\"1\"", "#000", false, true, {{0, 1}, {1, 2}}});
  const std::string plot = svg::plot_svg(spec);
  EXPECT_NE(plot.find(">s&amp;&quot;1&quot;</text>"), std::string::npos);
  EXPECT_NE(plot.find(">n &lt;1&gt;</text>"), std::string::npos);
  EXPECT_EQ(plot.find("s&\""), std::string::npos);
  EXPECT_NE(plot.find("stroke-dasharray=\"6 3\""), std::string::npos);  // a dashed series
  svg::HistogramSpec h;
  h.title = "h <2>";
  h.x_label = "x & y";
  h.note = "'q'";
  h.counts = {1};
  const std::string hist = svg::histogram_svg(h);
  EXPECT_NE(hist.find(">h &lt;2&gt;</text>"), std::string::npos);
  EXPECT_NE(hist.find(">x &amp; y</text>"), std::string::npos);
  EXPECT_NE(hist.find(">&#39;q&#39;</text>"), std::string::npos);
  EXPECT_EQ(hist.find("h <2>"), std::string::npos);
}

}  // namespace
}  // namespace rcsim::replay
