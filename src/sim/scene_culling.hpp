#pragma once
// The scene's broad phase (docs/fidelity.md, "Culling"): which objects a cycle needs at all. The sensors' own culling
// (culling.hpp) visits only objects within max range + reflection radius of the sensor; this
// stage finds them without evaluating every object's trajectory. The scene's run is cut into time
// slices; per slice, a box holds each object's origin while it is present
// (Trajectory::position_bounds). A cycle tests the sensors' positions against the boxes of its
// slice only, and objects out of every sensor's reach are neither evaluated nor visited.
#include <cstdint>
#include <span>
#include <vector>

#include "common/pose2.hpp"
#include "scene/scene.hpp"

namespace rcsim {

class SceneCulling {
 public:
  // Without a scene: every present object is selected (culling off).
  SceneCulling() = default;
  // `reflection_radius_m`: per object, the circle about its origin holding every reflection
  // point (reflection_radius_m in culling.hpp).
  SceneCulling(const Scene& scene, std::span<const double> reflection_radius_m);
  // The same over the scene times [t0_s, t1_s] only (a streaming replay, whose trajectories hold
  // only a window of the drive); times outside it visit every present object.
  SceneCulling(const Scene& scene, std::span<const double> reflection_radius_m, double t0_s, double t1_s);

  // Replaces `out` with the ascending indices of the objects present at t_s that may lie within
  // reach of a sensor at one of the positions p_WS_W. Outside the scene's cycle times (or culling
  // off) those are all present objects.
  void select(double t_s, std::span<const Vec2> p_WS_W, std::span<const SceneObject> objects,
              std::vector<std::uint32_t>& out) const;

  bool enabled() const { return slice_count_ > 0; }
  std::size_t slice_count() const { return slice_count_; }
  double slice_s() const { return slice_s_; }

 private:
  struct Entry {
    Eigen::AlignedBox2d box_W;  // the origin's positions within the slice
    double reach_m;             // a sensor farther than this from the box cannot need the object
    std::uint32_t object;
  };
  double t0_s_ = 0.0;
  double t1_s_ = 0.0;
  double slice_s_ = 0.0;
  std::size_t slice_count_ = 0;
  std::vector<std::size_t> slice_begin_;  // slice k: entries_[slice_begin_[k], slice_begin_[k + 1])
  std::vector<Entry> entries_;
};

}  // namespace rcsim
