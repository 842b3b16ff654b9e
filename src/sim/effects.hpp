#pragma once
// Effects beyond the basic model, each off unless a scene asks for it (scene `effects`):
// occlusion, multiple back-and-forth reflections (paper V/VI, Fig. 17), clutter (paper VI).
#include <span>

#include "common/rng.hpp"
#include "scene/scene.hpp"
#include "sim/ideal_targets.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Is the segment a -> b blocked by the oriented box of length x width at pose X_WB?
bool segment_hits_box(const Vec2& a_W, const Vec2& b_W, const Pose2& X_WB, double length_m, double width_m);

// Ideal targets whose line of sight passes through the box of another object among the
// candidates (per object: 1 if it can occlude; its state must be valid) are removed, or with a
// finite `occlusion.loss_db` kept with their ERCS lowered by that loss (once, however many boxes).
void apply_occlusion(const OcclusionConfig& occlusion, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                     std::span<const BodyState> object_states, std::span<const unsigned char> candidates,
                     IdealTargets& ideal);

// The ERCS factor of a multibounce copy of order k >= 2: -loss_per_bounce_db per extra bounce,
// 10^(-loss (k - 1) / 20).
double multibounce_ercs_factor(const MultibounceConfig& config, int order);

// Paper VI: duplicates of each target nearer than max_range_m at k = 2..max_order times its
// range and range rate (the path runs k times back and forth), same angle, weaker by
// loss_per_bounce_db per extra round trip (on top of the longer range in eq. (1)).
void add_multibounce_targets(const MultibounceConfig& config, IdealTargets& ideal);

// Paper VI: sporadic false detections, Poisson many per cycle, uniform over the view field,
// with the range rate of a stationary point and amplitude above the threshold by an
// exponentially distributed excess.
void add_clutter(const SensorConfig& config, const SensorKinematics& sensor, Rng& rng, Detections& detections);

}  // namespace rcsim
