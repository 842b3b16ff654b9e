#include "replay/run/object_figures.hpp"

#include <algorithm>
#include <cmath>

namespace rcsim::replay {

ObjectFigures::ObjectFigures(std::size_t sensors, std::size_t objects, double range_bin_m)
    : objects_(objects), range_bin_m_(range_bin_m), figures_(sensors * objects), recorded_(objects), simulated_(objects) {}

void ObjectFigures::add_cycle(const CycleComparison& cycle, const std::vector<metrics::BoxInSensor>& in_field) {
  if (in_field.empty()) return;
  std::fill(recorded_.begin(), recorded_.end(), 0);
  std::fill(simulated_.begin(), simulated_.end(), 0);
  for (const ComparedTarget& t : cycle.recorded) {
    if (t.target_class == metrics::TargetClass::object) ++recorded_[static_cast<std::size_t>(t.object)];
  }
  for (const ComparedTarget& t : cycle.simulated) {
    if (t.target_class == metrics::TargetClass::object) ++simulated_[static_cast<std::size_t>(t.object)];
  }
  for (const metrics::BoxInSensor& box : in_field) {
    const auto o = static_cast<std::size_t>(box.object);
    PerObject& f = figures_[static_cast<std::size_t>(cycle.sensor) * objects_ + o];
    const auto bin = static_cast<std::size_t>(std::max(0.0, std::floor(box.range_m / range_bin_m_)));
    if (f.by_range.size() <= bin) f.by_range.resize(bin + 1);
    for (Counts* c : {&f.all, &f.by_range[bin]}) {
      ++c->in_view;
      c->detected_recorded += recorded_[o] > 0;
      c->detected_simulated += simulated_[o] > 0;
      c->targets_recorded += recorded_[o];
      c->targets_simulated += simulated_[o];
    }
  }
}

void ObjectFigures::finish(ReplaySummary& summary) const {
  for (std::size_t i = 0; i < figures_.size(); ++i) {
    const PerObject& f = figures_[i];
    if (f.all.in_view == 0) continue;
    const int sensor = static_cast<int>(i / objects_), object = static_cast<int>(i % objects_);
    summary.objects.push_back({sensor, object, f.all.in_view, f.all.detected_recorded, f.all.detected_simulated,
                               f.all.targets_recorded, f.all.targets_simulated});
    for (std::size_t b = 0; b < f.by_range.size(); ++b) {
      const Counts& c = f.by_range[b];
      if (c.in_view == 0) continue;
      summary.object_ranges.push_back({sensor, object, static_cast<double>(b) * range_bin_m_,
                                       static_cast<double>(b + 1) * range_bin_m_, c.in_view, c.detected_recorded,
                                       c.detected_simulated, c.targets_recorded, c.targets_simulated});
    }
  }
}

}  // namespace rcsim::replay
