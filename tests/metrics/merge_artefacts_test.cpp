#include "metrics/merge_artefacts.hpp"

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

TEST(MergeArtefacts, TargetBetweenTwoCarsInOneCellIsAnArtefact) {
  // Two boxes side by side at equal range (paper Fig. 10); nearest points at azimuth ±atan(2/10).
  const std::vector<BoxInSensor> boxes{box_at(0, 12.0, 3.0), box_at(1, 12.0, -3.0)};
  const MergeParameters parameters;
  const auto pairs = merge_pairs(boxes, parameters);
  ASSERT_EQ(pairs.size(), 1u);
  const Vec2 between(10.0, 0.0);
  EXPECT_EQ(merge_artefact_of(boxes, pairs, 10.0, 0.0, between, parameters), 0);
  // On a contour, beside the pair, or a cell away in range: not an artefact.
  EXPECT_EQ(merge_artefact_of(boxes, pairs, 10.05, std::atan2(2.2, 10.0), Vec2(10.0, 2.2), parameters), -1);
  EXPECT_EQ(merge_artefact_of(boxes, pairs, 10.5, -0.6, Vec2(8.6, -5.9), parameters), -1);
  EXPECT_EQ(merge_artefact_of(boxes, pairs, 11.0, 0.0, Vec2(11.0, 0.0), parameters), -1);
}

TEST(MergeArtefacts, DifferentRangesOrSpeedsShareNoCell) {
  const MergeParameters parameters;
  EXPECT_TRUE(merge_pairs({box_at(0, 12.0, 3.0), box_at(1, 12.5, -3.0)}, parameters).empty());
  BodyState ego, moving;
  moving.X_WB = {12.0, -3.0, 0.0};
  moving.v_WB_W = Vec2(1.0, 0.0);  // 1 m/s apart in range rate: two cells
  const std::vector<BoxInSensor> boxes{box_at(0, 12.0, 3.0), box_in_sensor(1, Pose2{0, 0, 0}, ego, moving, 4.0, 2.0)};
  EXPECT_TRUE(merge_pairs(boxes, parameters).empty());
}

}  // namespace
}  // namespace rcsim::metrics
