// Time series and histograms as SVG (replay/report/svg_plot.hpp): gaps break lines, labels are escaped, outliers are clamped into the end bins.
#include "replay/report/svg_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

std::size_t count(const std::string& text, const std::string& needle) { return testing::count_occurrences(text, needle); }

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
  EXPECT_EQ(count(m[1], "M"), 2u);
  EXPECT_EQ(count(m[1], "L"), 2u);
  EXPECT_NE(out.find("T &lt;1&gt;"), std::string::npos);
  EXPECT_NE(out.find(">range / m<"), std::string::npos);
  EXPECT_NE(out.find(">t / s<"), std::string::npos);
}

TEST(SvgPlot, HistogramClampsOutliersIntoTheEndBins) {
  svg::HistogramSpec h;
  h.title = "r";
  h.x_label = "range / m";
  h.lo = -1.0;
  h.bin_width = 0.5;
  h.counts = {3, 1, 0, 2};
  h.below = 2;
  h.above = 1;
  const std::string out = svg::histogram_svg(h);
  EXPECT_EQ(count(out, "<rect class=\"bar\""), 3u);
  EXPECT_NE(out.find("2 below / 1 above"), std::string::npos);
}

}  // namespace
}  // namespace rcsim::replay
