// The view field as the detections show it (docs/sensor-profiles.md: "the largest |azimuth|",
// "the largest range"), by high quantiles so that one stray detection does not widen it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/angles.hpp"
#include "common/quantile.hpp"
#include "replay/profile/derivation_stages.hpp"

namespace rcsim::replay::profile {

double round_to(double x, double step) {
  // Divided by the steps per unit where they are whole (0.05: 20), so that 14 steps print 0.7, not
  // 0.7000000000000001.
  const double per_unit = 1.0 / step;
  if (std::abs(per_unit - std::round(per_unit)) < 1e-9) return std::round(x * per_unit) / std::round(per_unit);
  return std::round(x / step) * step;
}

namespace {

// The nearest detection must lie within this share of the farthest for the minimum range to be
// the radar's rather than the scene's (a highway's nearest is 12.6 m of 180 m: 7 %).
constexpr double kNearShare = 0.05;
// The antenna model covers the front half: a view field reaches less than 90 deg
// (src/sensor/sensor_config.cpp refuses 90 and beyond), so the widest it can hold in the derived
// 0.5-deg steps is 89.5 deg.
constexpr double kWidestHalfDeg = 89.5;
// Below this many detections the 0.1 % and 99.9 % quantiles rest on less than one detection each
// beyond them: the view field is read, but weakly.
constexpr long long kFewForQuantiles = 1000;

}  // namespace

std::vector<DerivedValue> derive_view_field(const DetectionPool& pool, std::vector<DerivationFigure>& figures) {
  std::vector<double> azimuth_deg, ranges_m;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) {
      azimuth_deg.push_back(rad_to_deg(d.azimuth_rad));
      ranges_m.push_back(d.range_m);
    }
  }
  std::sort(azimuth_deg.begin(), azimuth_deg.end());
  std::sort(ranges_m.begin(), ranges_m.end());
  const auto n = static_cast<long long>(ranges_m.size());
  std::vector<DerivedValue> values;
  // The view is symmetric: the half-width within which both sides report, the nearer of the
  // 0.1 % and 99.9 % quantiles (a wide imaging radar's outermost detections are sidelobes and
  // ghosts: the Astyx HiRes's reach 87 deg).
  const double right_deg = -quantile_of_sorted(azimuth_deg, 0.001), left_deg = quantile_of_sorted(azimuth_deg, 0.999);
  const double half_deg = std::min(right_deg, left_deg);
  const bool few = n < kFewForQuantiles;
  // The interval: from the nearer of the 0.5 % and 99.5 % quantiles to the nearer of the outermost.
  const double half_low_deg = std::min(-quantile_of_sorted(azimuth_deg, 0.005), quantile_of_sorted(azimuth_deg, 0.995));
  const double half_high_deg = std::min(-azimuth_deg.front(), azimuth_deg.back());
  std::string half_evidence = fmt::format("the nearer of the 0.1 % and 99.9 % quantiles of azimuth, {:.2f} and {:.2f} deg (outermost "
                                          "{:.2f} and {:.2f})",
                                          -right_deg, left_deg, azimuth_deg.front(), azimuth_deg.back());
  double half_value_deg = round_to(half_deg, 0.5);
  if (half_value_deg > kWidestHalfDeg) {
    // Detections beside the sensor (x about 0: a point cloud's side returns, ghosts) reach 90 deg,
    // which the antenna model (eq. (6), the front half) cannot hold: clamped, said so.
    const auto beyond = azimuth_deg.end() - std::lower_bound(azimuth_deg.begin(), azimuth_deg.end(), kWidestHalfDeg) +
                        (std::upper_bound(azimuth_deg.begin(), azimuth_deg.end(), -kWidestHalfDeg) - azimuth_deg.begin());
    half_evidence += fmt::format("; clamped from {:.1f} to {:.1f} deg, the antenna model's limit (it covers the front half, below 90 "
                                 "deg): {} detection(s) lie at {:.1f} deg or beyond, outside what the model can simulate",
                                 half_value_deg, kWidestHalfDeg, beyond, kWidestHalfDeg);
    half_value_deg = kWidestHalfDeg;
  }
  if (few) half_evidence += fmt::format("; weak: {} detections, the quantiles rest on less than one beyond them", n);
  values.push_back(with_interval({"field_of_view.azimuth_half_deg", half_value_deg, ValueSource::derived, half_evidence, n},
                                 std::min(half_low_deg, half_value_deg), std::max(half_high_deg, half_value_deg), few));
  const double max_range_m = quantile_of_sorted(ranges_m, 0.999);
  values.push_back(with_interval({"field_of_view.max_range_m", round_to(max_range_m, 1.0), ValueSource::derived,
                                  fmt::format("99.9 % quantile of range {:.1f} m (largest {:.1f}){}", max_range_m, ranges_m.back(),
                                              few ? "; weak: fewer than 1000 detections" : ""),
                                  n},
                                 quantile_of_sorted(ranges_m, 0.99), std::max(ranges_m.back(), round_to(max_range_m, 1.0)), few));
  const double nearest_m = ranges_m.front();
  if (nearest_m <= kNearShare * max_range_m) {
    const double min_range_m = std::floor(nearest_m * 10.0) / 10.0;
    values.push_back(with_interval({"field_of_view.min_range_m", min_range_m, ValueSource::derived,
                                    fmt::format("the nearest detection {:.2f} m (0.1 % quantile {:.2f})", nearest_m,
                                                quantile_of_sorted(ranges_m, 0.001)),
                                    n},
                                   min_range_m, std::max(min_range_m, quantile_of_sorted(ranges_m, 0.001)), few));
  } else {
    values.push_back({"field_of_view.min_range_m", nullptr, ValueSource::base,
                      fmt::format("not observable: the nearest detection is {:.1f} m, {:.0f} % of the farthest (the scene "
                                  "keeps away, not the radar)",
                                  nearest_m, 100.0 * nearest_m / max_range_m),
                      0});
  }
  DerivationFigure f{"Detections: range against azimuth", "azimuth / deg", "range / m",
                     "every detection (thinned); the lines: the derived view field", {}};
  std::vector<std::pair<double, double>> points;
  for (const PooledCycle& c : pool.cycles) {
    for (const PooledDetection& d : c.detections) points.emplace_back(rad_to_deg(d.azimuth_rad), d.range_m);
  }
  const double half = values[0].value.get<double>(), far = values[1].value.get<double>();
  f.series = {{"detections", true, thinned(points, 4000)},
              {"view field", false, {{-half, 0.0}, {-half, far}, {half, far}, {half, 0.0}}}};
  figures.push_back(std::move(f));
  return values;
}

}  // namespace rcsim::replay::profile
