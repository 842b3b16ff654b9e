// Measurement noise and the cycle time as the detections show them (docs/sensor-profiles.md,
// aimotive_lrr: "residual RMS of the stationary fit's inliers by SNR", "stationary points matched
// frame to frame", "stationary targets matched frame to frame after ego motion").
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <span>

#include "common/decibel.hpp"
#include "common/quantile.hpp"
#include "replay/profile/derivation_stages.hpp"
#include "sim/measurement_noise.hpp"

namespace rcsim::replay::profile {
namespace {

constexpr double kLowMarginDb = 4.0;    // "at threshold": within this of the threshold
constexpr double kHighMarginDb = 11.0;  // "the least noise": this far above it
constexpr std::size_t kMinSamples = 30;
constexpr double kCoarsestWrittenStep = 0.005;  // m or m/s

// The step of a quantised quantity: every value (99 %) on one lattice of the least distinct gap.
std::optional<double> lattice_step(const DetectionPool& pool, double (*value)(const PooledDetection&)) {
  std::vector<double> v;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) v.push_back(value(d));
  }
  const std::size_t detections = v.size();
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) < 2e-4; }), v.end());
  if (v.size() < 3) return std::nullopt;
  double step = INFINITY;
  for (std::size_t i = 1; i < v.size(); ++i) step = std::min(step, v[i] - v[i - 1]);
  std::size_t on = 0;
  for (const double x : v) {
    const double k = (x - v.front()) / step;
    on += std::abs(k - std::round(k)) * step < 2e-4 + 0.02 * step ? 1 : 0;
  }
  // A quantity written with 4 decimals is on a lattice of 1e-4 too: a radar's step is coarser, and
  // far fewer values than detections share it.
  if (100 * on < 99 * v.size() || step < kCoarsestWrittenStep || v.size() > detections / 5) return std::nullopt;
  return step;
}

double rms(const std::vector<double>& x) {
  double s = 0.0;
  for (const double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

// The model's noise law (sim/measurement_noise.hpp): sigma(m) = max(sigma_th 10^(-m/20), sigma_min)
// at an SNR margin of m dB. A matched pair's difference is normal with the variance of both ends,
// sigma(m_earlier)^2 + sigma(m_later)^2; a few pairs are wrong matches or a wandering scatterer,
// uniform over the gate. Both sigmas (and the share of such pairs) by maximum likelihood: a
// logarithmic grid, then a finer one around its best.
struct NoiseLaw {
  double at_threshold = 0.0, least = 0.0, outliers = 0.0;
  std::size_t pairs = 0, near_threshold = 0, far_above = 0;
  // The fine grid's span where the likelihood stays within its noise (the negative log-likelihood
  // within 2 of the least: about 95 %); on the grid's edge where it reaches it.
  double at_threshold_low = 0.0, at_threshold_high = 0.0, least_low = 0.0, least_high = 0.0;
  // Weak: the span wider than the issue's +-30 %, or fewer than 100 pairs showing an end.
  bool weak(double low, double high, double value) const {
    return near_threshold < kWeakEnds || far_above < kWeakEnds || high - low > 0.6 * value;
  }
  static constexpr std::size_t kWeakEnds = 100;
};

// How many pairs show each end of the law: one end near the threshold, both far above it.
NoiseLaw count_ends(const std::vector<MatchedDetection>& matches) {
  NoiseLaw law;
  for (const MatchedDetection& m : matches) {
    const double nearer_db = std::min(m.margin_earlier_db, m.margin_later_db);
    law.near_threshold += nearer_db < kLowMarginDb + 2.0 ? 1 : 0;
    law.far_above += nearer_db >= kHighMarginDb ? 1 : 0;
  }
  law.pairs = matches.size();
  return law;
}

std::optional<NoiseLaw> fit_noise_law(const std::vector<MatchedDetection>& matches, double (*difference)(const MatchedDetection&)) {
  NoiseLaw law = count_ends(matches);
  std::vector<double> d, ratio_a, ratio_b;
  double gate = 0.0;
  for (const MatchedDetection& m : matches) {
    d.push_back(difference(m));
    ratio_a.push_back(db_to_amplitude(-m.margin_earlier_db)), ratio_b.push_back(db_to_amplitude(-m.margin_later_db));
    gate = std::max(gate, std::abs(d.back()));
  }
  if (law.near_threshold < kMinSamples || law.far_above < kMinSamples || !(gate > 0.0)) return std::nullopt;
  const auto negative_log_likelihood = [&](double at_threshold, double least, double outliers) {
    double sum = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double sa = noise_sigma(at_threshold, least, ratio_a[i]), sb = noise_sigma(at_threshold, least, ratio_b[i]);
      const double variance = sa * sa + sb * sb;
      const double normal = std::exp(-0.5 * d[i] * d[i] / variance) / std::sqrt(2.0 * std::numbers::pi * variance);
      sum -= std::log((1.0 - outliers) * normal + outliers / (2.0 * gate));
    }
    return sum;
  };
  double best = INFINITY;
  std::vector<std::array<double, 3>> fine;  // nll, at_threshold, least of the fine grid
  bool record = false;
  const auto search = [&](double th_lo, double min_lo, double factor, int steps, std::span<const double> shares) {
    for (int i = 0; i < steps; ++i) {
      for (int j = 0; j < steps; ++j) {
        const double at_threshold = th_lo * std::pow(factor, i), least = min_lo * std::pow(factor, j);
        if (least > at_threshold) continue;
        for (const double outliers : shares) {
          const double nll = negative_log_likelihood(at_threshold, least, outliers);
          if (record) fine.push_back({nll, at_threshold, least});
          if (nll < best) best = nll, law.at_threshold = at_threshold, law.least = least, law.outliers = outliers;
        }
      }
    }
  };
  constexpr double kCoarseShare[] = {0.02}, kShares[] = {0.005, 0.02, 0.05, 0.1, 0.2};
  search(1e-3 * gate, 1e-3 * gate, 1.25, 32, kCoarseShare);  // 0.001 to 1 gate
  best = INFINITY;
  record = true;
  search(law.at_threshold / 1.25, law.least / 1.25, 1.02, 24, kShares);
  law.at_threshold_low = law.least_low = INFINITY, law.at_threshold_high = law.least_high = 0.0;
  for (const auto& [nll, at_threshold, least] : fine) {
    if (nll > best + 2.0) continue;
    law.at_threshold_low = std::min(law.at_threshold_low, at_threshold), law.at_threshold_high = std::max(law.at_threshold_high, at_threshold);
    law.least_low = std::min(law.least_low, least), law.least_high = std::max(law.least_high, least);
  }
  return law;
}

std::string noise_law_evidence(const NoiseLaw& law) {
  return fmt::format("stationary detections matched frame to frame: maximum likelihood of the model's law, sigma = max(sigma_th "
                     "A_th / A, sigma_min) at each end, over {} pairs ({} with an end within {:.0f} dB of the threshold, {} with both "
                     "{:.0f} dB or more above; {:.1f} % taken as wrong matches); within 2 of the least negative log-likelihood: "
                     "sigma_th {:.4f}-{:.4f}, sigma_min {:.4f}-{:.4f}",
                     law.pairs, law.near_threshold, kLowMarginDb + 2.0, law.far_above, kHighMarginDb, 100.0 * law.outliers,
                     law.at_threshold_low, law.at_threshold_high, law.least_low, law.least_high);
}

// The two values of a fitted law, each with its interval and mark.
std::vector<DerivedValue> noise_law_values(const NoiseLaw& law, const char* at_threshold_field, const char* least_field, double step,
                                           const std::string& at_threshold_evidence, const std::string& least_evidence) {
  const auto support = static_cast<long long>(law.pairs);
  return {with_interval({at_threshold_field, round_to(law.at_threshold, step), ValueSource::derived, at_threshold_evidence, support},
                        law.at_threshold_low, law.at_threshold_high, law.weak(law.at_threshold_low, law.at_threshold_high, law.at_threshold)),
          with_interval({least_field, round_to(law.least, step), ValueSource::derived, least_evidence, support}, law.least_low,
                        law.least_high, law.weak(law.least_low, law.least_high, law.least))};
}

// The fit drawn: per 2-dB bin of the nearer end's margin, the pairs' RMS difference / sqrt(2) (dots)
// and the fitted law's sqrt((sigma(m_earlier)^2 + sigma(m_later)^2) / 2) over the same pairs (line).
DerivationFigure noise_law_figure(std::string title, std::string y_label, const std::vector<MatchedDetection>& matches,
                                  double (*difference)(const MatchedDetection&), const NoiseLaw& law) {
  std::map<int, std::pair<double, double>> sums;  // bin -> (sum of squared differences, of the law's variances)
  std::map<int, std::size_t> counts;
  for (const MatchedDetection& m : matches) {
    const int bin = static_cast<int>(std::floor(std::min(m.margin_earlier_db, m.margin_later_db) / 2.0));
    const double sa = noise_sigma(law.at_threshold, law.least, db_to_amplitude(-m.margin_earlier_db));
    const double sb = noise_sigma(law.at_threshold, law.least, db_to_amplitude(-m.margin_later_db));
    sums[bin].first += difference(m) * difference(m), sums[bin].second += sa * sa + sb * sb;
    ++counts[bin];
  }
  std::vector<std::pair<double, double>> measured, fitted;
  for (const auto& [bin, sum] : sums) {
    if (counts[bin] < kMinSamples) continue;
    const auto n = static_cast<double>(counts[bin]);
    measured.emplace_back(2.0 * bin + 1.0, std::sqrt(sum.first / n / 2.0));
    fitted.emplace_back(2.0 * bin + 1.0, std::sqrt(sum.second / n / 2.0));
  }
  DerivationFigure figure{std::move(title), "nearer end's amplitude - threshold / dB", std::move(y_label),
                          "stationary detections matched frame to frame, per 2-dB bin with at least 30 pairs: the RMS difference / "
                          "sqrt(2), and the fitted law over the same pairs",
                          {{"pairs", true, measured}, {"fitted law", false, fitted}}};
  figure.y_from_zero = true;
  return figure;
}

double range_difference(const MatchedDetection& m) { return m.range_m; }
double range_rate_difference(const MatchedDetection& m) { return m.range_rate_mps; }

std::vector<MatchedDetection> all_matches(const std::vector<FramePair>& frame_pairs) {
  std::vector<MatchedDetection> matches;
  for (const FramePair& pair : frame_pairs) matches.insert(matches.end(), pair.matches.begin(), pair.matches.end());
  return matches;
}

// The radial speed's noise: a quantised speed's step / sqrt(12), else the stationary fit's residual
// near the threshold and (the quietest sensor's) far above it.
std::vector<DerivedValue> range_rate_noise(const DetectionPool& pool, double threshold_db, const std::vector<FramePair>& frame_pairs,
                                           std::vector<DerivationFigure>& figures) {
  std::vector<DerivedValue> values;
  const std::optional<NoiseLaw> law = fit_noise_law(all_matches(frame_pairs), range_rate_difference);
  if (const auto step = lattice_step(pool, range_rate_of)) {
    const double sigma = round_to(*step / std::sqrt(12.0), 0.001);
    const std::string why = fmt::format("the radial speed is quantised in steps of {:.4f} m/s: step / sqrt(12)", *step);
    // The step is read exactly: the interval is the value.
    values.push_back(with_interval({"measurement_noise.range_rate_sigma_at_threshold_mps", sigma, ValueSource::derived, why, pool.detections},
                                   sigma, sigma, false));
    values.push_back(with_interval({"measurement_noise.range_rate_sigma_min_mps", sigma, ValueSource::derived, why, pool.detections}, sigma,
                                   sigma, false));
  } else {
    // The least noise is the quietest sensor's far above the threshold: a sensor's residual there
    // also holds its mounting's and the fit's errors.
    std::vector<double> low;
    std::map<std::pair<int, int>, std::vector<double>> high_by_sensor;
    for (const PooledCycle& c : pool.cycles) {
      for (const PooledDetection& d : c.detections) {
        if (!d.stationary()) continue;
        const double margin_db = d.amplitude_db - threshold_db;
        if (margin_db < kLowMarginDb) low.push_back(d.stationary_residual_mps);
        if (margin_db >= kHighMarginDb) high_by_sensor[{c.recording, c.sensor}].push_back(d.stationary_residual_mps);
      }
    }
    std::vector<double> high;
    for (const auto& [sensor, residuals] : high_by_sensor) {
      if (residuals.size() >= kMinSamples && (high.empty() || rms(residuals) < rms(high))) high = residuals;
    }
    std::map<int, std::vector<double>> by_margin;
    for (const PooledCycle& c : pool.cycles) {
      for (const PooledDetection& d : c.detections) {
        if (d.stationary()) by_margin[static_cast<int>(std::floor((d.amplitude_db - threshold_db) / 2.0))].push_back(d.stationary_residual_mps);
      }
    }
    std::vector<std::pair<double, double>> rms_by_margin;
    for (const auto& [bin, residuals] : by_margin) {
      if (residuals.size() >= kMinSamples) rms_by_margin.emplace_back(2.0 * bin + 1.0, rms(residuals));
    }
    figures.push_back({"Radial-speed residual of the stationary world against SNR margin", "amplitude - threshold / dB",
                       "RMS residual / (m/s)", "per 2-dB bin with at least 30 inliers of the per-cycle stationary fit",
                       {{"RMS", false, rms_by_margin}}});
    figures.back().y_from_zero = true;
    if (law) {
      figures.push_back(noise_law_figure("Radial-speed noise of matched pairs against SNR margin", "noise / (m/s)", all_matches(frame_pairs),
                                         range_rate_difference, *law));
      // Differences of one scatterer's radial speed along one line of sight: the azimuth's error,
      // which the stationary fit's residual also holds (v sin(az) d(az)), cancels.
      const std::string residual =
          low.size() >= kMinSamples && high.size() >= kMinSamples
              ? fmt::format("; the stationary fit's residual reads {:.3f} and {:.3f} m/s (it holds the azimuth error's share)", rms(low), rms(high))
              : "";
      for (DerivedValue& v : noise_law_values(*law, "measurement_noise.range_rate_sigma_at_threshold_mps", "measurement_noise.range_rate_sigma_min_mps",
                                              0.001, noise_law_evidence(*law) + residual, noise_law_evidence(*law) + residual)) {
        values.push_back(std::move(v));
      }
    } else if (low.size() >= kMinSamples && high.size() >= kMinSamples) {
      const double at_threshold = rms(low), least = std::min(rms(high), at_threshold);
      // An RMS of n normal residuals: about +-2 / sqrt(2 n) of itself (95 %); weak below 100.
      const auto rms_interval = [](DerivedValue v, double sigma, std::size_t n) {
        const double half = 2.0 * sigma / std::sqrt(2.0 * static_cast<double>(n));
        return with_interval(std::move(v), sigma - half, sigma + half, n < 100);
      };
      values.push_back(rms_interval({"measurement_noise.range_rate_sigma_at_threshold_mps", round_to(at_threshold, 0.001), ValueSource::derived,
                                     fmt::format("RMS residual about the stationary fit of its {} inliers within {:.0f} dB of the threshold",
                                                 low.size(), kLowMarginDb),
                                     static_cast<long long>(low.size())},
                                    at_threshold, low.size()));
      values.push_back(rms_interval({"measurement_noise.range_rate_sigma_min_mps", round_to(least, 0.001), ValueSource::derived,
                                     fmt::format("the same of the quietest sensor's {} inliers {:.0f} dB or more above it", high.size(),
                                                 kHighMarginDb),
                                     static_cast<long long>(high.size())},
                                    least, high.size()));
    } else {
      const std::string why = fmt::format("too few stationary detections near the threshold ({}) or far above it ({})", low.size(), high.size());
      values.push_back({"measurement_noise.range_rate_sigma_at_threshold_mps", nullptr, ValueSource::base, why, 0});
      values.push_back({"measurement_noise.range_rate_sigma_min_mps", nullptr, ValueSource::base, why, 0});
    }
  }

  return values;
}

// The cycle time from the static world's shift between matched cycles: the largest time of which
// every step is a whole multiple; else the recordings' clock (a drive) or the base's (single frames).
DerivedValue cycle_time(const DetectionPool& pool, const std::vector<FramePair>& frame_pairs, std::vector<DerivationFigure>& figures) {
  std::vector<double> steps_s;
  for (const FramePair& pair : frame_pairs) steps_s.push_back(pair.dt_s);
  const std::optional<double> period_s = steps_s.size() >= 10 ? fundamental_period(steps_s) : std::nullopt;
  if (period_s) {
    figures.push_back(histogram_figure("Time between consecutive cycles, from the static world's shift", "step / s", steps_s,
                                       3.0 * *period_s, 60, *period_s, "cycle time"));
    // The interval: the 5 % and 95 % quantiles of each step over its whole multiple of the period.
    std::vector<double> per_cycle_s;
    for (const double step_s : steps_s) per_cycle_s.push_back(step_s / std::max(1.0, std::round(step_s / *period_s)));
    std::sort(per_cycle_s.begin(), per_cycle_s.end());
    const bool few = steps_s.size() < 30;
    return with_interval({"cycle_time_s", round_to(*period_s, 0.0001), ValueSource::derived,
                          fmt::format("the static world's shift between consecutive cycles over the speed: {} steps, median {:.1f} ms, "
                                      "each a whole multiple of {:.1f} ms (the recordings' clock: {:.1f} ms){}",
                                      steps_s.size(), 1e3 * median(steps_s), 1e3 * *period_s, 1e3 * pool.recorded_cycle_time_s,
                                      few ? "; weak: fewer than 30 steps" : ""),
                          static_cast<long long>(steps_s.size())},
                         std::min(*period_s, quantile_of_sorted(per_cycle_s, 0.05)), std::max(*period_s, quantile_of_sorted(per_cycle_s, 0.95)),
                         few);
  }
  if (pool.snapshots) return {"cycle_time_s", nullptr, ValueSource::base, "not observable: single frames, none follows another", 0};
  return {"cycle_time_s", round_to(pool.recorded_cycle_time_s, 0.0001), ValueSource::recording,
          fmt::format("the recordings' clock ({} frame pairs matched, too few to show the radar's own)", steps_s.size()), 0};
}

// The range's noise: matched stationary detections' range differences (a drive), a quantised
// range's step / sqrt(12), or, for single frames, the range cell / sqrt(12).
std::vector<DerivedValue> range_noise(const DetectionPool& pool, const Cells& cells, const std::vector<FramePair>& frame_pairs,
                                      std::vector<DerivationFigure>& figures) {
  std::vector<DerivedValue> values;
  const std::vector<MatchedDetection> matches = all_matches(frame_pairs);
  if (const std::optional<NoiseLaw> law = fit_noise_law(matches, range_difference)) {
    figures.push_back(noise_law_figure("Range noise of matched pairs against SNR margin", "noise / m", matches, range_difference, *law));
    for (DerivedValue& v : noise_law_values(*law, "measurement_noise.range_sigma_at_threshold_m", "measurement_noise.range_sigma_min_m", 0.005,
                                            noise_law_evidence(*law) + " (an upper bound: the scatterer wanders)", noise_law_evidence(*law))) {
      values.push_back(std::move(v));
    }
  } else if (const auto step = lattice_step(pool, range_of)) {
    const std::string why = fmt::format("the range is quantised in steps of {:.4f} m: step / sqrt(12)", *step);
    const double sigma = round_to(*step / std::sqrt(12.0), 0.001);
    values.push_back(with_interval({"measurement_noise.range_sigma_at_threshold_m", sigma, ValueSource::derived, why, pool.detections}, sigma,
                                   sigma, false));
    values.push_back(with_interval({"measurement_noise.range_sigma_min_m", sigma, ValueSource::derived, why, pool.detections}, sigma, sigma,
                                   false));
  } else if (cells.found && pool.snapshots) {
    // Single frames: nothing to match. A range read off a cell's centre is uniform over the cell.
    const double sigma = round_to(cells.range_m / std::sqrt(12.0), 0.001);
    const std::string why = fmt::format("assumed: the range cell ({:.3f} m) / sqrt(12), the quantisation of a cell's centre (single "
                                        "frames: nothing to match frame to frame)",
                                        cells.range_m);
    // An assumption, not a reading: weak, its interval the range cell's over sqrt(12).
    values.push_back(with_interval({"measurement_noise.range_sigma_at_threshold_m", sigma, ValueSource::derived, why + "; weak: an assumption", 0},
                                   cells.range_low_m / std::sqrt(12.0), cells.range_high_m / std::sqrt(12.0), true));
    values.push_back(with_interval({"measurement_noise.range_sigma_min_m", sigma, ValueSource::derived, why + "; weak: an assumption", 0},
                                   cells.range_low_m / std::sqrt(12.0), cells.range_high_m / std::sqrt(12.0), true));
  } else {
    const NoiseLaw counts = count_ends(matches);
    const std::string why = fmt::format("too few stationary detections matched frame to frame ({} pairs: {} with an end within {:.0f} dB "
                                        "of the threshold, {} with both {:.0f} dB or more above; {} of each needed)",
                                        counts.pairs, counts.near_threshold, kLowMarginDb + 2.0, counts.far_above, kHighMarginDb, kMinSamples);
    values.push_back({"measurement_noise.range_sigma_at_threshold_m", nullptr, ValueSource::base, why, 0});
    values.push_back({"measurement_noise.range_sigma_min_m", nullptr, ValueSource::base, why, 0});
  }
  return values;
}

}  // namespace

std::vector<DerivedValue> derive_noise(const DetectionPool& pool, const Cells& cells, double threshold_db,
                                       const std::vector<FramePair>& frame_pairs, std::vector<DerivationFigure>& figures) {
  std::vector<DerivedValue> values = range_rate_noise(pool, threshold_db, frame_pairs, figures);
  values.push_back(cycle_time(pool, frame_pairs, figures));
  const std::vector<DerivedValue> range = range_noise(pool, cells, frame_pairs, figures);
  values.insert(values.end(), range.begin(), range.end());
  return values;
}

}  // namespace rcsim::replay::profile
