// Escaping, number formatting and round axis ticks (replay/report/svg_writer.hpp).
#include "replay/report/svg_writer.hpp"

#include <gtest/gtest.h>


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

}  // namespace
}  // namespace rcsim::replay
