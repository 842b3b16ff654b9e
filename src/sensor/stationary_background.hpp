#pragma once
// The stationary world a sensor sees that no scene holds (guard rails, signs, the road): a density
// of targets over range and azimuth fitted from recordings' stationary background (paper VI:
// "add misdetections randomly"; docs/static-world.md). Part of a sensor configuration
// (`background`, schemas/sensor-config.md); `rcsim calibrate --real-drive` fits it.
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/json_reader.hpp"

namespace rcsim {

inline constexpr int kAmplitudeQuantiles = 11;  // deciles: 0, 10, ..., 100 %

struct StationaryBackground {
  std::string fitted_on;          // the recordings it was fitted on, for people
  double targets_per_cycle = 0.0;  // mean count per sensor cycle (Poisson); 0: none
  std::vector<double> range_edges_m;      // bins: [edge k, edge k+1)
  std::vector<double> azimuth_edges_rad;  // sensor frame, increasing
  std::vector<double> weights;  // per range bin, then azimuth bin (row-major); sums to 1
  // Per range bin, the amplitude (dB) at the deciles of the targets in that bin.
  std::vector<std::array<double, kAmplitudeQuantiles>> amplitude_deciles_db;

  bool empty() const { return !(targets_per_cycle > 0.0); }
  std::size_t range_bins() const { return range_edges_m.size() - 1; }
  std::size_t azimuth_bins() const { return azimuth_edges_rad.size() - 1; }
};

// Reads the `background` section; every field checked, errors name the field.
StationaryBackground parse_stationary_background(const JsonField& field);
// The same section as JSON (angles in degrees, as people read them).
nlohmann::ordered_json stationary_background_to_json(const StationaryBackground& background);

}  // namespace rcsim
