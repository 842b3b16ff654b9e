#include "replay/run/latency_episodes.hpp"

#include <algorithm>
#include <bit>

namespace rcsim::replay {

LatencyEpisodes::LatencyEpisodes(std::size_t sensors, std::size_t objects) : objects_(objects), open_(sensors * objects) {
  for (std::size_t s = 0; s < sensors; ++s) {
    for (std::size_t o = 0; o < objects; ++o) {
      open_[s * objects + o].row = {static_cast<int>(s), static_cast<int>(o), 0, -1.0, -1.0, -1.0};
    }
  }
  for (auto& seen : seen_) seen.assign(objects, 0);
}

void LatencyEpisodes::close(Open& open) {
  LatencyRow& r = open.row;
  if (r.detectable_from_s >= 0.0) closed_.push_back(r);
  r.detectable_from_s = r.first_recorded_s = r.first_simulated_s = -1.0;
  open.hits[0] = open.hits[1] = 0;
}

void LatencyEpisodes::update_detectable(std::size_t sensor, const std::vector<char>& detectable, double t_s) {
  for (std::size_t o = 0; o < objects_; ++o) {
    Open& open = open_[sensor * objects_ + o];
    if (detectable[o]) {
      if (open.row.detectable_from_s < 0.0) {
        open.row.detectable_from_s = t_s;
        open.row.episode = open.episodes++;
      }
      open.undetectable_cycles = 0;
    } else if (++open.undetectable_cycles == kEpisodeGapCycles) {
      close(open);
    }
  }
}

void LatencyEpisodes::note_targets(std::size_t sensor, const CycleComparison& cycle, double t_s) {
  for (int side = 0; side < 2; ++side) {
    std::fill(seen_[side].begin(), seen_[side].end(), 0);
    for (const ComparedTarget& t : side == 0 ? cycle.recorded : cycle.simulated) {
      if (t.target_class == metrics::TargetClass::object) seen_[side][static_cast<std::size_t>(t.object)] = 1;
    }
  }
  constexpr unsigned kWindowMask = (1u << kConfirmWindow) - 1u;
  for (std::size_t o = 0; o < objects_; ++o) {
    Open& open = open_[sensor * objects_ + o];
    if (open.row.detectable_from_s < 0.0) continue;
    for (int side = 0; side < 2; ++side) {
      open.hits[side] = ((open.hits[side] << 1) | (seen_[side][o] ? 1u : 0u)) & kWindowMask;
      double& confirmed_s = side == 0 ? open.row.first_recorded_s : open.row.first_simulated_s;
      if (confirmed_s < 0.0 && std::popcount(open.hits[side]) >= kConfirmHits) confirmed_s = t_s;
    }
  }
}

void LatencyEpisodes::finish(ReplaySummary& summary) {
  for (Open& open : open_) close(open);
  summary.latencies = std::move(closed_);
  closed_.clear();
  double sums[2] = {0.0, 0.0}, difference_sum_s = 0.0;
  int confirmed[2] = {0, 0};
  summary.latency_pairs = 0;
  for (const LatencyRow& r : summary.latencies) {
    const double latency_s[2] = {r.first_recorded_s < 0.0 ? -1.0 : r.first_recorded_s - r.detectable_from_s,
                                 r.first_simulated_s < 0.0 ? -1.0 : r.first_simulated_s - r.detectable_from_s};
    for (int side = 0; side < 2; ++side) {
      if (latency_s[side] >= 0.0) sums[side] += latency_s[side], ++confirmed[side];
    }
    if (latency_s[0] >= 0.0 && latency_s[1] >= 0.0) {
      difference_sum_s += latency_s[1] - latency_s[0];
      ++summary.latency_pairs;
    }
  }
  summary.latency_episodes = static_cast<int>(summary.latencies.size());
  summary.latency_unconfirmed_recorded = summary.latency_episodes - confirmed[0];
  summary.latency_unconfirmed_simulated = summary.latency_episodes - confirmed[1];
  summary.latency_recorded_s = confirmed[0] > 0 ? sums[0] / confirmed[0] : -1.0;
  summary.latency_simulated_s = confirmed[1] > 0 ? sums[1] / confirmed[1] : -1.0;
  summary.latency_difference_mean_s = summary.latency_pairs > 0 ? difference_sum_s / summary.latency_pairs : 0.0;
}

}  // namespace rcsim::replay
