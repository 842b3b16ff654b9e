// Paper eqs. (1)-(3).
#include "sim/amplitude.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim {
namespace {

TEST(Amplitude, ReferenceLawByHand) {
  const AmplitudeLaw law;
  // eq. (1): 26.5 - 0.75 * 10 = 19 dB
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 10.0)), 19.0, 1e-12);
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 0.0)), 26.5, 1e-12);
  // Threshold crossing: 26.5 - 0.75 R = 6  =>  R = 27.333 m
  EXPECT_NEAR(amplitude_to_db(reference_range_amplitude(law, 82.0 / 3.0)), 6.0, 1e-12);
}

TEST(Amplitude, DecibelConversionsByHand) {
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

TEST(Amplitude, EchoOfReferenceReflectorAtBoresight) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  IdealTargets ideal(1);
  ideal[0].range_m = 10.0;
  ideal[0].set_azimuth(0.0);
  ideal[0].ercs = 1.0;
  Echoes echoes;
  compute_echoes(AmplitudeLaw{}, antenna, ideal, echoes);
  ASSERT_EQ(echoes.size(), 1u);
  EXPECT_NEAR(amplitude_to_db(echoes[0].amplitude), 19.0, 1e-12);
}

TEST(Amplitude, EchoScalesWithErcsAndAntennaPattern) {
  const MonopulseAntenna antenna{AntennaGeometry{}};
  IdealTargets ideal(1);
  ideal[0].range_m = 10.0;
  ideal[0].set_azimuth(deg_to_rad(30.0));
  ideal[0].ercs = 2.0;
  Echoes echoes;
  compute_echoes(AmplitudeLaw{}, antenna, ideal, echoes);
  // eq. (3): 19 dB + 20 log10(2) + 20 log10(0.551329) = 19 + 6.0206 - 5.1718 = 19.8488 dB
  EXPECT_NEAR(amplitude_to_db(echoes[0].amplitude), 19.0 + 20 * std::log10(2.0) + 20 * std::log10(0.5513288954), 1e-8);
  // eq. (8) weights the pointers by A_ref^R(R) ERCS only: |delta| / |sum| is the pattern ratio
  const auto h = antenna.pattern(deg_to_rad(30.0));
  EXPECT_NEAR(std::abs(echoes[0].delta_pointer) / std::abs(echoes[0].sum_pointer), std::abs(h.delta) / std::abs(h.sum),
              1e-12);
}

}  // namespace
}  // namespace rcsim
