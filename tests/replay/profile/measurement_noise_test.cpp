// The noise stage of `rcsim profile derive` (replay/profile/measurement_noise.cpp, declared in
// derivation_stages.hpp): a quantised quantity's step / sqrt(12), residual RMS by SNR margin,
// the model's noise law fitted to matched pairs and the cycle time from the matched steps, each worked by hand on
// detections and frame pairs laid out in code; and what is left to the base or the recordings.
#include "replay/profile/derivation_stages.hpp"
#include "replay/profile/derivation_checks.hpp"

#include <gtest/gtest.h>

#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace rcsim::replay::profile::measurement_noise_test {

constexpr double kThreshold_db = 10.0;

using rcsim::testing::by_field;

// 200 detections in two cycles; range and range rate of the i-th as given.
template <class Range, class Rate>
DetectionPool pool_of(Range range_m, Rate range_rate_mps) {
  DetectionPool pool;
  pool.cycles.resize(2);
  for (int i = 0; i < 200; ++i) {
    PooledDetection d;
    d.range_m = range_m(i), d.range_rate_mps = range_rate_mps(i), d.amplitude_db = 20.0;
    pool.cycles[static_cast<std::size_t>(i % 2)].detections.push_back(d);
  }
  pool.detections = 200;
  pool.recorded_cycle_time_s = 0.0667;
  return pool;
}

TEST(ProfileMeasurementNoise, AQuantisedQuantitysNoiseIsItsStepOverRootTwelve) {
  // Range rates on 10 steps of 0.1 m/s, ranges on 20 steps of 0.2 m (at most a fifth as many
  // values as detections): 0.1 / sqrt(12) = 0.0289 -> 0.029, 0.2 / sqrt(12) = 0.0577 -> 0.058.
  const DetectionPool pool = pool_of([](int i) { return 10.0 + 0.2 * (i % 20); }, [](int i) { return -0.5 + 0.1 * (i % 10); });
  std::vector<DerivationFigure> figures;
  const auto values = by_field(derive_noise(pool, Cells{}, kThreshold_db, {}, figures));
  ASSERT_EQ(values.size(), 5u);
  for (const char* field : {"measurement_noise.range_rate_sigma_at_threshold_mps", "measurement_noise.range_rate_sigma_min_mps"}) {
    EXPECT_DOUBLE_EQ(values.at(field).value.get<double>(), 0.029) << field;
    EXPECT_EQ(values.at(field).evidence, "the radial speed is quantised in steps of 0.1000 m/s: step / sqrt(12)");
    EXPECT_EQ(values.at(field).support, 200);
  }
  for (const char* field : {"measurement_noise.range_sigma_at_threshold_m", "measurement_noise.range_sigma_min_m"}) {
    EXPECT_DOUBLE_EQ(values.at(field).value.get<double>(), 0.058) << field;
    EXPECT_EQ(values.at(field).evidence, "the range is quantised in steps of 0.2000 m: step / sqrt(12)");
  }
  // No frame pairs on a drive: the recordings' clock.
  EXPECT_EQ(values.at("cycle_time_s").source, ValueSource::recording);
  EXPECT_DOUBLE_EQ(values.at("cycle_time_s").value.get<double>(), 0.0667);
  EXPECT_TRUE(figures.empty());
}

TEST(ProfileMeasurementNoise, ResidualsByMarginAndMatchedRangesByHand) {
  // Range rates 0.001 m/s apart and ranges 0.01 m apart: no lattice a radar's step could be
  // (finer than 5 mm). 100 stationary detections within 4 dB of the threshold with residuals
  // +-0.05 m/s (RMS 0.05), 100 at 11 dB or more with +-0.02 (RMS 0.02).
  DetectionPool pool = pool_of([](int i) { return 10.0 + 0.01 * i; }, [](int i) { return 0.001 * i; });
  int n = 0;
  for (PooledCycle& c : pool.cycles) {
    for (PooledDetection& d : c.detections) {
      const bool low = n % 2 == 0;
      d.amplitude_db = kThreshold_db + (low ? 1.0 : 12.0);
      d.stationary_residual_mps = low ? 0.05 : 0.02;
      ++n;
    }
  }
  // 10 frame pairs 0.05 s apart, their matches drawn (at the normal's quantiles) from the model's
  // law sigma(m) = max(sigma_th 10^(-m/20), sigma_min) with sigma_th 0.1 m and 0.05 m/s, sigma_min
  // 0.04 m and 0.015 m/s: 30 a pair with one end 1 dB and the other 12 dB above the threshold
  // (sigma 0.0891 and 0.04 m: the difference's 0.0977 m), 30 with both 12 dB above (0.0566 m).
  // Both come back within the search's 2-% steps, rounded to 5 mm and 1 mm/s.
  const auto quantiles = [](int count) {
    std::vector<double> z;
    for (int k = 0; k < count; ++k) z.push_back(std::sqrt(2.0) * boost::math::erf_inv(2.0 * (k + 0.5) / count - 1.0));
    return z;
  };
  const auto sigma = [](double at_threshold, double least, double margin_db) {
    return std::max(at_threshold * std::pow(10.0, -margin_db / 20.0), least);
  };
  const auto difference_sigma = [&](double at_threshold, double least, double margin_a_db, double margin_b_db) {
    return std::hypot(sigma(at_threshold, least, margin_a_db), sigma(at_threshold, least, margin_b_db));
  };
  const std::vector<double> z = quantiles(30);
  std::vector<FramePair> pairs(10);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    pairs[p].dt_s = 0.05;
    for (std::size_t k = p; k < z.size(); k += pairs.size()) {
      pairs[p].matches.push_back({difference_sigma(0.1, 0.04, 1.0, 12.0) * z[k], difference_sigma(0.05, 0.015, 1.0, 12.0) * z[k], 1.0, 12.0});
      pairs[p].matches.push_back({difference_sigma(0.1, 0.04, 12.0, 12.0) * z[k], difference_sigma(0.05, 0.015, 12.0, 12.0) * z[k], 12.0, 12.0});
    }
  }
  std::vector<DerivationFigure> figures;
  const auto values = by_field(derive_noise(pool, Cells{}, kThreshold_db, pairs, figures));
  EXPECT_NEAR(values.at("measurement_noise.range_sigma_at_threshold_m").value.get<double>(), 0.1, 0.0051);
  EXPECT_NEAR(values.at("measurement_noise.range_sigma_min_m").value.get<double>(), 0.04, 0.0051);
  EXPECT_NEAR(values.at("measurement_noise.range_rate_sigma_at_threshold_mps").value.get<double>(), 0.05, 0.0021);
  EXPECT_NEAR(values.at("measurement_noise.range_rate_sigma_min_mps").value.get<double>(), 0.015, 0.0011);
  EXPECT_EQ(values.at("measurement_noise.range_sigma_at_threshold_m").support, 60);
  EXPECT_NE(values.at("measurement_noise.range_sigma_min_m").evidence.find("over 60 pairs (30 with an end within 6 dB of the threshold, 30 with both 11 dB or more above"),
            std::string::npos)
      << values.at("measurement_noise.range_sigma_min_m").evidence;
  // Without pairs near the threshold the radial speed's noise is the stationary fit's residual RMS
  // near the threshold and far above it.
  std::vector<FramePair> far_only = pairs;
  for (FramePair& p : far_only) std::erase_if(p.matches, [](const MatchedDetection& m) { return m.margin_earlier_db < 11.0; });
  std::vector<DerivationFigure> unused;
  const auto rms_values = by_field(derive_noise(pool, Cells{}, kThreshold_db, far_only, unused));
  EXPECT_DOUBLE_EQ(rms_values.at("measurement_noise.range_rate_sigma_at_threshold_mps").value.get<double>(), 0.05);
  EXPECT_EQ(rms_values.at("measurement_noise.range_rate_sigma_at_threshold_mps").support, 100);
  EXPECT_DOUBLE_EQ(rms_values.at("measurement_noise.range_rate_sigma_min_mps").value.get<double>(), 0.02);
  EXPECT_EQ(rms_values.at("measurement_noise.range_sigma_min_m").source, ValueSource::base);
  // The cycle time from the 10 steps of exactly 50 ms: each one period, sum(k d) / sum(k^2) = 50 ms
  // (the search's first fit, 52.5 ms, is only where the least-squares period starts).
  EXPECT_EQ(values.at("cycle_time_s").source, ValueSource::derived);
  EXPECT_DOUBLE_EQ(values.at("cycle_time_s").value.get<double>(), 0.05);
  EXPECT_EQ(values.at("cycle_time_s").support, 10);
  // Figures: the residual RMS per 2-dB bin of margin (bins at 1 and 13 dB), the radial speed's law
  // against the pairs, the steps' histogram, the range's law against the pairs: per 2-dB bin of the
  // nearer end (1 dB: 30 pairs, 12 dB: 30), the RMS difference / sqrt(2) and the law's over the
  // same pairs, within 5 % of each other (the law fitted to them).
  ASSERT_EQ(figures.size(), 4u);
  EXPECT_EQ(figures[1].title, "Radial-speed noise of matched pairs against SNR margin");
  EXPECT_EQ(figures[3].title, "Range noise of matched pairs against SNR margin");
  for (const std::size_t f : {std::size_t{1}, std::size_t{3}}) {
    const auto& measured = figures[f].series[0].points;
    const auto& law = figures[f].series[1].points;
    ASSERT_EQ(measured.size(), 2u);
    ASSERT_EQ(law.size(), 2u);
    EXPECT_DOUBLE_EQ(measured[0].first, 1.0);
    EXPECT_DOUBLE_EQ(measured[1].first, 13.0);
    for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(measured[i].second / law[i].second, 1.0, 0.05) << figures[f].title << " " << i;
  }
  // Range, the 1-dB bin: sigma 0.0891 and 0.04 m at the ends, (0.0891^2 + 0.04^2) / 2 -> 0.069 m.
  EXPECT_NEAR(figures[3].series[1].points[0].second, 0.069, 0.005);
  const auto& rms = figures[0].series[0].points;
  ASSERT_EQ(rms.size(), 2u);
  EXPECT_DOUBLE_EQ(rms[0].first, 1.0);
  EXPECT_NEAR(rms[0].second, 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(rms[1].first, 13.0);
  EXPECT_NEAR(rms[1].second, 0.02, 1e-12);
}

TEST(ProfileMeasurementNoise, WhatTheDataCannotShowComesFromTheBaseOrTheRecordings) {
  // Nothing quantised, nothing stationary, no frame pairs.
  DetectionPool pool = pool_of([](int i) { return 10.0 + 0.01 * i; }, [](int i) { return 0.001 * i; });
  std::vector<DerivationFigure> figures;
  auto values = by_field(derive_noise(pool, Cells{}, kThreshold_db, {}, figures));
  EXPECT_EQ(values.at("measurement_noise.range_rate_sigma_min_mps").source, ValueSource::base);
  EXPECT_EQ(values.at("measurement_noise.range_rate_sigma_min_mps").evidence,
            "too few stationary detections near the threshold (0) or far above it (0)");
  EXPECT_EQ(values.at("measurement_noise.range_sigma_at_threshold_m").source, ValueSource::base);
  EXPECT_EQ(values.at("measurement_noise.range_sigma_at_threshold_m").evidence,
            "too few stationary detections matched frame to frame (0 pairs: 0 with an end within 6 dB of the threshold, 0 with both 11 dB or more above; 30 of each needed)");
  EXPECT_EQ(values.at("cycle_time_s").evidence, "the recordings' clock (0 frame pairs matched, too few to show the radar's own)");
  // Single frames with a range cell: the range noise is the cell's quantisation, 0.15 / sqrt(12)
  // = 0.0433 -> 0.043; the cycle time cannot be seen.
  pool.snapshots = true;
  values = by_field(derive_noise(pool, Cells{0.15, 0.1, true}, kThreshold_db, {}, figures));
  EXPECT_EQ(values.at("measurement_noise.range_sigma_min_m").source, ValueSource::derived);
  EXPECT_DOUBLE_EQ(values.at("measurement_noise.range_sigma_min_m").value.get<double>(), 0.043);
  EXPECT_EQ(values.at("measurement_noise.range_sigma_min_m").support, 0);
  EXPECT_EQ(values.at("cycle_time_s").source, ValueSource::base);
  EXPECT_TRUE(values.at("cycle_time_s").value.is_null());
  EXPECT_EQ(values.at("cycle_time_s").evidence, "not observable: single frames, none follows another");
}

}  // namespace rcsim::replay::profile::measurement_noise_test
