#include "replay/import/ego_log.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/angles.hpp"
#include "common/input_error.hpp"

namespace rcsim::replay {

std::vector<EgoSample> ego_at_times(const std::vector<EgoSample>& log, const std::vector<double>& t_s,
                                    const std::filesystem::path& file) {
  std::vector<EgoSample> out;
  out.reserve(t_s.size());
  constexpr double kTolerance_s = 1e-6;  // a log written with microsecond times still covers its ends
  for (const double t_keyframe_s : t_s) {
    double t = t_keyframe_s;
    if (!log.empty()) {
      if (t < log.front().t_s && t >= log.front().t_s - kTolerance_s) t = log.front().t_s;
      if (t > log.back().t_s && t <= log.back().t_s + kTolerance_s) t = log.back().t_s;
    }
    if (log.empty() || t < log.front().t_s || t > log.back().t_s) {
      throw InputError(file.string(), "t_s",
                       fmt::format("the ego log covers {} to {} s but a keyframe is at {} s (times on the importer's "
                                   "clock: seconds since the first keyframe; nothing is extrapolated)",
                                   log.empty() ? 0.0 : log.front().t_s, log.empty() ? 0.0 : log.back().t_s,
                                   t_keyframe_s));
    }
    const auto hi = std::lower_bound(log.begin(), log.end(), t, [](const EgoSample& s, double v) { return s.t_s < v; });
    if (hi->t_s == t) {
      out.push_back(*hi);
      out.back().t_s = t_keyframe_s;
      continue;
    }
    out.push_back(interpolate_ego(*(hi - 1), *hi, t));
    out.back().t_s = t_keyframe_s;
  }
  return out;
}

nlohmann::json ego_difference_report(const std::vector<EgoSample>& log, const std::vector<EgoSample>& estimate) {
  const std::size_t n = std::min(log.size(), estimate.size());
  double speed_sum = 0.0, speed_sq = 0.0, rate_sum = 0.0, rate_sq = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double dv = estimate[k].speed_mps - log[k].speed_mps;
    const double dw = estimate[k].yaw_rate_radps - log[k].yaw_rate_radps;
    speed_sum += dv;
    speed_sq += dv * dv;
    rate_sum += dw;
    rate_sq += dw * dw;
  }
  const double m = std::max<double>(1.0, static_cast<double>(n));
  return {{"cycles", n},
          {"speed_difference_mean_mps", speed_sum / m},
          {"speed_difference_rms_mps", std::sqrt(speed_sq / m)},
          {"yaw_rate_difference_mean_radps", rate_sum / m},
          {"yaw_rate_difference_rms_radps", std::sqrt(rate_sq / m)},
          {"sign", "Doppler estimate minus ego log"}};
}

}  // namespace rcsim::replay
