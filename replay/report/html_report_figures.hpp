#pragma once
// The pictures of one run for the HTML report, from what store/figure_reader.hpp read: a few
// informative cycles as bird's-eye pictures, time series thinned to at most `max_points` points
// per series, and histograms of the matched pairs' residuals (binned while streaming, never
// loaded whole).

#include <string>
#include <vector>

#include "replay/store/figure_reader.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/report/svg_birdseye.hpp"
#include "replay/report/svg_plot.hpp"

namespace rcsim::replay::report {

struct ChosenCycle {
  int cycle = 0;
  std::string reason;  // why it is pictured, e.g. "largest GOSPA (2.31 m, front_left)"
};

// Up to `max_count` distinct cycles, in time order: the largest GOSPA, the most merge
// artefacts, the first reported target, the largest count mismatch, the middle of the run.
std::vector<ChosenCycle> choose_cycles(const CycleHighlights& found, const RunData& run, std::size_t max_count);

// The bird's-eye picture of one cycle, all sensors, with the cycles of the window before it as traces.
svg::BirdsEyeSpec birdseye_of_cycle(const RunData& run, const ChosenCycle& chosen, const CycleWindow& window);

// Every how many cycles the time series take a point, for at most `max_points` points.
int series_stride(const RunData& run, int max_points);

// "every 2nd cycle", "every 11th cycle", "every 23rd cycle": the English ordinal of `stride`
// ("every cycle" for 1), for the note under thinned series (was "every 2th cycle").
std::string every_nth_cycle(int stride);

// Per sensor: nearest object target's range and lateral position (recorded and simulated, like paper
// Fig. 5), targets per cycle, and GOSPA over time.
std::vector<svg::PlotSpec> time_series(const RunData& run, int stride, const std::vector<NearestTargetRow>& nearest,
                                       const std::vector<CycleBucketRow>& buckets);

// Every how many cycles the residual sample that sets the histogram ranges takes (about 5000).
int residual_sample_stride(const RunData& run);

// Histograms of the residuals (simulated - recorded) of the assigned pairs in range, azimuth,
// range rate and amplitude, over all sensors: ranges from a sample's statistics, then every
// pair added as it is streamed.
class ResidualHistograms {
 public:
  ResidualHistograms(const ResidualSampleStats& sample, int bins);
  void add(const Residuals& residuals);
  std::vector<svg::HistogramSpec> specs() const;  // with the exact mean and RMS of all pairs added

 private:
  std::vector<svg::HistogramSpec> histograms_;
  std::int64_t count_ = 0;
  Residuals sum_{}, sum_sq_{};
};

}  // namespace rcsim::replay::report
