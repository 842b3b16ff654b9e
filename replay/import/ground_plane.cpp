#include "replay/import/ground_plane.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim::replay {

std::optional<GroundPlaneFit> fit_ground_plane(const Recording& rec) {
  // Sums of the least-squares line z = a + b x through the box bottoms (x: horizontal distance).
  double n = 0.0, sum_x = 0.0, sum_z = 0.0, sum_xx = 0.0, sum_xz = 0.0, sum_zz = 0.0;
  for (std::size_t i = 0; i < rec.objects.size() && i < rec.boxes.size(); ++i) {
    const nlohmann::json& a = rec.objects[i].attributes;
    if (!a.is_object() || !a.contains("z_m") || !a.contains("height_m") || !a["z_m"].is_number() ||
        !a["height_m"].is_number() || rec.boxes[i].size() != 1) {
      continue;
    }
    const double bottom_m = a["z_m"].get<double>() - 0.5 * a["height_m"].get<double>();
    const double x_m = std::hypot(rec.boxes[i][0].x_m, rec.boxes[i][0].y_m);
    if (!std::isfinite(bottom_m) || !std::isfinite(x_m)) continue;
    n += 1.0, sum_x += x_m, sum_z += bottom_m, sum_xx += x_m * x_m, sum_xz += x_m * bottom_m, sum_zz += bottom_m * bottom_m;
  }
  constexpr double kMinBoxes = 10.0;
  const double spread = n * sum_xx - sum_x * sum_x;
  if (n < kMinBoxes || !(spread > 0.0)) return std::nullopt;
  const double slope = (n * sum_xz - sum_x * sum_z) / spread;
  const double intercept = (sum_z - slope * sum_x) / n;
  GroundPlaneFit fit;
  fit.pitch_rad = std::atan(slope);
  fit.z_m = -intercept * std::cos(fit.pitch_rad);
  fit.boxes = static_cast<int>(n);
  // sum of (z - a - b x)^2 from the sums
  const double residual2 = sum_zz - intercept * sum_z - slope * sum_xz;
  fit.residual_rms_m = std::sqrt(std::max(residual2, 0.0) / n);
  if (!(fit.z_m >= 0.1 && fit.z_m <= 5.0) || !(std::abs(fit.pitch_rad) <= deg_to_rad(10.0))) return std::nullopt;
  return fit;
}

std::string describe(const GroundPlaneFit& fit) {
  return fmt::format("the road {:.2f} m below the radar, pitched {:.2f} deg {} (a plane through {} box bottoms, {:.2f} m rms)",
                     fit.z_m, std::abs(rad_to_deg(fit.pitch_rad)), fit.pitch_rad >= 0.0 ? "down" : "up", fit.boxes,
                     fit.residual_rms_m);
}

}  // namespace rcsim::replay
