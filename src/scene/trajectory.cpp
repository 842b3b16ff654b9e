#include "scene/trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "common/angles.hpp"

namespace rcsim {

Trajectory::Node Trajectory::node_of(const TrajectorySample& s) const {
  double yaw_rad = s.yaw_rad;
  if (!nodes_.empty()) yaw_rad = nodes_.back().yaw_rad + angle_difference_rad(s.yaw_rad, nodes_.back().yaw_rad);
  return {s.t_s,     Vec2(s.x_m, s.y_m), yaw_rad, s.speed_mps, s.yaw_rate_radps.value_or(0.0),
          s.speed_mps * Vec2(std::cos(yaw_rad), std::sin(yaw_rad)), s.gap_after};
}

void Trajectory::append(const TrajectorySample& sample) {
  if (!sample.yaw_rate_radps) throw std::invalid_argument("Trajectory::append: a sample needs its yaw rate");
  if (!nodes_.empty() && !(sample.t_s > nodes_.back().t_s)) {
    throw std::invalid_argument("Trajectory::append: times must increase");
  }
  nodes_.push_back(node_of(sample));
}

void Trajectory::drop_before(double t_s) {
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t_s,
                                   [](double t, const Node& node) { return t < node.t_s; });
  if (it == nodes_.begin()) return;
  const auto forgettable = static_cast<std::size_t>(it - 1 - nodes_.begin());  // keep the one at or before t_s
  if (forgettable > 0 && 2 * forgettable >= nodes_.size()) {
    nodes_.erase(nodes_.begin(), nodes_.begin() + static_cast<std::ptrdiff_t>(forgettable));
  }
}

Trajectory::Trajectory(const std::vector<TrajectorySample>& samples) {
  nodes_.reserve(samples.size());
  for (const auto& s : samples) nodes_.push_back(node_of(s));
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
  Vec2 p = node.p_WB_W;
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
  if (nodes_.empty()) return {};
  if (nodes_.size() == 1 || t_s <= nodes_.front().t_s) return extrapolate(nodes_.front(), t_s - nodes_.front().t_s);
  if (t_s >= nodes_.back().t_s) return extrapolate(nodes_.back(), t_s - nodes_.back().t_s);
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t_s,
                                   [](double t, const Node& node) { return t < node.t_s; });
  const Node& a = *(it - 1);
  const Node& b = *it;
  if (a.gap_after) return t_s - a.t_s <= b.t_s - t_s ? extrapolate(a, t_s - a.t_s) : extrapolate(b, t_s - b.t_s);
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
  const Vec2 p = h00 * a.p_WB_W + h10 * h * va + h01 * b.p_WB_W + h11 * h * vb;
  const double yaw_rad = h00 * a.yaw_rad + h10 * h * a.yaw_rate_radps + h01 * b.yaw_rad + h11 * h * b.yaw_rate_radps;
  state.X_WB = {p.x(), p.y(), wrap_angle_rad(yaw_rad)};
  state.v_WB_W = (d00 * a.p_WB_W + d10 * h * va + d01 * b.p_WB_W + d11 * h * vb) / h;
  state.yaw_rate_radps = (d00 * a.yaw_rad + d10 * h * a.yaw_rate_radps + d01 * b.yaw_rad + d11 * h * b.yaw_rate_radps) / h;
  return state;
}

Eigen::AlignedBox2d Trajectory::position_bounds(double t0_s, double t1_s) const {
  Eigen::AlignedBox2d box;  // empty
  if (nodes_.empty()) return box;
  // Extrapolation from a node over dt in [dt0, dt1]: the path has length |speed| |dt| at most.
  const auto add_extrapolated = [&](const Node& node, double dt0_s, double dt1_s) {
    const double reach_m = std::abs(node.speed_mps) * std::max(std::abs(dt0_s), std::abs(dt1_s));
    box.extend(node.p_WB_W - Vec2::Constant(reach_m));
    box.extend(node.p_WB_W + Vec2::Constant(reach_m));
  };
  const Node& first = nodes_.front();
  const Node& last = nodes_.back();
  if (nodes_.size() == 1) {
    add_extrapolated(first, t0_s - first.t_s, t1_s - first.t_s);
    return box;
  }
  if (t0_s < first.t_s) add_extrapolated(first, t0_s - first.t_s, std::min(t1_s, first.t_s) - first.t_s);
  // From the last node on (t1 = the last node's time included: no segment holds it alone).
  if (t1_s >= last.t_s) add_extrapolated(last, std::max(t0_s, last.t_s) - last.t_s, t1_s - last.t_s);
  // Segments [a, b] overlapping [t0, t1]: the cubic of state_at in Bezier form has the control
  // points p_a, p_a + h v_a / 3, p_b - h v_b / 3, p_b; its piece over [u, v] of the segment's
  // parameter has the control points of the blossom at (u,u,u), (u,u,v), (u,v,v), (v,v,v).
  auto it = std::upper_bound(nodes_.begin(), nodes_.end(), t0_s,
                             [](double t, const Node& node) { return t < node.t_s; });
  if (it != nodes_.begin()) --it;
  for (; it + 1 != nodes_.end() && it->t_s <= t1_s; ++it) {
    const Node& a = *it;
    const Node& b = *(it + 1);
    if (b.t_s < t0_s) continue;
    if (a.gap_after) {  // each end's constant turn over its part of [t0, t1]
      const double from_s = std::max(t0_s, a.t_s), until_s = std::min(t1_s, b.t_s);
      add_extrapolated(a, from_s - a.t_s, until_s - a.t_s);
      add_extrapolated(b, from_s - b.t_s, until_s - b.t_s);
      continue;
    }
    const double h_s = b.t_s - a.t_s;
    const std::array<Vec2, 4> control = {a.p_WB_W, a.p_WB_W + (h_s / 3.0) * a.v_W, b.p_WB_W - (h_s / 3.0) * b.v_W, b.p_WB_W};
    const auto blossom = [&](double s1, double s2, double s3) {
      const auto lerp = [](const Vec2& p, const Vec2& q, double s) -> Vec2 { return p + s * (q - p); };
      const Vec2 q0 = lerp(control[0], control[1], s1), q1 = lerp(control[1], control[2], s1),
                 q2 = lerp(control[2], control[3], s1);
      return lerp(lerp(q0, q1, s2), lerp(q1, q2, s2), s3);
    };
    const double u = std::clamp((t0_s - a.t_s) / h_s, 0.0, 1.0);
    const double v = std::clamp((t1_s - a.t_s) / h_s, 0.0, 1.0);
    box.extend(blossom(u, u, u));
    box.extend(blossom(u, u, v));
    box.extend(blossom(u, v, v));
    box.extend(blossom(v, v, v));
  }
  return box;
}

}  // namespace rcsim
