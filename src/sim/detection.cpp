#include "sim/detection.hpp"

#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <algorithm>
#include <cmath>

#include "common/decibel.hpp"

namespace rcsim {

double detection_probability(Fluctuation fluctuation, double mean_level_db, double threshold_db, double noise_sigma) {
  const double signal_power = db_to_power(mean_level_db);
  const double threshold_power = db_to_power(threshold_db);
  const double noise_power = noise_sigma * noise_sigma;
  switch (fluctuation) {
    case Fluctuation::none: {
      if (noise_power == 0.0) return signal_power >= threshold_power ? 1.0 : 0.0;
      // |H + n|^2 / (s2 / 2) is non-central chi-square, 2 degrees of freedom, lambda = 2 S / s2.
      const boost::math::non_central_chi_squared_distribution<double> measured(2.0, 2.0 * signal_power / noise_power);
      return boost::math::cdf(boost::math::complement(measured, 2.0 * threshold_power / noise_power));
    }
    case Fluctuation::swerling1:
      return std::exp(-threshold_power / (noise_power + signal_power));
    case Fluctuation::swerling3: {
      const double half = 0.5 * signal_power;
      const double spread = noise_power + half;
      return std::exp(-threshold_power / spread) * (1.0 + half * threshold_power / (spread * spread));
    }
  }
  return 0.0;
}

double detection_floor_db(const SensorConfig& config) {
  const double threshold_db = config.amplitude.detection_threshold_db;
  const Fluctuation fluctuation = config.detection.fluctuation;
  if (fluctuation == Fluctuation::none) return threshold_db;
  // The curve rises monotonically with the mean level: bisect on it, 120 dB below the threshold
  // to the threshold (where a fluctuating target is detected with probability > 1e-6 anyway).
  double low_db = threshold_db - 120.0, high_db = threshold_db;
  for (int i = 0; i < 60; ++i) {
    const double mid_db = 0.5 * (low_db + high_db);
    const double pd = detection_probability(fluctuation, mid_db, threshold_db, pointer_noise_amplitude(config));
    (pd < kNegligibleDetectionProbability ? low_db : high_db) = mid_db;
  }
  return low_db;
}

void apply_fluctuation(Fluctuation fluctuation, Rng& rng, ResolutionCells& cells) {
  if (fluctuation == Fluctuation::none) return;
  for (auto& c : cells) {
    const double power_factor = fluctuation == Fluctuation::swerling1
                                    ? rng.exponential(1.0)
                                    : 0.5 * (rng.exponential(1.0) + rng.exponential(1.0));
    const double amplitude_factor = std::sqrt(power_factor);
    c.sum_pointer *= amplitude_factor;
    c.delta_pointer *= amplitude_factor;
  }
}

void keep_local_maxima(const ResolutionCell& cell, Detections& detections, LocalMaximaBuffers& buffers) {
  // Neighbours are the eight map cells around a detection's own (map_cell_index), as a peak search
  // over the FFT's bins compares; two of them lie less than two cells apart in range.
  const double range_window_m = 2.0 * cell.range_cell_m;
  const std::size_t n = detections.size();
  auto& order = buffers.by_range;
  order.resize(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return detections[a].range_m < detections[b].range_m;
  });
  const auto range_of = [&](std::size_t k) { return detections[order[k]].range_m; };
  const auto neighbours = [&](const Detection& a, const Detection& b) {
    return std::abs(map_cell_index(a.range_m, cell.range_cell_m) - map_cell_index(b.range_m, cell.range_cell_m)) <= 1.0 &&
           std::abs(map_cell_index(a.range_rate_mps, cell.range_rate_cell_mps) -
                    map_cell_index(b.range_rate_mps, cell.range_rate_cell_mps)) <= 1.0 &&
           // cells in elevation: a peak of another elevation cell beside is a peak of its own
           (!cell.resolves_elevation() || std::abs(map_cell_index(a.elevation_rad, cell.elevation_cell_rad) -
                                                   map_cell_index(b.elevation_rad, cell.elevation_cell_rad)) <= 1.0);
  };
  // `other` dominates `self`: in a neighbouring cell (or the same) and stronger (or as strong and earlier).
  const auto dominates = [&](std::size_t other, std::size_t self) {
    const Detection& o = detections[other];
    const Detection& d = detections[self];
    if (!neighbours(o, d)) return false;
    return o.amplitude_db > d.amplitude_db || (o.amplitude_db == d.amplitude_db && other < self);
  };
  buffers.peak.assign(n, 1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t self = order[k];
    bool peak = true;
    for (std::size_t j = k; peak && j-- > 0 && range_of(k) - range_of(j) < range_window_m;) peak = !dominates(order[j], self);
    for (std::size_t j = k + 1; peak && j < n && range_of(j) - range_of(k) < range_window_m; ++j) {
      peak = !dominates(order[j], self);
    }
    buffers.peak[self] = peak ? 1 : 0;
  }
  std::size_t i = 0;
  std::erase_if(detections, [&](const Detection&) { return buffers.peak[i++] == 0; });
}

}  // namespace rcsim
