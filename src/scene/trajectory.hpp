#pragma once
// Smooth motion through trajectory samples: cubic Hermite interpolation of position (tangents
// from each sample's speed along its yaw) and of yaw (tangents from the yaw rates), so that
// velocity and yaw rate are the derivatives of the interpolated pose. Before the first and after
// the last sample the body moves on at that sample's speed and yaw rate (constant turn rate).
// Across a gap (a sample marked gap_after: the body is absent until the next one, e.g. an
// annotation gap of an imported recording) nothing is interpolated: each time in the gap takes
// the nearer sample's constant turn.
//
// A trajectory may also grow and shrink as it is used (streaming replay): append() adds samples
// at its end, drop_before() forgets those no longer needed; a time whose surrounding samples are
// held evaluates exactly as it would on the whole trajectory.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim {

struct TrajectorySample {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double speed_mps = 0.0;
  std::optional<double> yaw_rate_radps;
  std::optional<double> length_m;
  std::optional<double> width_m;
  bool gap_after = false;  // absent between this sample and the next: no interpolation
};

class Trajectory {
 public:
  Trajectory() = default;
  // Samples must be non-empty with strictly increasing times (the scene loader checks this).
  explicit Trajectory(const std::vector<TrajectorySample>& samples);

  BodyState state_at(double t_s) const;
  // A box holding the origin's position over [t0_s, t1_s] (t0_s <= t1_s), for the scene's broad
  // phase: each Hermite segment's piece lies in the convex hull of its Bezier control points, and a
  // constant-turn extrapolation stays within speed * |dt| of its node.
  Eigen::AlignedBox2d position_bounds(double t0_s, double t1_s) const;
  double start_s() const { return nodes_.front().t_s; }
  double end_s() const { return nodes_.back().t_s; }
  std::size_t size() const { return nodes_.size(); }
  bool empty() const { return nodes_.empty(); }

  // Adds a sample after the last one (time later, yaw rate given: no neighbour is known yet).
  void append(const TrajectorySample& sample);
  // Forgets the samples before the last one at or before t_s (times from t_s on keep evaluating
  // as before). Amortised: the storage moves only once half of it is forgotten.
  void drop_before(double t_s);

 private:
  struct Node {
    double t_s;
    Vec2 p_WB_W;
    double yaw_rad;  // unwrapped along the trajectory
    double speed_mps;
    double yaw_rate_radps;
    Vec2 v_W;  // speed_mps * (cos yaw, sin yaw), once per node instead of once per evaluation
    bool gap_after;
  };
  Node node_of(const TrajectorySample& s) const;  // yaw unwrapped after the last node
  BodyState extrapolate(const Node& node, double dt_s) const;
  std::vector<Node> nodes_;
};

}  // namespace rcsim
