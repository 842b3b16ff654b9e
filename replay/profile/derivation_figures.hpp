#pragma once
// What `rcsim profile derive --report` draws (docs/profile-derive.md): the data each value was read
// from, with the fit or the value over it. Plain data; replay/report turns it into SVG.
#include <string>
#include <utility>
#include <vector>

namespace rcsim::replay::profile {

struct FigureSeries {
  std::string label;
  bool dots = false;  // a scatter, else a line
  std::vector<std::pair<double, double>> points;
};

// A plot of series, or (bin_width > 0) a histogram with the derived value marked.
struct DerivationFigure {
  std::string title, x_label, y_label, note;
  std::vector<FigureSeries> series;
  double lo = 0.0, bin_width = 0.0;
  std::vector<long long> counts{};
  double marker = 0.0;
  std::string marker_label{};
  bool y_from_zero = false;  // a quantity that cannot be negative (a noise), its axis from 0
};

// A histogram of `values` over [0, hi) in `bins` bins, what lies beyond in the last.
DerivationFigure histogram_figure(std::string title, std::string x_label, const std::vector<double>& values, double hi, int bins,
                                  double marker, std::string marker_label);

// Every k-th of `points` so that at most `max_points` remain.
std::vector<std::pair<double, double>> thinned(const std::vector<std::pair<double, double>>& points, std::size_t max_points);

}  // namespace rcsim::replay::profile
