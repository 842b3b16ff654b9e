#pragma once
// A dataset importer's ego log given by the user (`rcsim import --from DATASET --ego-log FILE`):
// ego.csv's columns on the importer's clock, at any rate, interpolated to the keyframe times; and
// how far the Doppler estimate of the stationary world is from it, as a cross-check.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "io/recording.hpp"

namespace rcsim::replay {

// The log at each of t_s (increasing): linear in x, y, speed and yaw rate, along the shorter arc
// in yaw. A time outside the log's span (by more than 1 us) is refused (InputError naming
// `file`): nothing is extrapolated.
std::vector<EgoSample> ego_at_times(const std::vector<EgoSample>& log, const std::vector<double>& t_s,
                                    const std::filesystem::path& file);

// Speed and yaw rate of `estimate` minus those of `log` (same cycles): mean and RMS of each.
nlohmann::json ego_difference_report(const std::vector<EgoSample>& log, const std::vector<EgoSample>& estimate);

}  // namespace rcsim::replay
