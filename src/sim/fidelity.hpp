#pragma once
// Named fidelity levels of the sensor cycle (docs/fidelity.md): which stages of the paper's
// Fig. 13 run in full and which are replaced by a cheaper stand-in.
#include <optional>
#include <string_view>

namespace rcsim {

enum class Fidelity {
  full,          // every stage and every effect the scene asks for
  no_monopulse,  // the cell's angle is its strongest reflector's ideal azimuth plus Gaussian noise, not eqs. (7)-(8)
  points_only,   // plane reflectors dropped: point reflection centers only
  no_tracking,   // the detections are the target list (ids = row index), no tracker (III-E)
};

// Standard deviation of the Gaussian angle noise that stands in for eqs. (7)-(8) at no_monopulse:
// 0.5 deg, the order of the srr24's monopulse angle scatter well above the threshold.
inline constexpr double kNoMonopulseAngleSigmaRad = 0.5 * 3.14159265358979323846 / 180.0;

// "full", "no_monopulse", "points_only", "no_tracking"; std::nullopt for any other name.
std::optional<Fidelity> parse_fidelity(std::string_view name);
std::string_view fidelity_name(Fidelity fidelity);
// The names above separated by " | " (for --help).
inline constexpr std::string_view kFidelityNames = "full | no_monopulse | points_only | no_tracking";

}  // namespace rcsim
