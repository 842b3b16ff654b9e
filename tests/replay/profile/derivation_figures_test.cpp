// The figures of `rcsim profile derive --report` (replay/profile/derivation_figures.hpp): a
// histogram's bins counted by hand, with what lies outside in the end bins, and the thinning.
#include "replay/profile/derivation_figures.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace rcsim::replay::profile::derivation_figures_test {

TEST(ProfileDerivationFigures, AHistogramCountsByHandWithWhatLiesOutsideInTheEndBins) {
  // [0, 4) in 4 bins of 1: 0.1, 0.5, 0.99 and -1 (below: the first bin) | 1.0 (a bin's lower
  // edge belongs to it) | 2.5 | 3.999 and 7 (beyond: the last bin).
  const DerivationFigure f =
      histogram_figure("gaps", "gap / m", {0.1, 0.5, 0.99, -1.0, 1.0, 2.5, 3.999, 7.0}, 4.0, 4, 1.5, "cell");
  EXPECT_EQ(f.title, "gaps");
  EXPECT_EQ(f.x_label, "gap / m");
  EXPECT_EQ(f.y_label, "pairs");
  EXPECT_DOUBLE_EQ(f.lo, 0.0);
  EXPECT_DOUBLE_EQ(f.bin_width, 1.0);
  EXPECT_EQ(f.counts, (std::vector<long long>{4, 1, 1, 2}));
  EXPECT_DOUBLE_EQ(f.marker, 1.5);
  EXPECT_EQ(f.marker_label, "cell");
  EXPECT_TRUE(f.series.empty());
  // No values: every bin empty; 60 bins over 3: width 0.05.
  const DerivationFigure empty = histogram_figure("t", "x", {}, 3.0, 60, 0.0, "");
  EXPECT_EQ(empty.counts, std::vector<long long>(60, 0));
  EXPECT_DOUBLE_EQ(empty.bin_width, 0.05);
}

TEST(ProfileDerivationFigures, ThinningKeepsEveryKthFromTheFirst) {
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i < 10; ++i) points.emplace_back(i, 10.0 * i);
  // 10 points, at most 3: every ceil(10 / 3) = 4th: 0, 4, 8.
  using Points = std::vector<std::pair<double, double>>;
  EXPECT_EQ(thinned(points, 3), (Points{{0, 0}, {4, 40}, {8, 80}}));
  // At most 5: every 2nd, exactly 5.
  EXPECT_EQ(thinned(points, 5).size(), 5u);
  EXPECT_EQ(thinned(points, 5).back(), (std::pair<double, double>{8, 80}));
  // At most 9: every 2nd as well (never more than asked), 5 points.
  EXPECT_EQ(thinned(points, 9).size(), 5u);
  // As many or fewer: all, unchanged.
  EXPECT_EQ(thinned(points, 10), points);
  EXPECT_EQ(thinned({}, 4000), Points{});
}

}  // namespace rcsim::replay::profile::derivation_figures_test
