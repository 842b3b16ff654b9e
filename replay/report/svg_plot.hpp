#pragma once
// Plots for the HTML report, as self-contained SVG text: time series (lines or dots over time,
// like paper Fig. 5) and histograms of residuals. Every label is escaped here.
#include <string>
#include <utility>
#include <vector>

#include "common/target_colours.hpp"

namespace rcsim::replay::svg {

inline constexpr const char* kRecordedColour = colours::kRecorded;
inline constexpr const char* kSimulatedColour = colours::kSimulated;
// Targets on no annotated box: the stationary background and the other (moving) ones.
inline constexpr const char* kBackgroundColour = colours::kBackground;
inline constexpr const char* kOtherColour = colours::kOther;

struct PlotSeries {
  std::string label;
  std::string colour;
  bool dots = false;                              // dots (a scatter) instead of a line
  bool dashed = false;
  std::vector<std::pair<double, double>> points;  // (x, y); a NaN y breaks a line
};

struct PlotSpec {
  std::string title;
  std::string x_label;  // with unit, e.g. "t / s"
  std::string y_label;
  std::string note;     // small text under the title, e.g. how the series was thinned
  int width_px = 600, height_px = 250;
  bool y_from_zero = false;  // for quantities that cannot be negative
  std::vector<PlotSeries> series;
};

std::string plot_svg(const PlotSpec& spec);

// A vertical line across a histogram at x, labelled at its top (a criterion's threshold).
struct HistogramMarker {
  double x = 0.0;
  std::string label;
  std::string colour = "#c92a2a";
  bool dashed = false;
};

struct HistogramSpec {
  std::string title;
  std::string x_label;
  std::string y_label = "matched pairs";
  double lo = 0.0, bin_width = 1.0;  // bin i covers [lo + i w, lo + (i + 1) w)
  std::vector<long long> counts;     // the first and last bins include what lies beyond them
  long long below = 0, above = 0;    // how many of those were clamped into the end bins
  std::string note;
  int width_px = 600, height_px = 230;
  bool zero_line = true;  // a dashed line at x = 0 (the ideal residual) where the axis spans it
  std::vector<HistogramMarker> markers;  // drawn where they fall on the axis
};

std::string histogram_svg(const HistogramSpec& spec);

}  // namespace rcsim::replay::svg
