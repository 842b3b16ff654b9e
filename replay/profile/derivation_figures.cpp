#include "replay/profile/derivation_figures.hpp"

#include <algorithm>
#include <cmath>

namespace rcsim::replay::profile {

DerivationFigure histogram_figure(std::string title, std::string x_label, const std::vector<double>& values, double hi, int bins,
                                  double marker, std::string marker_label) {
  DerivationFigure f;
  f.title = std::move(title), f.x_label = std::move(x_label), f.y_label = "pairs";
  f.bin_width = hi / bins;
  f.counts.assign(static_cast<std::size_t>(bins), 0);
  for (const double v : values) {
    const auto bin = static_cast<std::size_t>(std::clamp(std::floor(v / f.bin_width), 0.0, static_cast<double>(bins - 1)));
    ++f.counts[bin];
  }
  f.marker = marker, f.marker_label = std::move(marker_label);
  return f;
}

std::vector<std::pair<double, double>> thinned(const std::vector<std::pair<double, double>>& points, std::size_t max_points) {
  if (points.size() <= max_points) return points;
  const std::size_t every = (points.size() + max_points - 1) / max_points;
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i < points.size(); i += every) out.push_back(points[i]);
  return out;
}

}  // namespace rcsim::replay::profile
