#include "scene/trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim {

Trajectory::Trajectory(const std::vector<TrajectorySample>& samples) {
  nodes_.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    double yaw_rad = s.yaw_rad;
    if (i > 0) yaw_rad = nodes_.back().yaw_rad + angle_difference_rad(s.yaw_rad, nodes_.back().yaw_rad);
    nodes_.push_back({s.t_s, Vec2(s.x_m, s.y_m), yaw_rad, s.speed_mps, 0.0,
                      s.speed_mps * Vec2(std::cos(yaw_rad), std::sin(yaw_rad))});
  }
  // Yaw rates not given are the (central, at the ends one-sided) differences of the unwrapped yaw.
  const std::size_t n = nodes_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (samples[i].yaw_rate_radps) {
      nodes_[i].yaw_rate_radps = *samples[i].yaw_rate_radps;
    } else if (n > 1) {
      const std::size_t a = i == 0 ? 0 : i - 1;
      const std::size_t b = i + 1 == n ? n - 1 : i + 1;
      nodes_[i].yaw_rate_radps = (nodes_[b].yaw_rad - nodes_[a].yaw_rad) / (nodes_[b].t_s - nodes_[a].t_s);
    }
  }
}

BodyState Trajectory::extrapolate(const Node& node, double dt_s) const {
  // Constant speed and yaw rate from the node (the exact integral of a constant turn).
  const double w = node.yaw_rate_radps;
  const double yaw_rad = node.yaw_rad + w * dt_s;
  Vec2 p = node.p_W;
  if (std::abs(w * dt_s) < 1e-9) {
    const double mid_yaw_rad = node.yaw_rad + 0.5 * w * dt_s;
    p += node.speed_mps * dt_s * Vec2(std::cos(mid_yaw_rad), std::sin(mid_yaw_rad));
  } else {
    const double r = node.speed_mps / w;
    p += Vec2(r * (std::sin(yaw_rad) - std::sin(node.yaw_rad)), -r * (std::cos(yaw_rad) - std::cos(node.yaw_rad)));
  }
  BodyState state;
  state.X_WB = {p.x(), p.y(), wrap_angle_rad(yaw_rad)};
  state.v_WB_W = node.speed_mps * Vec2(std::cos(yaw_rad), std::sin(yaw_rad));
  state.yaw_rate_radps = w;
  return state;
}

BodyState Trajectory::state_at(double t_s) const {
  if (nodes_.size() == 1 || t_s <= nodes_.front().t_s) return extrapolate(nodes_.front(), t_s - nodes_.front().t_s);
  if (t_s >= nodes_.back().t_s) return extrapolate(nodes_.back(), t_s - nodes_.back().t_s);
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t_s,
                                   [](double t, const Node& node) { return t < node.t_s; });
  const Node& a = *(it - 1);
  const Node& b = *it;
  const double h = b.t_s - a.t_s;
  const double s = (t_s - a.t_s) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  // Cubic Hermite basis and its derivative with respect to s.
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
  const Vec2& va = a.v_W;
  const Vec2& vb = b.v_W;
  BodyState state;
  const Vec2 p = h00 * a.p_W + h10 * h * va + h01 * b.p_W + h11 * h * vb;
  const double yaw_rad = h00 * a.yaw_rad + h10 * h * a.yaw_rate_radps + h01 * b.yaw_rad + h11 * h * b.yaw_rate_radps;
  state.X_WB = {p.x(), p.y(), wrap_angle_rad(yaw_rad)};
  state.v_WB_W = (d00 * a.p_W + d10 * h * va + d01 * b.p_W + d11 * h * vb) / h;
  state.yaw_rate_radps = (d00 * a.yaw_rad + d10 * h * a.yaw_rate_radps + d01 * b.yaw_rad + d11 * h * b.yaw_rate_radps) / h;
  return state;
}

}  // namespace rcsim
