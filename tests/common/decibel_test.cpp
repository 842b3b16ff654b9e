// The one decibel helper (common/decibel.hpp): L = 20 log10 a for amplitudes, 10 log10 p for
// powers (paper III-B), by hand.
#include "common/decibel.hpp"

#include <gtest/gtest.h>

namespace rcsim {
namespace {

TEST(Decibel, ConversionsByHand) {
  EXPECT_NEAR(amplitude_to_db(10.0), 20.0, 1e-13);
  EXPECT_NEAR(amplitude_to_db(0.5), -6.020599913279624, 1e-13);
  EXPECT_NEAR(db_to_amplitude(-6.0), 0.5011872336272722, 1e-15);
  EXPECT_NEAR(db_to_amplitude(26.5), 21.134890398366466, 1e-13);
  // From the squared amplitude: the same level without the square root.
  for (const double a : {1e-3, 0.5, 1.0, 3.7, 250.0}) {
    EXPECT_NEAR(power_to_db(a * a), amplitude_to_db(a), 1e-12) << a;
    EXPECT_NEAR(db_to_amplitude(amplitude_to_db(a)) / a, 1.0, 1e-14) << a;  // a few ulp through exp and log
  }
}

TEST(Decibel, PowerLevelsByHand) {
  EXPECT_NEAR(power_to_db(100.0), 20.0, 1e-13);
  EXPECT_NEAR(db_to_power(-3.0), 0.5011872336272722, 1e-15);
  // A power level and the amplitude level of its square root agree.
  for (const double level_db : {-40.0, -6.0, 0.0, 13.5}) {
    EXPECT_NEAR(db_to_power(level_db), db_to_amplitude(level_db) * db_to_amplitude(level_db), 1e-12 * db_to_power(level_db));
  }
}

}  // namespace
}  // namespace rcsim
