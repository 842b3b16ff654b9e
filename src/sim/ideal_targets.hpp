#pragma once
// The geometric ideal target list (paper II-B, IV-2/3).
#include <span>

#include "scene/scene.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Where the sensor is and how it moves, in the world.
struct SensorKinematics {
  Pose2 X_WS;
  Vec2 v_WS_W = Vec2::Zero();
};

// The sensor's pose and velocity from the ego vehicle's motion and the mounting pose X_VS
// (the mounting offset adds omega x r to the sensor's velocity).
SensorKinematics sensor_kinematics(const BodyState& ego, const Pose2& X_VS);

// Per reflection center of every object: range check, view-field check, visibility check;
// for each one that passes, range, azimuth, range rate (relative velocity of the reflecting
// point on the line of sight) and ERCS. Appends to `out` after clearing it. `bounding_radius_m`
// holds each object's ObjectModel::bounding_radius_m(), computed once per scene.
void compute_ideal_targets(const FieldOfView& fov, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                           std::span<const BodyState> object_states, std::span<const unsigned char> present,
                           std::span<const double> bounding_radius_m,
                           IdealTargets& out);

}  // namespace rcsim
