// The view-field stage of `rcsim profile derive` (replay/profile/view_field.cpp, declared in
// derivation_stages.hpp) and its rounding, on detection sets laid out in code: the quantiles are
// order statistics picked by hand.
#include "replay/profile/derivation_stages.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "common/angles.hpp"

namespace rcsim::replay::profile::view_field_test {

// 1001 detections in two cycles, the i-th at azimuth_deg(i) and range_m(i).
template <class Azimuth, class Range>
DetectionPool laid_out(Azimuth azimuth_deg, Range range_m) {
  DetectionPool pool;
  pool.cycles.resize(2);
  for (int i = 0; i <= 1000; ++i) {
    PooledDetection d;
    d.azimuth_rad = deg_to_rad(azimuth_deg(i)), d.range_m = range_m(i);
    pool.cycles[static_cast<std::size_t>(i % 2)].detections.push_back(d);
  }
  pool.detections = 1001;
  return pool;
}

TEST(ProfileViewField, RoundsToTheNearestMultipleOfTheStep) {
  EXPECT_DOUBLE_EQ(round_to(1.234, 0.01), 1.23);
  EXPECT_DOUBLE_EQ(round_to(16.26, 0.5), 16.5);
  EXPECT_DOUBLE_EQ(round_to(2.5, 1.0), 3.0);     // halves away from zero
  EXPECT_DOUBLE_EQ(round_to(-0.25, 0.5), -0.5);  // -0.5 steps: away from zero as well
  EXPECT_DOUBLE_EQ(round_to(0.0554, 0.0001), 0.0554);
}

TEST(ProfileViewField, TheNearerSideAndTheFarRangeByQuantileTheNearestWhereItIsNear) {
  // Azimuths -10 + 0.03 i deg (-10 to 20: wider to the left), ranges 2 + 0.1 i m. Of 1001 sorted
  // values the 0.1 % quantile is the 2nd (h = 0.001 x 1000 = 1), the 99.9 % the 1000th: azimuth
  // -9.97 and 19.97 deg, the nearer 9.97 -> 10 (0.5 deg steps); range 101.9 -> 102 m. The nearest,
  // 2 m, lies within 5 % of 101.9 m: the radar's minimum range, to 0.1 m below.
  const DetectionPool pool = laid_out([](int i) { return -10.0 + 0.03 * i; }, [](int i) { return 2.0 + 0.1 * i; });
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_view_field(pool, figures);
  ASSERT_EQ(values.size(), 3u);
  EXPECT_EQ(values[0].field, "field_of_view.azimuth_half_deg");
  EXPECT_DOUBLE_EQ(values[0].value.get<double>(), 10.0);
  EXPECT_EQ(values[0].source, ValueSource::derived);
  EXPECT_EQ(values[0].support, 1001);
  EXPECT_EQ(values[0].evidence, "the nearer of the 0.1 % and 99.9 % quantiles of azimuth, -9.97 and 19.97 deg (outermost -10.00 and 20.00)");
  EXPECT_EQ(values[1].field, "field_of_view.max_range_m");
  EXPECT_DOUBLE_EQ(values[1].value.get<double>(), 102.0);
  EXPECT_EQ(values[1].evidence, "99.9 % quantile of range 101.9 m (largest 102.0)");
  EXPECT_EQ(values[2].field, "field_of_view.min_range_m");
  EXPECT_EQ(values[2].source, ValueSource::derived);
  EXPECT_DOUBLE_EQ(values[2].value.get<double>(), 2.0);
  // The figure: every detection, and the view field's outline at the rounded values.
  ASSERT_EQ(figures.size(), 1u);
  ASSERT_EQ(figures[0].series.size(), 2u);
  EXPECT_EQ(figures[0].series[0].points.size(), 1001u);
  EXPECT_EQ(figures[0].series[1].points,
            (std::vector<std::pair<double, double>>{{-10.0, 0.0}, {-10.0, 102.0}, {10.0, 102.0}, {10.0, 0.0}}));
}

TEST(ProfileViewField, ANearestDetectionFarFromTheRadarLeavesTheMinimumRangeToTheBase) {
  // Ranges 10 + 0.1 i: the nearest is 10 m, 9 % of the 99.9 % quantile 109.9 m (more than 5 %):
  // the scene kept away, not the radar. Azimuths symmetric, -15 + 0.03 i: +-14.97 -> 15 deg.
  const DetectionPool pool = laid_out([](int i) { return -15.0 + 0.03 * i; }, [](int i) { return 10.0 + 0.1 * i; });
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_view_field(pool, figures);
  ASSERT_EQ(values.size(), 3u);
  EXPECT_DOUBLE_EQ(values[0].value.get<double>(), 15.0);
  EXPECT_DOUBLE_EQ(values[1].value.get<double>(), 110.0);
  EXPECT_EQ(values[2].field, "field_of_view.min_range_m");
  EXPECT_EQ(values[2].source, ValueSource::base);
  EXPECT_TRUE(values[2].value.is_null());
  EXPECT_EQ(values[2].support, 0);
  EXPECT_EQ(values[2].evidence,
            "not observable: the nearest detection is 10.0 m, 9 % of the farthest (the scene keeps away, not the radar)");
}

}  // namespace rcsim::replay::profile::view_field_test
