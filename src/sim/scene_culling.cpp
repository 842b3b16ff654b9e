#include "sim/scene_culling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rcsim {
namespace {

constexpr double kSliceS = 0.5;                  // a car at 40 m/s sweeps 20 m of box per slice
constexpr std::size_t kMaxEntries = 1u << 18;    // about 12 MB at most, however long the scene
constexpr double kMarginM = 1.0;                 // beyond compute_ideal_targets' 1 mm
constexpr double kRelativeMargin = 1e-6;         // rounding far from the origin

bool present_within(const SceneObject& object, double t0_s, double t1_s) {
  if (object.presence.empty()) return true;
  return std::any_of(object.presence.begin(), object.presence.end(),
                     [&](const TimeInterval& i) { return i.from_s <= t1_s && i.until_s >= t0_s; });
}

}  // namespace

SceneCulling::SceneCulling(const Scene& scene, std::span<const double> reflection_radius_m)
    : SceneCulling(scene, reflection_radius_m, scene.cycle_time_at(0),
                   scene.cycle_count() > 0 ? scene.cycle_time_at(scene.cycle_count() - 1)
                                           : -std::numeric_limits<double>::infinity()) {}

SceneCulling::SceneCulling(const Scene& scene, std::span<const double> reflection_radius_m, double t0_s,
                           double t1_s) {
  if (!(t1_s >= t0_s) || scene.sensors.empty() || reflection_radius_m.size() != scene.objects.size()) return;
  // compute_ideal_targets visits an object only within max range + reflection radius of the
  // sensor, and lets it occlude within max range + radius + 1 mm (+ 1e-9 of the distance).
  double max_range_m = 0.0;
  for (const auto& s : scene.sensors) max_range_m = std::max(max_range_m, s.config.fov.max_range_m);
  if (!std::isfinite(max_range_m)) return;
  t0_s_ = t0_s;
  t1_s_ = t1_s;
  const std::size_t per_slice = std::max<std::size_t>(scene.objects.size(), 1);
  const double span_s = t1_s_ - t0_s_;
  const double max_slices = static_cast<double>(std::max<std::size_t>(kMaxEntries / per_slice, 1));
  // Clamped as a double, so that a huge span cannot overflow the conversion.
  slice_count_ = static_cast<std::size_t>(std::clamp(std::ceil(span_s / kSliceS), 1.0, max_slices));
  slice_s_ = span_s > 0.0 ? span_s / static_cast<double>(slice_count_) : 1.0;
  slice_begin_.reserve(slice_count_ + 1);
  for (std::size_t k = 0; k < slice_count_; ++k) {
    slice_begin_.push_back(entries_.size());
    const double from_s = t0_s_ + static_cast<double>(k) * slice_s_;
    const double until_s = k + 1 == slice_count_ ? t1_s_ : from_s + slice_s_;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const SceneObject& object = scene.objects[i];
      if (!present_within(object, from_s, until_s)) continue;
      Entry e{object.trajectory.position_bounds(from_s, until_s), 0.0, static_cast<std::uint32_t>(i)};
      const double magnitude_m = std::max(e.box_W.min().cwiseAbs().maxCoeff(), e.box_W.max().cwiseAbs().maxCoeff());
      e.reach_m = max_range_m + reflection_radius_m[i] + kMarginM + kRelativeMargin * magnitude_m;
      entries_.push_back(e);
    }
  }
  slice_begin_.push_back(entries_.size());
}

void SceneCulling::select(double t_s, std::span<const Vec2> p_WS_W, std::span<const SceneObject> objects,
                          std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!enabled() || !(t_s >= t0_s_ && t_s <= t1_s_)) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].present_at(t_s)) out.push_back(static_cast<std::uint32_t>(i));
    }
    return;
  }
  const auto k = std::min(static_cast<std::size_t>((t_s - t0_s_) / slice_s_), slice_count_ - 1);
  // A time on a slice boundary belongs to both; the box of the slice it falls in holds it.
  for (std::size_t n = slice_begin_[k]; n < slice_begin_[k + 1]; ++n) {
    const Entry& e = entries_[n];
    const bool near = std::any_of(p_WS_W.begin(), p_WS_W.end(), [&](const Vec2& p) {
      return e.box_W.squaredExteriorDistance(p) <= e.reach_m * e.reach_m;
    });
    if (near && objects[e.object].present_at(t_s)) out.push_back(e.object);
  }
}

}  // namespace rcsim
