// Escaping, number formatting and round axis ticks (replay/report/svg_writer.hpp).
#include "replay/report/svg_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::replay {
namespace {

TEST(SvgWriter, EscapesMarkupAndQuotes) {
  EXPECT_EQ(svg::escape("<script>alert(1)</script> & \"x\""), "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;x&quot;");
  EXPECT_EQ(svg::escape("a'b"), "a&#39;b");
  EXPECT_EQ(svg::escape("plain"), "plain");
}

TEST(SvgWriter, TicksAreRoundAndCoverTheInterval) {
  const svg::Ticks t = svg::nice_ticks(0.3, 9.7, 5);
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  ASSERT_EQ(t.values.size(), 4u);
  EXPECT_DOUBLE_EQ(t.values.front(), 2.0);
  EXPECT_DOUBLE_EQ(t.values.back(), 8.0);
  const svg::Ticks small = svg::nice_ticks(-0.012, 0.013, 5);
  EXPECT_DOUBLE_EQ(small.step, 0.005);
  EXPECT_EQ(small.decimals, 3);
  EXPECT_EQ(svg::fixed(-0.0001, 2), "0.00");
  EXPECT_EQ(svg::coord(-0.01), "0");
}

TEST(SvgWriter, ShortenCountsCodePointsNotBytes) {
  EXPECT_EQ(svg::shorten("abcdef", 3), "abc\u2026");
  EXPECT_EQ(svg::shorten("abc", 3), "abc");
  EXPECT_EQ(svg::shorten("\u00e4\u00f6\u00fc\u00df", 2), "\u00e4\u00f6\u2026");  // never cuts a character in two
  EXPECT_EQ(svg::shorten("", 0), "");
}

TEST(SvgWriter, FixedDashesNaNAndScalesMapLinearly) {
  EXPECT_EQ(svg::fixed(std::nan(""), 2), "\u2013");
  EXPECT_EQ(svg::fixed(1.005, 0), "1");
  EXPECT_EQ(svg::coord(12.34), "12.3");
  EXPECT_EQ(svg::coord(3.0), "3");
  const svg::LinearScale down{0.0, 10.0, 100.0, 0.0};  // a y axis: larger values higher on screen
  EXPECT_DOUBLE_EQ(down(0.0), 100.0);
  EXPECT_DOUBLE_EQ(down(2.5), 75.0);
}

TEST(SvgWriter, WidenGivesANonEmptyPaddedInterval) {
  double lo = 2.0, hi = 2.0;
  svg::widen(lo, hi, 1.0, 0.0);
  EXPECT_DOUBLE_EQ(lo, 1.5);
  EXPECT_DOUBLE_EQ(hi, 2.5);
  lo = 0.0, hi = 10.0;
  svg::widen(lo, hi, 1.0, 0.1);
  EXPECT_DOUBLE_EQ(lo, -1.0);
  EXPECT_DOUBLE_EQ(hi, 11.0);
  lo = std::nan(""), hi = 1.0;
  svg::widen(lo, hi, 4.0, 0.0);
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 4.0);
}

}  // namespace
}  // namespace rcsim::replay
