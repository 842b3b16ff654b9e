#include "metrics/merge_artefacts.hpp"
#include "metrics/sensor_view.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::metrics {
namespace {

// A standing sensor at the origin looking along +x; standing boxes.
BoxInSensor box_at(int object, double x_m, double y_m, double length_m = 4.0, double width_m = 2.0) {
  BodyState ego, obj;
  obj.X_WB = {x_m, y_m, 0.0};
  return box_in_sensor(object, Pose2{0.0, 0.0, 0.0}, ego, obj, length_m, width_m);
}

TEST(SensorView, NearestContourPointRangeAndRate) {
  const BoxInSensor box = box_at(0, 12.0, 0.0);  // rear face at x = 10
  EXPECT_DOUBLE_EQ(box.range_m, 10.0);
  EXPECT_DOUBLE_EQ(box.azimuth_rad, 0.0);
  EXPECT_DOUBLE_EQ(distance_to_box_m(box, Vec2(13.0, 4.0)), 3.0);
  EXPECT_DOUBLE_EQ(distance_to_box_m(box, Vec2(11.0, 0.5)), 0.0);
  EXPECT_NEAR(distance_to_box_m(box, Vec2(7.0, 5.0)), 5.0, 1e-12);  // from the corner (10, 1)
  // An object approaching at 3 m/s along -x: range rate -3 m/s.
  BodyState ego, obj;
  obj.X_WB = {12.0, 0.0, 0.0};
  obj.v_WB_W = Vec2(-3.0, 0.0);
  EXPECT_DOUBLE_EQ(box_in_sensor(0, Pose2{0, 0, 0}, ego, obj, 4.0, 2.0).range_rate_mps, -3.0);
}

TEST(SensorView, NearestBoxWithinTheGate) {
  const std::vector<BoxInSensor> boxes{box_at(4, 12.0, 3.0), box_at(7, 12.0, -3.0)};
  EXPECT_EQ(nearest_box(boxes, Vec2(10.5, -2.5), 1.0), 1);
  EXPECT_EQ(nearest_box(boxes, Vec2(10.5, 0.0), 1.0), -1);  // 2 m from both
}

// A cell shared by objects 0 and 1 (paper Fig. 10): at 10 m, -2 m/s, their echoes at azimuths
// -0.2 and +0.2 rad. srr24's cells: 0.3 m, 0.5 m/s. The cars' boxes (4 m x 2 m, rear faces at
// x = 10) stand at y = +-3.5, so the gap between them is |y| < 2.5.
const MergeCell kCell{0, 1, 10.0, -2.0, -0.2, 0.2};

std::vector<BoxInSensor> two_cars() { return {box_at(0, 12.0, -3.5), box_at(1, 12.0, 3.5)}; }

// A target at (range, azimuth) with its Cartesian position.
int artefact(double range_m, double range_rate_mps, double azimuth_rad, const std::vector<MergeCell>& cells = {kCell}) {
  const Vec2 p(range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad));
  return merge_artefact_of(cells, two_cars(), range_m, range_rate_mps, azimuth_rad, p, MergeParameters{});
}

TEST(MergeArtefacts, ATargetInTheCellBetweenAndOffBothBoxesIsAnArtefact) {
  EXPECT_EQ(artefact(10.1, -2.1, 0.0), 0);     // 2.5 m from both boxes
  EXPECT_EQ(artefact(10.29, -2.0, 0.19), 0);   // (10.10, 1.94): 0.56 m from the left box
  // (9.91, 2.43): 0.12 m from the left box's corner (10, 2.5), inside the margin (a wider span).
  EXPECT_EQ(artefact(10.2, -2.0, 0.24, {MergeCell{0, 1, 10.0, -2.0, -0.3, 0.3}}), -1);
  EXPECT_EQ(artefact(10.31, -2.0, 0.0), -1);   // beyond one range cell
  EXPECT_EQ(artefact(10.0, -2.0, -0.21), -1);  // outside the echoes' span
  EXPECT_EQ(artefact(10.0, -2.0, 0.0, {}), -1);
}

TEST(MergeArtefacts, AWrongSpeedIsNotAnArtefact) {
  EXPECT_EQ(artefact(10.0, -2.0 + 20.0, 0.0), -1);  // +20 m/s: another cell
  EXPECT_EQ(artefact(10.0, -2.45, 0.0), 0);         // within one range-rate cell
  EXPECT_EQ(artefact(10.0, -2.55, 0.0), -1);
}

TEST(MergeArtefacts, TwoArtefactsOfOnePairMatchByPosition) {
  const std::vector<Vec2> recorded{{10.0, 0.5}, {10.0, -0.5}};
  // One simulated artefact 0.11 m from the first, one 1.1 m from it and 2.1 m from the second.
  EXPECT_EQ(matched_artefacts(recorded, {{10.1, 0.45}, {10.0, 1.6}}, 1.0), 1);
  EXPECT_EQ(matched_artefacts(recorded, {{10.1, 0.45}, {10.2, -0.3}}, 1.0), 2);
  // Counting would have said 2 for both; neither is near: 0.
  EXPECT_EQ(matched_artefacts(recorded, {{12.0, 0.0}, {8.0, 0.0}}, 1.0), 0);
  EXPECT_EQ(matched_artefacts(recorded, {}, 1.0), 0);
}

}  // namespace
}  // namespace rcsim::metrics
