// The fluctuation stage of `rcsim profile derive` (replay/profile/fluctuation.cpp, declared in
// derivation_stages.hpp): re-detections made to follow each model's curve (by its formula, worked
// by hand at a few margins) are told apart, a plateau below 1 is read back, and too little data
// leaves the model to the base.
#include "replay/profile/derivation_stages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace rcsim::replay::profile::fluctuation_test {

// The three curves of fluctuation.cpp's header, for margin m dB (x = 10^(m/10)): at 0 dB all give
// one half; at 10 dB 10/11 = 0.909, 100/121 + 200/1331 = 0.977 and ~1 (Phi(6.7)).
double swerling1(double margin_db) {
  const double x = std::pow(10.0, margin_db / 10.0);
  return x / (1.0 + x);
}
double swerling3(double margin_db) {
  const double x = std::pow(10.0, margin_db / 10.0);
  return std::pow(x / (1.0 + x), 2) + 2.0 * x * x / std::pow(1.0 + x, 3);
}
double steady(double margin_db) { return 0.5 * std::erfc(-margin_db / 1.5 / std::sqrt(2.0)); }

// One frame pair holding, at each 2-dB bin's centre 1, 3, ..., 19 dB, 1000 stationary detections
// of which round(plateau x p(margin) x 1000) are seen again.
std::vector<FramePair> following(double (*p)(double), double plateau = 1.0) {
  FramePair pair;
  for (double margin_db = 1.0; margin_db < 20.0; margin_db += 2.0) {
    const auto seen = std::lround(1000.0 * plateau * p(margin_db));
    for (long i = 0; i < 1000; ++i) pair.redetections.push_back({margin_db, i < seen});
  }
  return {pair};
}

TEST(ProfileFluctuation, EachModelsOwnCurveIsToldApart) {
  for (const auto& [p, name] : std::vector<std::pair<double (*)(double), std::string>>{
           {swerling1, "swerling1"}, {swerling3, "swerling3"}, {steady, "none"}}) {
    std::vector<DerivationFigure> figures;
    const std::vector<DerivedValue> values = derive_fluctuation(following(p), false, figures);
    ASSERT_EQ(values.size(), 1u) << name;
    EXPECT_EQ(values[0].field, "detection.fluctuation");
    EXPECT_EQ(values[0].source, ValueSource::derived) << name;
    EXPECT_EQ(values[0].value, name) << values[0].evidence;
    EXPECT_EQ(values[0].support, 10000) << name;
    // The fit is exact to the counts' rounding: plateau 1, RMS below 0.001.
    EXPECT_NE(values[0].evidence.find(name + " fits best (RMS 0.000, plateau 1.00;"), std::string::npos) << values[0].evidence;
    // The figure: measured per bin (10), and each model's curve.
    ASSERT_EQ(figures.size(), 1u);
    ASSERT_EQ(figures[0].series.size(), 4u);
    EXPECT_EQ(figures[0].series[0].points.size(), 10u);
  }
  // Swerling 1 at 1 dB: 10^0.1 = 1.2589, 1.2589 / 2.2589 = 0.557 seen again; at 19 dB 0.988.
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_fluctuation(following(swerling1), false, figures);
  EXPECT_NE(values[0].evidence.find("10000 stationary detections followed to the next cycle: seen again 0.56 at 1 dB over the "
                                    "threshold, 0.99 at 19 dB"),
            std::string::npos)
      << values[0].evidence;
}

TEST(ProfileFluctuation, MatchingLossesShowAsThePlateau) {
  // Swerling 3 with a fifth of the matches lost whatever the margin: still Swerling 3, plateau 0.80.
  std::vector<DerivationFigure> figures;
  const std::vector<DerivedValue> values = derive_fluctuation(following(swerling3, 0.8), false, figures);
  ASSERT_EQ(values.size(), 1u);
  EXPECT_EQ(values[0].value, "swerling3") << values[0].evidence;
  EXPECT_NE(values[0].evidence.find("plateau 0.80"), std::string::npos) << values[0].evidence;
}

TEST(ProfileFluctuation, TooLittleDataOrSingleFramesLeaveTheModelToTheBase) {
  std::vector<DerivationFigure> figures;
  // Bins must reach from within 4 dB of the threshold to 14 dB or more: 1 to 13 dB falls short.
  std::vector<FramePair> short_reach = following(swerling1);
  std::erase_if(short_reach[0].redetections, [](const Redetection& r) { return r.margin_db > 13.0; });
  std::vector<DerivedValue> values = derive_fluctuation(short_reach, false, figures);
  ASSERT_EQ(values.size(), 1u);
  EXPECT_EQ(values[0].source, ValueSource::base);
  EXPECT_TRUE(values[0].value.is_null());
  EXPECT_EQ(values[0].evidence,
            "too few stationary detections matched from cycle to cycle (7000 in 7 bins of 2 dB with 30 or more)");
  // 29 in a bin are too few for it: none of 10 bins counts.
  FramePair sparse;
  for (double margin_db = 1.0; margin_db < 20.0; margin_db += 2.0) {
    for (int i = 0; i < 29; ++i) sparse.redetections.push_back({margin_db, true});
  }
  values = derive_fluctuation({sparse}, false, figures);
  EXPECT_EQ(values[0].evidence, "too few stationary detections matched from cycle to cycle (290 in 0 bins of 2 dB with 30 or more)");
  values = derive_fluctuation({}, true, figures);
  EXPECT_EQ(values[0].evidence, "not observable: single frames, none follows another");
  EXPECT_TRUE(figures.empty());
}

}  // namespace rcsim::replay::profile::fluctuation_test
