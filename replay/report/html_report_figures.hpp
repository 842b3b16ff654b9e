#pragma once
// The pictures of one run for the HTML report, read from the report database with bounded
// queries: a few informative cycles as bird's-eye pictures, time series thinned to at most
// `max_points` points per series, and histograms of the matched pairs' residuals (binned while
// streaming, never loaded whole).
#include <SQLiteCpp/SQLiteCpp.h>

#include <string>
#include <vector>

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
std::vector<ChosenCycle> choose_cycles(SQLite::Database& db, const RunData& run, std::size_t max_count);

// The bird's-eye picture of one cycle, all sensors, with the `trace_cycles` cycles before it.
svg::BirdsEyeSpec birdseye_of_cycle(SQLite::Database& db, const RunData& run, const ChosenCycle& chosen,
                                    int trace_cycles);

// Per sensor: nearest target's range and lateral position (recorded and simulated, like paper
// Fig. 5), targets per cycle, and GOSPA over time.
std::vector<svg::PlotSpec> time_series(SQLite::Database& db, const RunData& run, int max_points);

// Residuals (simulated - recorded) of the assigned pairs in range, azimuth, range rate and
// amplitude, over all sensors.
std::vector<svg::HistogramSpec> residual_histograms(SQLite::Database& db, const RunData& run, int bins);

}  // namespace rcsim::replay::report
