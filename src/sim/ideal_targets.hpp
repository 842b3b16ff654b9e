#pragma once
// The geometric ideal target list (paper II-B, IV-2/3).
#include <span>

#include "scene/scene.hpp"
#include "sim/culling.hpp"
#include "sim/stage_types.hpp"
#include "sim/visibility.hpp"

namespace rcsim {

// Where the sensor is and how it moves, in the world.
struct SensorKinematics {
  Pose2 X_WS;
  Vec2 v_WS_W = Vec2::Zero();
  // A radar that measures elevation: its height above the road and its pitch (boresight down
  // positive), from the mounting; the cycle's time sets the phase of limbs' and wheels' swing.
  double z_WS_m = 0.0;
  double pitch_rad = 0.0;
  double t_s = 0.0;
};

// The sensor's pose and velocity from the ego vehicle's motion and the mounting pose X_VS
// (the mounting offset adds omega x r to the sensor's velocity).
SensorKinematics sensor_kinematics(const BodyState& ego, const Pose2& X_VS);

// What compute_ideal_targets leaves out: plane reflectors (Fidelity::points_only) and the objects
// the broad phase culls (null: none).
struct IdealTargetFilter {
  bool planes = true;
  const CullingBounds* culling = nullptr;
  // With culling: set per object to 1 if it is visited and can lie on a line of sight to a point
  // in view (within max range + radius, not culled by the view wedge), else 0. The segment from
  // the sensor to a target in view lies inside the convex view wedge and within max range, so only
  // these objects can occlude (apply_occlusion). Range culling does not clear it.
  std::vector<unsigned char>* may_occlude = nullptr;
  // The sensor's diffuse face pieces (ExtendedObjects; 0: none) and their range extent (its cell).
  double diffuse_relative_ercs_per_sqrt_m = 0.0;
  DiffusePieceSize diffuse_piece;
  bool diffuse_on_box = false;  // the pieces on the object's box sides, not on its plane reflectors
  double box_side_inset_m = 0.0;  // the box's left and right sides this far inside (box_sides)
};

// Per reflection center of every object: range check, view-field check, visibility check;
// for each one that passes, range, azimuth, range rate (relative velocity of the reflecting
// point on the line of sight, a swinging limb's or wheel's swing included) and ERCS. Where the
// view has an elevation (FieldOfView::measures_elevation), in 3D: each reflector at its height,
// the sensor at its height and pitch, range and range rate along the slant line of sight,
// azimuth and elevation in the pitched sensor frame, the view checked in elevation too. Appends to `out` after clearing it. Without
// filter.culling every reflection center of every visited object (ascending indices) is visited.
void compute_ideal_targets(const FieldOfView& fov, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                           std::span<const BodyState> object_states, std::span<const std::uint32_t> visited,
                           IdealTargets& out, const IdealTargetFilter& filter = {});

}  // namespace rcsim
