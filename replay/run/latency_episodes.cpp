#include "replay/run/latency_episodes.hpp"

namespace rcsim::replay {

LatencyEpisodes::LatencyEpisodes(std::size_t sensors, std::size_t objects)
    : objects_(objects),
      open_(sensors * objects),
      undetected_cycles_(sensors * objects, kEpisodeGapCycles),
      episodes_(sensors * objects, 0) {
  for (std::size_t s = 0; s < sensors; ++s) {
    for (std::size_t o = 0; o < objects; ++o) row(s, o) = {static_cast<int>(s), static_cast<int>(o), 0, -1.0, -1.0, -1.0};
  }
}

void LatencyEpisodes::close(std::size_t key) {
  LatencyRow& r = open_[key];
  if (r.detectable_from_s >= 0.0) closed_.push_back(r);
  r.detectable_from_s = r.first_recorded_s = r.first_simulated_s = -1.0;
}

void LatencyEpisodes::update_detected(std::size_t sensor, const std::vector<char>& detected, double t_s) {
  for (std::size_t o = 0; o < objects_; ++o) {
    const std::size_t key = sensor * objects_ + o;
    if (detected[o]) {
      if (open_[key].detectable_from_s < 0.0) {
        open_[key].detectable_from_s = t_s;
        open_[key].episode = episodes_[key]++;
      }
      undetected_cycles_[key] = 0;
    } else if (++undetected_cycles_[key] == kEpisodeGapCycles) {
      close(key);
    }
  }
}

void LatencyEpisodes::note_first_targets(std::size_t sensor, const CycleComparison& cycle, double t_s) {
  for (int origin = 0; origin < 2; ++origin) {
    for (const auto& t : origin == 0 ? cycle.recorded : cycle.simulated) {
      if (t.object < 0) continue;
      LatencyRow& r = row(sensor, static_cast<std::size_t>(t.object));
      double& first = origin == 0 ? r.first_recorded_s : r.first_simulated_s;
      if (r.detectable_from_s >= 0.0 && first < 0.0) first = t_s;
    }
  }
}

void LatencyEpisodes::finish(ReplaySummary& summary) {
  for (std::size_t key = 0; key < open_.size(); ++key) close(key);
  summary.latencies = std::move(closed_);
  closed_.clear();
  double rec_sum = 0.0, sim_sum = 0.0;
  for (const LatencyRow& r : summary.latencies) {
    if (r.first_recorded_s >= 0.0 && r.first_simulated_s >= 0.0) {
      rec_sum += r.first_recorded_s - r.detectable_from_s;
      sim_sum += r.first_simulated_s - r.detectable_from_s;
      ++summary.latency_pairs;
    }
  }
  if (summary.latency_pairs > 0) {
    summary.latency_recorded_s = rec_sum / summary.latency_pairs;
    summary.latency_simulated_s = sim_sum / summary.latency_pairs;
  }
}

}  // namespace rcsim::replay
