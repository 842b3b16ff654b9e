// The assignment of a point-cloud replay (issue 52), frame by frame: replays a recording (e.g.
// the Astyx frames, scripts/bench-pointcloud.sh) without matching, keeps each sensor cycle's
// recorded and simulated positions, then times GOSPA (c = 2 m, p = 2, the replay's defaults) on
// each by the sparse exact assignment (metrics::gospa) and by the dense assignment on each
// connected component (metrics::detail::gospa_dense_components, the way before), on all targets
// and on the object targets alike, and checks them equal: GOSPA, its parts and OSPA to 1e-9; the
// frames whose pairs differ, and of them those whose matched positions differ too (pairs that
// differ only between targets at identical positions are equal-cost optima).
//   usage: rcsim_bench_pointcloud RECORDING_DIR [FRAMES_OUT]   (--help: the usage)
// FRAMES_OUT: the cycles' positions as text ("cycle side x_m y_m", side 0 recorded, 1 simulated)
// for a timing of scipy's linear_sum_assignment on the same frames; derived from the recording,
// so keep it beside the data, never in the repository.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "metrics/gospa.hpp"
#include "replay/run/replay_run.hpp"
#include "tool_arguments.hpp"

namespace {

using namespace rcsim;
using SteadyClock = std::chrono::steady_clock;

struct Frame {
  std::vector<Vec2> recorded, simulated, recorded_object, simulated_object;
};

// Keeps each cycle's positions (the replay runs without matching: the positions are all it needs).
class FrameSink final : public replay::ReplaySink {
 public:
  void begin_run(const Recording&, const replay::ImportedScene&, const Scene&, const replay::ReplayOptions&) override {}
  void add_cycle(const replay::CycleComparison& cycle) override {
    Frame f;
    for (const auto& t : cycle.recorded) {
      f.recorded.push_back(t.p_ST_S);
      if (t.target_class == metrics::TargetClass::object) f.recorded_object.push_back(t.p_ST_S);
    }
    for (const auto& t : cycle.simulated) {
      f.simulated.push_back(t.p_ST_S);
      if (t.target_class == metrics::TargetClass::object) f.simulated_object.push_back(t.p_ST_S);
    }
    frames.push_back(std::move(f));
  }
  void end_run(const replay::ReplaySummary&) override {}
  std::vector<Frame> frames;
};

double seconds_since(SteadyClock::time_point start) { return std::chrono::duration<double>(SteadyClock::now() - start).count(); }

bool same_figures(const metrics::GospaResult& a, const metrics::GospaResult& b) {
  const auto near = [](double x, double y) { return std::abs(x - y) <= 1e-9; };
  return a.assigned == b.assigned && a.missed == b.missed && a.false_targets == b.false_targets &&
         near(a.gospa_m, b.gospa_m) && near(a.localisation_mp, b.localisation_mp) && near(a.missed_mp, b.missed_mp) &&
         near(a.false_mp, b.false_mp) && near(a.ospa_m, b.ospa_m);
}

// Pairs closer than c (all pairs tested: the bench's own count, untimed).
long long pairs_within(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c) {
  long long n = 0;
  for (const Vec2& a : x) {
    for (const Vec2& b : y) n += (a - b).norm() < c ? 1 : 0;
  }
  return n;
}

struct Timing {
  double sparse_s = 0.0, dense_s = 0.0;
  // Frames whose pairs differ; of them, those not explained by targets at identical positions
  // (equal-cost optima: a recorded point cloud holds points that differ in height or Doppler only).
  int frames = 0, figures_differ = 0, pairs_differ = 0, positions_differ = 0;
};

// The matched pairs as positions, sorted: equal when two assignments differ only by swapping
// partners between targets at identical positions.
std::vector<std::array<double, 4>> matched_positions(const std::vector<Vec2>& x, const std::vector<Vec2>& y,
                                                     const metrics::GospaResult& r) {
  std::vector<std::array<double, 4>> pairs;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const int j = r.simulated_of_recorded[i];
    if (j >= 0) pairs.push_back({x[i].x(), x[i].y(), y[static_cast<std::size_t>(j)].x(), y[static_cast<std::size_t>(j)].y()});
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Times one side of the comparison on every frame: the sparse assignment repeated until 5 ms have
// passed (its calls are short), the dense one once.
template <class Pick>
Timing time_frames(const std::vector<Frame>& frames, const metrics::GospaParameters& g, Pick&& pick, int min_targets) {
  Timing t;
  for (const Frame& f : frames) {
    const auto& [x, y] = pick(f);
    if (static_cast<int>(std::min(x.size(), y.size())) < min_targets) continue;
    int repeats = 0;
    metrics::GospaResult sparse;
    const auto start = SteadyClock::now();
    double elapsed_s = 0.0;
    do {
      sparse = metrics::gospa(x, y, g);
      ++repeats;
      elapsed_s = seconds_since(start);
    } while (elapsed_s < 5e-3);
    t.sparse_s += elapsed_s / repeats;
    const auto dense_start = SteadyClock::now();
    const metrics::GospaResult dense = metrics::detail::gospa_dense_components(x, y, g);
    t.dense_s += seconds_since(dense_start);
    ++t.frames;
    t.figures_differ += same_figures(sparse, dense) ? 0 : 1;
    if (sparse.simulated_of_recorded != dense.simulated_of_recorded) {
      ++t.pairs_differ;
      t.positions_differ += matched_positions(x, y, sparse) == matched_positions(x, y, dense) ? 0 : 1;
    }
  }
  return t;
}

void print_timing(const char* what, const Timing& t) {
  if (t.frames == 0) {
    std::printf("%-34s no frames\n", what);
    return;
  }
  const double sparse_ms = 1e3 * t.sparse_s / t.frames, dense_ms = 1e3 * t.dense_s / t.frames;
  std::printf("%-34s %6d %12.3f %12.3f %9.1f x   %d / %d / %d\n", what, t.frames, sparse_ms, dense_ms,
              dense_ms / sparse_ms, t.figures_differ, t.pairs_differ, t.positions_differ);
}

}  // namespace

int main(int argc, char** argv) {
  const bench_tools::ToolUsage usage{
      "rcsim_bench_pointcloud", "RECORDING_DIR [FRAMES_OUT]",
      "Replays RECORDING_DIR (a point-cloud recording, e.g. rcsim import --from astyx) without matching, then times\n"
      "GOSPA (c = 2 m, p = 2) on each sensor cycle by the sparse exact assignment against the dense assignment per\n"
      "connected component, and checks them equal (GOSPA, parts, OSPA to 1e-9; the pairs). FRAMES_OUT: the\n"
      "cycles' positions as text (cycle side x_m y_m) for scipy; derived from the data, never to be committed.",
      1, 2};
  int exit_status = 0;
  const auto arguments = bench_tools::tool_arguments(argc, argv, usage, exit_status);
  if (!arguments) return exit_status;
  try {
    replay::ReplayOptions options;
    options.match_targets = false;
    FrameSink sink;
    const auto replay_start = SteadyClock::now();
    replay::replay_recording_dir((*arguments)[0], options, sink);
    const double replay_s = seconds_since(replay_start);
    const metrics::GospaParameters g = options.gospa;

    long long recorded = 0, simulated = 0, pairs = 0;
    std::size_t largest = 0;
    for (const Frame& f : sink.frames) {
      recorded += static_cast<long long>(f.recorded.size());
      simulated += static_cast<long long>(f.simulated.size());
      pairs += pairs_within(f.recorded, f.simulated, g.cutoff_m);
      largest = std::max({largest, f.recorded.size(), f.simulated.size()});
    }
    const auto frames = static_cast<double>(std::max<std::size_t>(sink.frames.size(), 1));
    std::printf("frames %zu (replay without matching %.2f s); per frame: %.0f recorded, %.0f simulated, %.0f pairs "
                "closer than %.1f m; largest side %zu\n",
                sink.frames.size(), replay_s, static_cast<double>(recorded) / frames,
                static_cast<double>(simulated) / frames, static_cast<double>(pairs) / frames, g.cutoff_m, largest);
    std::printf("%-34s %6s %12s %12s %11s   %s\n", "GOSPA per frame", "frames", "sparse ms", "dense ms", "ratio",
                "differ: figures / pairs / pairs' positions");
    const auto all = [](const Frame& f) { return std::tie(f.recorded, f.simulated); };
    const auto objects = [](const Frame& f) { return std::tie(f.recorded_object, f.simulated_object); };
    print_timing("all targets", time_frames(sink.frames, g, all, 0));
    print_timing("all targets, frames >= 1,800 a side", time_frames(sink.frames, g, all, 1800));
    print_timing("object targets", time_frames(sink.frames, g, objects, 0));

    if (arguments->size() == 2) {
      std::ofstream out((*arguments)[1]);
      out.precision(17);
      for (std::size_t k = 0; k < sink.frames.size(); ++k) {
        for (const Vec2& v : sink.frames[k].recorded) out << k << " 0 " << v.x() << ' ' << v.y() << '\n';
        for (const Vec2& v : sink.frames[k].simulated) out << k << " 1 " << v.x() << ' ' << v.y() << '\n';
      }
      if (!out) throw std::runtime_error("cannot write " + (*arguments)[1]);
    }
  } catch (const std::exception& e) {
    std::cerr << "rcsim_bench_pointcloud: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
