// The page of `rcsim profile derive --report` (replay/report/profile_report.hpp), from a
// derivation made by hand: the header and counts, one row per value with its source, evidence and
// support, a histogram per histogram figure (its value marked, no zero line) and a plot per plot
// figure (its series coloured in turn), every text escaped.
#include "replay/report/profile_report.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "replay/replay_fixtures.hpp"

namespace rcsim::profile_report_test {

using replay::profile::DerivationFigure;
using replay::profile::DerivedValue;
using replay::profile::FigureSeries;
using replay::profile::ProfileDerivation;
using replay::profile::ValueSource;
using testing::count_occurrences;

ProfileDerivation hand_derivation() {
  ProfileDerivation d;
  d.profile = {{"name", "radar <1>"}};
  d.base = "srr24 & co";
  d.detections = 1200;
  d.sensor_cycles = 40;
  d.values = {
      replay::profile::with_interval({"field_of_view.azimuth_half_deg", 16.8, ValueSource::derived, "99.9 % quantile of |azimuth| <x>", 1180},
                                     16.5, 17.2, true),
      {"cycle_time_s", 0.05, ValueSource::recording, "header", 0},
      {"noise", nlohmann::json{{"a", 1}}, ValueSource::base, "", 0},
  };
  return d;
}

std::string page_of(const ProfileDerivation& d, const std::string& profile_file) {
  std::ostringstream out;
  replay::write_profile_report(out, d, profile_file);
  return out.str();
}

TEST(ProfileReport, HeaderAndOneRowPerValueEscaped) {
  const std::string html = page_of(hand_derivation(), "out/<p>.json");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>\n", 0), 0u);
  EXPECT_NE(html.find("<title>rcsim profile derive: radar &lt;1&gt;</title>"), std::string::npos) << html;
  EXPECT_NE(html.find("<h1>Sensor profile radar &lt;1&gt;, derived from recordings</h1>"), std::string::npos);
  EXPECT_NE(html.find("<p class=\"meta\">1200 detections in 40 sensor cycles; base srr24 &amp; co; written to "
                      "out/&lt;p&gt;.json."),
            std::string::npos)
      << html;
  // A derived value with its support; a value of the header and one of the base without (support 0
  // leaves the cell empty); a JSON value as JSON, escaped.
  EXPECT_NE(html.find("<tr><td>field_of_view.azimuth_half_deg</td><td class=\"num\">16.8</td><td>derived, weak</td>"
                      "<td class=\"num\">[16.5, 17.2]</td><td>99.9 % quantile of |azimuth| &lt;x&gt;</td><td class=\"num\">1180</td></tr>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<tr><td>cycle_time_s</td><td class=\"num\">0.05</td><td>recording</td><td class=\"num\"></td><td>header</td>"
                      "<td class=\"num\"></td></tr>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<tr><td>noise</td><td class=\"num\">{&quot;a&quot;:1}</td><td>base</td><td class=\"num\"></td><td></td>"),
            std::string::npos)
      << html;
  EXPECT_EQ(html.find("<x>"), std::string::npos);
  EXPECT_EQ(html.find("<svg"), std::string::npos) << "no figure, no picture";
  EXPECT_NE(html.find("</body></html>\n"), std::string::npos);
}

TEST(ProfileReport, AHistogramWithItsValueMarkedAndAPlotWithItsSeriesColouredInTurn) {
  ProfileDerivation d = hand_derivation();
  DerivationFigure histogram;
  histogram.title = "pair distance";
  histogram.x_label = "d / m";
  histogram.y_label = "pairs";
  histogram.lo = -1.0;  // the axis spans 0: a residual histogram would draw its zero line there
  histogram.bin_width = 1.0;
  histogram.counts = {1, 3, 2};
  histogram.marker = 0.5;
  histogram.marker_label = "cell 0.5 m";
  DerivationFigure plot;
  plot.title = "SNR against range";
  plot.x_label = "r / m";
  plot.y_label = "SNR / dB";
  for (int i = 0; i < 4; ++i) {
    plot.series.push_back(FigureSeries{"series " + std::to_string(i), i == 0, {{1.0, 1.0 + i}, {2.0, 2.0 + i}}});
  }
  d.figures = {histogram, plot};
  const std::string html = page_of(d, "p.json");
  EXPECT_EQ(count_occurrences(html, "<svg class=\"histogram\""), 1u);
  EXPECT_EQ(count_occurrences(html, "<svg class=\"plot\""), 1u);
  EXPECT_LT(html.find("aria-label=\"pair distance\""), html.find("aria-label=\"SNR against range\""));
  EXPECT_EQ(count_occurrences(html, "class=\"marker\""), 1u);
  EXPECT_NE(html.find(">cell 0.5 m</text>"), std::string::npos);
  EXPECT_EQ(html.find("stroke-dasharray=\"3 3\""), std::string::npos) << "no zero line";
  // Blue dots, then orange and green lines, then blue again.
  EXPECT_NE(html.find("<path class=\"series dots\" d=\"M"), std::string::npos);
  const auto first = html.find("class=\"series dots\"");
  const auto second = html.find("class=\"series line\"", first);
  const auto third = html.find("class=\"series line\"", second + 1);
  const auto fourth = html.find("class=\"series line\"", third + 1);
  ASSERT_NE(fourth, std::string::npos) << html;
  const auto colour_at = [&](std::size_t at) { return html.substr(html.find("stroke=\"", at) + 8, 7); };
  EXPECT_EQ(colour_at(first), "#1f5fbf");
  EXPECT_EQ(colour_at(second), "#d9480f");
  EXPECT_EQ(colour_at(third), "#2b8a3e");
  EXPECT_EQ(colour_at(fourth), "#1f5fbf");
}

}  // namespace rcsim::profile_report_test
