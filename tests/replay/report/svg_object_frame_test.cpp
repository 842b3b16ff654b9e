// The targets of one object drawn in its own frame (replay/report/svg_object_frame.hpp): the
// scale, the box and its front edge, the recorded dots under the simulated diamonds, the targets
// beyond the plot clamped to its edge, the notes pushing the plot down, and the escaping, by hand.
#include "replay/report/svg_object_frame.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rcsim::svg_object_frame_test {

using replay::svg::object_frame_svg;
using replay::svg::ObjectFrameSpec;

// A 4.5 m x 1.8 m car; the plot spans +-(2.25 + 1.5) = +-3.75 m over 240 px: 32 px per metre.
// Without notes the plot area starts at (44, 34): x_px = 44 + (3.75 - y_m) 32 (y to the left),
// y_px = 274 - (x_m + 3.75) 32 (x up).
ObjectFrameSpec car_spec() {
  ObjectFrameSpec spec;
  spec.title = "car";
  spec.length_m = 4.5;
  spec.width_m = 1.8;
  return spec;
}

TEST(SvgObjectFrame, TheBoxAndItsFrontEdgeByHand) {
  const std::string svg = object_frame_svg(car_spec());
  // 44 + 240 + 12 = 296 wide, 34 + 240 + 58 = 332 high.
  EXPECT_NE(svg.find(R"(width="296" height="332" viewBox="0 0 296 332")"), std::string::npos) << svg;
  // Box corners: y = +0.9 -> 44 + 2.85 * 32 = 135.2; x = +2.25 -> 274 - 6 * 32 = 82; 1.8 m = 57.6 px,
  // 4.5 m = 144 px.
  EXPECT_NE(svg.find(R"(<rect class="box" x="135.2" y="82" width="57.6" height="144")"), std::string::npos) << svg;
  // The front edge along x = +2.25 from y = +0.9 to y = -0.9.
  EXPECT_NE(svg.find(R"(<line class="front" x1="135.2" y1="82" x2="192.8" y2="82")"), std::string::npos) << svg;
  // Ticks at round metres, 0 in the middle: x_px(0) = 164, y_px(0) = 154.
  EXPECT_NE(svg.find(R"(<text x="164" y="287" text-anchor="middle">0</text>)"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(<text x="40" y="157" text-anchor="end">0</text>)"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("<circle"), std::string::npos);
  EXPECT_EQ(svg.find("<polygon"), std::string::npos);
}

TEST(SvgObjectFrame, RecordedDotsComeBeforeSimulatedDiamondsAndFarTargetsAreClamped) {
  ObjectFrameSpec spec = car_spec();
  spec.targets = {{{0.0, -0.9}, true},    // the right side's middle, simulated: (192.8, 154)
                  {{2.25, 0.0}, false},   // the front's middle, recorded: (164, 82)
                  {{10.0, 10.0}, false}}; // far ahead and left: clamped to the top-left corner (44, 34)
  const std::string svg = object_frame_svg(spec);
  const auto front = svg.find(R"(<circle class="t rec" cx="164" cy="82")");
  const auto far = svg.find(R"(<circle class="t rec" cx="44" cy="34")");
  const auto side = svg.find(R"(<polygon class="t sim" points="192.8,150 196.8,154 192.8,158 188.8,154")");
  ASSERT_NE(front, std::string::npos) << svg;
  ASSERT_NE(far, std::string::npos) << svg;
  ASSERT_NE(side, std::string::npos) << svg;
  EXPECT_LT(front, far) << "recorded in the given order";
  EXPECT_LT(far, side) << "the simulated diamonds drawn over the recorded dots";
}

TEST(SvgObjectFrame, NotesPushThePlotDownAndTextIsEscaped) {
  ObjectFrameSpec spec = car_spec();
  spec.title = "car <b>&</b>";
  spec.notes = {"12 cycles", "id \"x\""};
  const std::string svg = object_frame_svg(spec);
  // Two notes: the plot starts 2 x 14 px lower, at 62; 62 + 240 + 58 = 360 high.
  EXPECT_NE(svg.find(R"(height="360")"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(<rect class="box" x="135.2" y="110" width="57.6" height="144")"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(<text x="44" y="32" class="note">12 cycles</text>)"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(<text x="44" y="46" class="note">id &quot;x&quot;</text>)"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(aria-label="car &lt;b&gt;&amp;&lt;/b&gt;")"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
}

TEST(SvgObjectFrame, ASmallObjectKeepsAtLeastTwoMetresEachSide) {
  ObjectFrameSpec spec;
  spec.title = "post";
  spec.length_m = 0.2;
  spec.width_m = 0.2;
  spec.size_px = 200;
  // max(0.1 + 1.5, 2) = 2 m each side over 200 px: 50 px per metre; the 0.2 m box is 10 px,
  // its corner at x_px = 44 + (2 - 0.1) 50 = 139, y_px = 234 - (0.1 + 2) 50 = 129.
  const std::string svg = object_frame_svg(spec);
  EXPECT_NE(svg.find(R"(<rect class="box" x="139" y="129" width="10" height="10")"), std::string::npos) << svg;
  EXPECT_NE(svg.find(R"(width="256" height="292")"), std::string::npos) << svg;
}

}  // namespace rcsim::svg_object_frame_test
