// Hard case of the tracker (III-E): a very long run keeps every covariance symmetric positive
// definite and every state finite.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "common/rng.hpp"
#include "hard_cases/hard_case_support.hpp"
#include "sanitizers.hpp"
#include "sim/tracking.hpp"

namespace rcsim {
namespace {

// 1e6 cycles take about a second in Release; sanitizer builds (ASan/UBSan run the suite too) are
// some ten times slower, so they run 1e5.
constexpr long kLongRunCycles = RCSIM_UNDER_ASAN ? 100'000 : 1'000'000;

void expect_spd(const TrackCovariance& P, long cycle) {
  ASSERT_TRUE(P.allFinite()) << cycle;
  ASSERT_LE((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-9 * P.cwiseAbs().maxCoeff()) << cycle;
  const Eigen::LLT<Eigen::Matrix4d> llt(0.5 * (P + P.transpose()));
  ASSERT_EQ(llt.info(), Eigen::Success) << "not positive definite at cycle " << cycle;
}

TEST(HardCaseTracker, MillionCyclesStaySymmetricPositiveDefinite) {
  const SensorConfig config = builtin_sensor_config("srr24");
  Tracker tracker(config.tracker, config.cycle_time_s);
  Rng rng(7, 0);
  Detections detections;
  ReportedTargets reported;
  detections.reserve(8);
  reported.reserve(static_cast<std::size_t>(config.tracker.max_tracks));
  // One target going back and forth in range, one standing still at the edge of the view field
  // with rare misses, one flickering at the threshold; amplitudes from far below to far above.
  for (long k = 0; k < kLongRunCycles; ++k) {
    const double t_s = static_cast<double>(k) * config.cycle_time_s;
    detections.clear();
    const double r_m = 20.0 + 15.0 * std::sin(0.05 * t_s);
    detections.push_back({r_m + 0.1 * rng.normal(), 0.3 + 0.01 * rng.normal(), 0.75 * std::cos(0.05 * t_s) + 0.1 * rng.normal(),
                          30.0 + 20.0 * std::sin(0.3 * t_s), 0});
    if (k % 97 != 0) detections.push_back({12.0 + 0.02 * rng.normal(), -0.6 + 0.05 * rng.normal(), 0.0, 10.0, 1});
    if (k % 3 == 0) detections.push_back({35.0 + rng.normal(), rng.normal(), 0.3 * rng.normal(), 6.0, -1});
    tracker.step(detections, reported);
    if (k % 1000 == 0 || k + 1 == kLongRunCycles) {
      for (const auto& tr : tracker.tracks()) {
        expect_spd(tr.P, k);
        ASSERT_TRUE(tr.x.allFinite()) << k;
      }
    }
  }
  EXPECT_FALSE(reported.empty());
}

}  // namespace
}  // namespace rcsim
