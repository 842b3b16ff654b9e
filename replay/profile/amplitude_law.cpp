// The reporting threshold and the amplitude law as the detections show them
// (docs/sensor-profiles.md, aimotive_lrr: "least squares of SNR - RCS against log10 R and az²",
// "the residual SNR against azimuth").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <cmath>
#include <algorithm>
#include <array>
#include <map>

#include "common/angles.hpp"
#include "common/decibel.hpp"
#include "common/quantile.hpp"
#include "replay/profile/derivation_stages.hpp"
#include "sim/antenna.hpp"

namespace rcsim::replay::profile {
namespace {

// A grid search's objective "within its noise" of the least: at most 10 % (and 0.05 dB) above it.
// The values of the candidates within it span the derived value's interval.
bool near_least(double score, double least) { return score <= least + std::max(0.1 * least, 0.05); }
struct GridSpan {
  double low = INFINITY, high = -INFINITY;
  void add(double v) { low = std::min(low, v), high = std::max(high, v); }
};
// A pattern's interval is weak where the near-best candidates span more than this many wavelengths.
constexpr double kWeakPatternSpanWavelengths = 0.3;

// A_phi = |H_sum|^n of eq. (2): the paper's one-way pattern (1), or the two-way pattern of a radar
// whose transmit and receive antennas are alike (2).
constexpr double kPatternExponents[] = {1.0, 2.0};

// The base's exponent n of A^phi = |H_sum|^n, 1 where it gives none (the paper's, schemas/sensor-config.md).
double base_pattern_exponent(const nlohmann::json& base) {
  return base.value("/antenna/amplitude_pattern_exponent"_json_pointer, 1.0);
}

// The widest spacing, in 0.05 steps, that keeps eq. (7) invertible over the derived view field.
// No margin beyond it: that edge, the 99.9 % quantile of the estimated azimuths, already lies
// beyond the true one by the estimates' noise (aimotive_lrr's 17 deg reads 17.8 from its own model).
double max_invertible_spacing(double azimuth_half_deg) {
  return std::floor(20.0 / (2.0 * std::sin(deg_to_rad(azimuth_half_deg)))) / 20.0;
}

struct LawFit {
  double constant_db = 0.0, range_exponent = 0.0, residual_rms_db = 0.0;
  double constant_se_db = 0.0, range_exponent_se = 0.0;  // least squares' standard errors
};

// y = C - 10 n log10 R by least squares.
LawFit fit_range_law(const std::vector<double>& log10_range, const std::vector<double>& y) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(y.size()), 2);
  Eigen::VectorXd b(static_cast<Eigen::Index>(y.size()));
  for (std::size_t i = 0; i < y.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    a(row, 0) = 1.0, a(row, 1) = -10.0 * log10_range[i], b(row) = y[i];
  }
  const Eigen::Vector2d x = a.colPivHouseholderQr().solve(b);
  const Eigen::VectorXd residual = a * x - b;
  const double dof = std::max(1.0, static_cast<double>(y.size()) - 2.0);
  const Eigen::Matrix2d covariance = (residual.squaredNorm() / dof) * (a.transpose() * a).inverse();
  return {x(0), x(1), std::sqrt(residual.squaredNorm() / static_cast<double>(y.size())), std::sqrt(std::max(0.0, covariance(0, 0))),
          std::sqrt(std::max(0.0, covariance(1, 1)))};
}

// SNR - RCS at a detection: C - 10 n log10 R + the two-way pattern of eq. (6), |H_sum|^p in dB.
std::vector<double> pattern_db(const std::vector<double>& azimuth_rad, const AntennaGeometry& geometry) {
  const MonopulseAntenna antenna(geometry);
  std::vector<double> out;
  for (const double a : azimuth_rad) out.push_back(amplitude_to_db(std::pow(antenna.sum_magnitude(a), geometry.amplitude_pattern_exponent)));
  return out;
}

// How far the fit's residual strays with azimuth: the RMS over 0.025-rad bins of |azimuth| (with at
// least 10 detections) of the bins' mean residual, each bin one vote, so that the few detections
// off boresight, where the pattern shows, weigh as much as the many ahead.
double azimuth_bias_db(const std::vector<double>& azimuth_rad, const std::vector<double>& log10_range, const std::vector<double>& y,
                       const LawFit& fit) {
  constexpr double kBinRad = 0.025;
  std::map<int, std::pair<double, int>> bins;
  for (std::size_t i = 0; i < y.size(); ++i) {
    auto& [sum, count] = bins[static_cast<int>(std::abs(azimuth_rad[i]) / kBinRad)];
    sum += y[i] - (fit.constant_db - 10.0 * fit.range_exponent * log10_range[i]), ++count;
  }
  double sum_sq = 0.0;
  int used = 0;
  for (const auto& [bin, sc] : bins) {
    if (sc.second < 10) continue;
    const double mean = sc.first / sc.second;
    sum_sq += mean * mean, ++used;
  }
  return used == 0 ? INFINITY : std::sqrt(sum_sq / used);
}

// SNR - RCS against range with the fitted law, and its residual against azimuth with the pattern.
void law_figures(const LawFit& fit, const AntennaGeometry& geometry, const std::vector<double>& log10_range,
                 const std::vector<double>& azimuth_rad, const std::vector<double>& snr_minus_rcs_db, std::vector<DerivationFigure>& figures) {
  std::vector<std::pair<double, double>> points, law;
  std::map<int, std::pair<double, int>> bins;
  constexpr double kBinRad = 0.025;
  for (std::size_t i = 0; i < log10_range.size(); ++i) {
    points.emplace_back(std::pow(10.0, log10_range[i]), snr_minus_rcs_db[i]);
    auto& [sum, count] = bins[static_cast<int>(std::floor(azimuth_rad[i] / kBinRad))];
    sum += snr_minus_rcs_db[i] - (fit.constant_db - 10.0 * fit.range_exponent * log10_range[i]), ++count;
  }
  for (double r = 1.0; r <= 300.0; r *= 1.05) law.emplace_back(r, fit.constant_db - 10.0 * fit.range_exponent * std::log10(r));
  double far_m = 0.0;
  for (const auto& p : points) far_m = std::max(far_m, p.first);
  std::erase_if(law, [&](const auto& p) { return p.first > far_m; });
  figures.push_back({"SNR - RCS against range", "range / m", "SNR - RCS / dB",
                     fmt::format("every detection (thinned); the line: C - 10 n log10 R with C {:.1f} dB, n {:.2f} (boresight)",
                                 fit.constant_db, fit.range_exponent),
                     {{"detections", true, thinned(points, 4000)}, {"fitted law", false, law}}});
  std::vector<std::pair<double, double>> means, pattern;
  for (const auto& [bin, sc] : bins) {
    if (sc.second >= 10) means.emplace_back(rad_to_deg((bin + 0.5) * kBinRad), sc.first / sc.second);
  }
  const MonopulseAntenna antenna(geometry);
  for (const auto& m : means) {
    pattern.emplace_back(m.first, amplitude_to_db(std::pow(antenna.sum_magnitude(deg_to_rad(m.first)), geometry.amplitude_pattern_exponent)));
  }
  figures.push_back({"The law's residual against azimuth", "azimuth / deg", "mean residual / dB",
                     fmt::format("the mean of SNR - RCS - (C - 10 n log10 R) per 0.025-rad bin (at least 10 detections); the "
                                 "line: eq. (6)'s two-way pattern, dipole {:.2f}, spacing {:.2f} wavelengths",
                                 geometry.dipole_length_wavelengths, geometry.element_spacing_wavelengths),
                     {{"bins", true, means}, {"pattern", false, pattern}}});
}

// The antenna pattern of a radar whose amplitude has no cross-section beside it (a level on its
// own scale, or an SNR without RCS): the targets differ, but their mix differs little with
// azimuth. The 90 % quantile of the amplitude per bin of range (25 % wide) and azimuth (0.05 rad,
// at least 30 detections) is split into a part of range and a part of azimuth, y(r, a) = L(r) +
// P(a) by alternating least squares; P folded over |azimuth| (bins of at least 200 detections) is
// what eq. (6)'s two-way pattern must follow, up to a constant.
struct AzimuthProfile {
  std::vector<std::pair<double, double>> points;  // |azimuth| / rad, P / dB
  int cells = 0;
};
constexpr double kPatternQuantile = 0.9;
constexpr double kPatternAzimuthBinRad = 0.05;

AzimuthProfile azimuth_profile(const DetectionPool& pool) {
  std::map<std::pair<int, int>, std::vector<double>> by_cell;
  const double log_step = std::log(1.25);
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) {
      const int r = static_cast<int>(std::floor(std::log(std::max(d.range_m, 0.1)) / log_step));
      by_cell[{r, static_cast<int>(std::floor(d.azimuth_rad / kPatternAzimuthBinRad))}].push_back(d.amplitude_db);
    }
  }
  struct Cell {
    int r, a;
    double q_db;
    std::size_t n;
  };
  std::vector<Cell> cells;
  for (auto& [key, v] : by_cell) {
    if (v.size() < 30) continue;
    const auto k = static_cast<std::size_t>(kPatternQuantile * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    cells.push_back({key.first, key.second, v[k], v.size()});
  }
  std::map<int, double> range_part, azimuth_part;
  for (const Cell& c : cells) range_part[c.r] = 0.0, azimuth_part[c.a] = 0.0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    std::map<int, std::pair<double, int>> sums;
    for (const Cell& c : cells) sums[c.r].first += c.q_db - azimuth_part[c.a], ++sums[c.r].second;
    for (auto& [r, v] : range_part) v = sums[r].first / sums[r].second;
    sums.clear();
    for (const Cell& c : cells) sums[c.a].first += c.q_db - range_part[c.r], ++sums[c.a].second;
    for (auto& [a, v] : azimuth_part) v = sums[a].first / sums[a].second;
  }
  std::map<int, std::size_t> detections_in;
  for (const Cell& c : cells) detections_in[c.a] += c.n;
  std::map<int, std::pair<double, int>> folded;  // by |bin centre| in bins (k + 0.5 -> k for k >= 0, -k - 1 for k < 0)
  for (const auto& [a, part] : azimuth_part) {
    if (detections_in[a] < 200) continue;
    auto& f = folded[a >= 0 ? a : -a - 1];
    f.first += part, ++f.second;
  }
  AzimuthProfile out;
  out.cells = static_cast<int>(cells.size());
  for (const auto& [k, f] : folded) out.points.emplace_back((k + 0.5) * kPatternAzimuthBinRad, f.first / f.second);
  return out;
}

// The RMS about their mean of the differences P - pattern, and that mean.
std::pair<double, double> offset_residual(const std::vector<std::pair<double, double>>& points, const std::vector<double>& pattern) {
  double mean = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) mean += points[i].second - pattern[i];
  mean /= static_cast<double>(points.size());
  double ss = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) ss += std::pow(points[i].second - pattern[i] - mean, 2);
  return {std::sqrt(ss / static_cast<double>(points.size())), mean};
}

// Eq. (6)'s pattern (dipole 0.3-1.5, spacing up to max_spacing wavelengths) that the azimuth part
// follows best, or nothing where fewer than 5 azimuth bins show it. The spacing from 0.1 for an
// array that resolves azimuth (the base's resolution.azimuth_cell_deg: the pattern sets only the
// amplitude), else from 0.5 (a monopulse pair's spacing also sets eq. (7)'s slope).
std::vector<DerivedValue> derive_relative_pattern(const DetectionPool& pool, const nlohmann::json& base, double max_spacing,
                                                  std::vector<DerivationFigure>& figures) {
  const AzimuthProfile profile = azimuth_profile(pool);
  const std::vector<std::string> fields{"antenna.dipole_length_wavelengths", "antenna.element_spacing_wavelengths"};
  if (profile.points.size() < 5) {
    const std::string why = fmt::format("too few azimuth bins with 200 detections ({}) to show the pattern", profile.points.size());
    return {{fields[0], nullptr, ValueSource::base, why, 0}, {fields[1], nullptr, ValueSource::base, why, 0}};
  }
  AntennaGeometry geometry;
  geometry.amplitude_pattern_exponent = base_pattern_exponent(base);
  const int min_spacing_20 = base.contains("/resolution/azimuth_cell_deg"_json_pointer) ? 2 : 10;
  std::vector<double> azimuth_rad;
  for (const auto& p : profile.points) azimuth_rad.push_back(p.first);
  double best_rms = INFINITY, best_offset = 0.0;
  const int max_spacing_20 = static_cast<int>(std::floor(max_spacing * 20.0 + 1e-9));
  std::vector<std::array<double, 3>> scored;  // rms, dipole, spacing
  for (int spacing_20 = min_spacing_20; spacing_20 <= max_spacing_20; ++spacing_20) {
    for (int length_20 = 6; length_20 <= 30; ++length_20) {
      AntennaGeometry candidate = geometry;
      candidate.dipole_length_wavelengths = 0.05 * length_20, candidate.element_spacing_wavelengths = 0.05 * spacing_20;
      const auto [rms, offset] = offset_residual(profile.points, pattern_db(azimuth_rad, candidate));
      scored.push_back({rms, candidate.dipole_length_wavelengths, candidate.element_spacing_wavelengths});
      if (rms < best_rms) best_rms = rms, best_offset = offset, geometry.dipole_length_wavelengths = candidate.dipole_length_wavelengths,
                          geometry.element_spacing_wavelengths = candidate.element_spacing_wavelengths;
    }
  }
  const auto [flat_rms, flat_offset] = offset_residual(profile.points, std::vector<double>(profile.points.size(), 0.0));
  const MonopulseAntenna antenna(geometry);
  const auto pattern_at = [&](double a_rad) { return amplitude_to_db(std::pow(antenna.sum_magnitude(a_rad), geometry.amplitude_pattern_exponent)); };
  std::vector<std::pair<double, double>> data, line;
  for (const auto& [a, p] : profile.points) data.emplace_back(rad_to_deg(a), p - best_offset), line.emplace_back(rad_to_deg(a), pattern_at(a));
  figures.push_back({"The amplitude's azimuth part", "|azimuth| / deg", "dB",
                     fmt::format("90 % quantile per range x azimuth bin less its range part; the line: eq. (6), dipole {:.2f}, "
                                 "spacing {:.2f} wavelengths",
                                 geometry.dipole_length_wavelengths, geometry.element_spacing_wavelengths),
                     {{"azimuth bins", true, data}, {"pattern", false, line}}});
  std::vector<std::string> bounds;
  if (geometry.dipole_length_wavelengths <= 0.3 + 1e-9) bounds.push_back("the shortest dipole, 0.3");
  if (geometry.dipole_length_wavelengths >= 1.5 - 1e-9) bounds.push_back("the longest dipole, 1.5");
  if (geometry.element_spacing_wavelengths <= 0.05 * min_spacing_20 + 1e-9) bounds.push_back(fmt::format("the narrowest spacing, {:.1f}", 0.05 * min_spacing_20));
  if (geometry.element_spacing_wavelengths >= 0.05 * max_spacing_20 - 1e-9) bounds.push_back(fmt::format("the widest spacing, {:.2f}", 0.05 * max_spacing_20));
  const std::string evidence = fmt::format(
      "no cross-section beside the amplitude: the 90 % quantile per bin of range and azimuth ({} bins), its azimuth part over "
      "{} bins of |azimuth| follows eq. (6)'s pattern within {:.2f} dB RMS (flat: {:.2f} dB): {:.1f} dB at 30 deg, {:.1f} dB at "
      "60 deg{}",
      profile.cells, profile.points.size(), best_rms, flat_rms, pattern_at(deg_to_rad(30.0)), pattern_at(deg_to_rad(60.0)),
      bounds.empty() ? "" : fmt::format("; on the search's bound ({} wavelengths): the optimum may lie beyond it", fmt::join(bounds, ", ")));
  const auto support = static_cast<long long>(pool.detections);
  GridSpan dipole, spacing;
  for (const auto& [rms, d, sp] : scored) {
    if (near_least(rms, best_rms)) dipole.add(d), spacing.add(sp);
  }
  // Weak: on the search's bound, few bins, or the near-best patterns spread wide.
  const bool few_bins = profile.points.size() < 8;
  const bool dipole_weak = !bounds.empty() || few_bins || dipole.high - dipole.low > kWeakPatternSpanWavelengths;
  const bool spacing_weak = !bounds.empty() || few_bins || spacing.high - spacing.low > kWeakPatternSpanWavelengths;
  const std::string within = fmt::format("; the patterns within 10 % of the least RMS span dipole {:.2f}-{:.2f}, spacing {:.2f}-{:.2f}",
                                         dipole.low, dipole.high, spacing.low, spacing.high);
  return {with_interval({fields[0], round_to(geometry.dipole_length_wavelengths, 0.05), ValueSource::derived, evidence + within, support},
                        dipole.low, dipole.high, dipole_weak),
          with_interval({fields[1], round_to(geometry.element_spacing_wavelengths, 0.05), ValueSource::derived,
                         fmt::format("fitted with the dipole length, {:.1f} to {:.2f} (0.05 steps) so that eq. (7) stays invertible over "
                                     "the view field{}",
                                     0.05 * min_spacing_20, max_spacing, within),
                         support},
                        spacing.low, spacing.high, spacing_weak)};
}

std::vector<DerivedValue> derive_threshold(const std::vector<double>& sorted_db, AmplitudeUnit unit) {
  const double q_db = quantile_of_sorted(sorted_db, 0.001);
  const double threshold_db = std::floor(q_db * 2.0) / 2.0;
  const auto n = static_cast<long long>(sorted_db.size());
  const auto within_1db = std::upper_bound(sorted_db.begin(), sorted_db.end(), threshold_db + 1.0) - sorted_db.begin();
  // Its interval: from the lowest amplitude to the 1 % quantile; weak below 1000 detections (the
  // 0.1 % quantile then rests on less than one below it).
  const bool few = n < 1000;
  return {with_interval({"amplitude.detection_threshold_db", threshold_db, ValueSource::derived,
                         fmt::format("the {} histogram starts abruptly: lowest {:.2f} dB, 0.1 % quantile {:.2f}, 1 % {:.2f}; {:.1f} % "
                                     "within 1 dB above{}",
                                     unit == AmplitudeUnit::snr_db ? "SNR" : "amplitude", sorted_db.front(), q_db,
                                     quantile_of_sorted(sorted_db, 0.01), 100.0 * static_cast<double>(within_1db) / static_cast<double>(n),
                                     few ? "; weak: fewer than 1000 detections" : ""),
                         n},
                        std::min(threshold_db, sorted_db.front()), std::max(threshold_db, quantile_of_sorted(sorted_db, 0.01)), few)};
}

}  // namespace

std::vector<DerivedValue> derive_amplitude(const DetectionPool& pool, const nlohmann::json& base, double azimuth_half_deg,
                                           std::vector<DerivationFigure>& figures) {
  std::vector<double> amplitudes_db, log10_range, azimuth_rad, snr_minus_rcs_db;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) {
      amplitudes_db.push_back(d.amplitude_db);
      if (std::isnan(d.rcs_dbsm)) continue;
      log10_range.push_back(std::log10(std::max(d.range_m, 0.1)));
      azimuth_rad.push_back(d.azimuth_rad);
      snr_minus_rcs_db.push_back(d.amplitude_db - d.rcs_dbsm);
    }
  }
  std::vector<std::pair<double, double>> amplitude_at_range;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) amplitude_at_range.emplace_back(d.range_m, d.amplitude_db);
  }
  std::sort(amplitudes_db.begin(), amplitudes_db.end());
  std::vector<DerivedValue> values = derive_threshold(amplitudes_db, pool.amplitude_unit);
  const double threshold_db = values.front().value.get<double>();
  double far_m = 0.0;
  for (const auto& [r, a] : amplitude_at_range) far_m = std::max(far_m, r);
  figures.push_back({"Amplitude against range", "range / m", "amplitude / dB", "every detection (thinned); the line: the derived threshold",
                     {{"detections", true, thinned(amplitude_at_range, 4000)}, {"threshold", false, {{0.0, threshold_db}, {far_m, threshold_db}}}}});

  const auto n = static_cast<long long>(snr_minus_rcs_db.size());
  const std::vector<std::string> law_fields{"amplitude.snr_at_1m_for_1m2_db", "amplitude.range_exponent", "antenna.dipole_length_wavelengths",
                                            "antenna.element_spacing_wavelengths"};
  if (pool.amplitude_unit != AmplitudeUnit::snr_db || 10 * n < 9 * static_cast<long long>(amplitudes_db.size())) {
    // A level on the radar's own scale, or an SNR without the radar's RCS beside it: the level
    // mixes the law with the targets' unknown cross-sections, so only a replay can fit it.
    const std::string why = pool.amplitude_unit != AmplitudeUnit::snr_db
                                ? "the amplitude is on the radar's own scale (relative_db), not an SNR: the law is fitted by "
                                  "rcsim calibrate --real-drive (the count per object against range)"
                                : "the recordings hold no rcs_dbsm beside the SNR: the law cannot be told from the targets' "
                                  "cross-sections (rcsim calibrate --real-drive fits it)";
    for (std::size_t k = 0; k < 2; ++k) values.push_back({law_fields[k], nullptr, ValueSource::base, why, 0});
    const double max_spacing = max_invertible_spacing(azimuth_half_deg);
    for (DerivedValue& v : derive_relative_pattern(pool, base, max_spacing, figures)) values.push_back(std::move(v));
    return values;
  }
  // The radar equation with eq. (6)'s pattern: the pattern's exponent (one-way as the paper's, or
  // two-way), the dipole length and the spacing (as wide as keeps eq. (7) invertible over the view
  // field) whose pattern leaves the least residual per azimuth bin.
  AntennaGeometry geometry;
  const double max_spacing = max_invertible_spacing(azimuth_half_deg);
  const int max_spacing_20 = static_cast<int>(std::lround(20.0 * max_spacing));
  LawFit best;
  double best_score = INFINITY;
  struct Scored {
    double score;
    AntennaGeometry geometry;
    LawFit fit;
  };
  std::vector<Scored> scored;
  for (const double exponent : kPatternExponents) {
    for (int spacing_20 = 10; spacing_20 <= max_spacing_20; ++spacing_20) {
      for (int length_20 = 6; length_20 <= 30; ++length_20) {
        AntennaGeometry candidate = geometry;
        candidate.amplitude_pattern_exponent = exponent;
        candidate.dipole_length_wavelengths = 0.05 * length_20, candidate.element_spacing_wavelengths = 0.05 * spacing_20;
        const std::vector<double> pattern = pattern_db(azimuth_rad, candidate);
        std::vector<double> y(snr_minus_rcs_db.size());
        for (std::size_t i = 0; i < y.size(); ++i) y[i] = snr_minus_rcs_db[i] - pattern[i];
        const LawFit fit = fit_range_law(log10_range, y);
        const double score = azimuth_bias_db(azimuth_rad, log10_range, y, fit);
        scored.push_back({score, candidate, fit});
        if (score < best_score) best = fit, geometry = candidate, best_score = score;
      }
    }
  }
  // The paper's 1/R^4 with the same pattern, for comparison.
  const std::vector<double> pattern = pattern_db(azimuth_rad, geometry);
  double fourth_power_ss = 0.0, fourth_power_mean = 0.0;
  for (std::size_t i = 0; i < pattern.size(); ++i) fourth_power_mean += snr_minus_rcs_db[i] - pattern[i] + 40.0 * log10_range[i];
  fourth_power_mean /= static_cast<double>(pattern.size());
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const double r = snr_minus_rcs_db[i] - pattern[i] + 40.0 * log10_range[i] - fourth_power_mean;
    fourth_power_ss += r * r;
  }
  const std::string law = fmt::format("least squares of SNR - RCS = C - 10 n log10 R + eq. (6)'s pattern: C {:.2f} dB, n {:.3f}, "
                                      "residual {:.2f} dB (n = 4: {:.2f} dB)",
                                      best.constant_db, best.range_exponent, best.residual_rms_db,
                                      std::sqrt(fourth_power_ss / static_cast<double>(pattern.size())));
  // The intervals: the laws and patterns of every candidate within the objective's noise of the
  // best, each law widened by twice its standard errors.
  GridSpan constant, exponent_n, dipole, spacing, pattern_exponent;
  for (const Scored& c : scored) {
    if (!near_least(c.score, best_score)) continue;
    constant.add(c.fit.constant_db - 2.0 * c.fit.constant_se_db), constant.add(c.fit.constant_db + 2.0 * c.fit.constant_se_db);
    exponent_n.add(c.fit.range_exponent - 2.0 * c.fit.range_exponent_se), exponent_n.add(c.fit.range_exponent + 2.0 * c.fit.range_exponent_se);
    dipole.add(c.geometry.dipole_length_wavelengths), spacing.add(c.geometry.element_spacing_wavelengths);
    pattern_exponent.add(c.geometry.amplitude_pattern_exponent);
  }
  // Weak: fewer than 1000 detections with a cross-section, or the near-best laws spread over more
  // than 1 dB or 0.2 in n (the tolerances: +-0.5 dB, +-0.2).
  const bool few = n < 1000;
  const std::string within = fmt::format("; within 10 % of the least residual: C {:.2f}-{:.2f} dB, n {:.3f}-{:.3f} (with 2 standard errors), "
                                         "dipole {:.2f}-{:.2f}, spacing {:.2f}-{:.2f}, exponent {:g}-{:g}",
                                         constant.low, constant.high, exponent_n.low, exponent_n.high, dipole.low, dipole.high, spacing.low,
                                         spacing.high, pattern_exponent.low, pattern_exponent.high);
  values.push_back(with_interval({"amplitude.snr_at_1m_for_1m2_db", round_to(best.constant_db, 0.1), ValueSource::derived, law + within, n},
                                 constant.low, constant.high, few || constant.high - constant.low > 1.0));
  values.push_back(with_interval({"amplitude.range_exponent", round_to(best.range_exponent, 0.01), ValueSource::derived, law + within, n},
                                 exponent_n.low, exponent_n.high, few || exponent_n.high - exponent_n.low > 0.4));
  const MonopulseAntenna antenna(geometry);
  law_figures(best, geometry, log10_range, azimuth_rad, snr_minus_rcs_db, figures);
  const auto pattern_at = [&](double a_rad) { return amplitude_to_db(std::pow(antenna.sum_magnitude(a_rad), geometry.amplitude_pattern_exponent)); };
  const std::string pattern_evidence =
      fmt::format("the pattern (exponent 1 or 2, dipole 0.3-1.5 wavelengths, spacing 0.5-{:.2f} so that eq. (7) stays invertible "
                  "over the view field, 0.05 steps) that leaves the least residual per 0.025-rad bin of azimuth ({:.2f} dB RMS over the "
                  "bins): {:.1f} dB at 0.1 rad, {:.1f} dB at 0.25 rad",
                  max_spacing, best_score, pattern_at(0.1), pattern_at(0.25));
  values.push_back(with_interval({"antenna.amplitude_pattern_exponent", geometry.amplitude_pattern_exponent, ValueSource::derived,
                                  pattern_evidence + within, n},
                                 pattern_exponent.low, pattern_exponent.high, few || pattern_exponent.high > pattern_exponent.low));
  values.push_back(with_interval({"antenna.dipole_length_wavelengths", round_to(geometry.dipole_length_wavelengths, 0.05), ValueSource::derived,
                                  pattern_evidence + within, n},
                                 dipole.low, dipole.high, few || dipole.high - dipole.low > kWeakPatternSpanWavelengths));
  values.push_back(with_interval({"antenna.element_spacing_wavelengths", round_to(geometry.element_spacing_wavelengths, 0.05),
                                  ValueSource::derived, pattern_evidence + within, n},
                                 spacing.low, spacing.high, few || spacing.high - spacing.low > kWeakPatternSpanWavelengths));
  return values;
}

}  // namespace rcsim::replay::profile
