#include "replay/calibrate/bounded_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rcsim::replay {
namespace {

constexpr int kMaxRestarts = 2;

}  // namespace

SearchResult compass_search(const std::vector<SearchParameter>& parameters,
                            const std::function<double(const std::vector<double>&)>& objective, int max_evaluations,
                            const std::atomic<bool>* stop, const std::function<void(const SearchProgress&)>& progress) {
  SearchResult r;
  r.objective = INFINITY;
  std::vector<double> steps;
  for (const SearchParameter& p : parameters) {
    if (!(p.lower <= p.start && p.start <= p.upper && p.step > 0.0 && p.resolution > 0.0)) {
      throw std::invalid_argument("search parameter " + p.name + ": needs lower <= start <= upper and positive steps");
    }
    r.best.push_back(p.start);
    steps.push_back(p.step);
  }
  const auto stopped = [&] { return stop != nullptr && stop->load(); };
  double lowest = INFINITY, highest = -INFINITY;
  const auto evaluate = [&](const std::vector<double>& x) {
    const double value = objective(x);
    if (stopped()) return static_cast<double>(INFINITY);  // cut short by the stop (a replay stopped midway): counts for nothing
    lowest = std::min(lowest, value), highest = std::max(highest, value);
    ++r.evaluations;
    if (progress) progress({r.evaluations, max_evaluations, std::min(value, r.objective), r.best});
    return value;
  };
  if (max_evaluations < 1 || stopped()) {
    r.stopped = stopped();
    r.on_bound.assign(parameters.size(), false);
    return r;
  }
  r.objective = evaluate(r.best);
  int restarts = 0;
  bool improved_since_restart = false;
  while (!r.converged && r.evaluations < max_evaluations && !stopped()) {
    bool improved = false;
    for (std::size_t i = 0; i < parameters.size() && r.evaluations < max_evaluations && !stopped(); ++i) {
      for (const double direction : {1.0, -1.0}) {
        if (r.evaluations >= max_evaluations || stopped()) break;
        std::vector<double> x = r.best;
        x[i] = std::clamp(r.best[i] + direction * steps[i], parameters[i].lower, parameters[i].upper);
        if (x[i] == r.best[i]) continue;
        const double value = evaluate(x);
        if (value < r.objective) {
          r.best = std::move(x), r.objective = value, improved = true;
          break;
        }
      }
    }
    if (improved) {
      improved_since_restart = true;
      continue;
    }
    bool fine = true;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      steps[i] *= 0.5;
      fine = fine && steps[i] < parameters[i].resolution;
    }
    if (!fine) continue;
    // Converged in the small; a rough objective (a replay's counts) has local minima there, so
    // start again from the best with the first steps while that still improves it.
    if (!improved_since_restart || restarts == kMaxRestarts) {
      r.converged = true;
      break;
    }
    ++restarts, improved_since_restart = false;
    for (std::size_t i = 0; i < steps.size(); ++i) steps[i] = parameters[i].step;
  }
  r.stopped = !r.converged && stopped();
  r.flat = r.evaluations >= 2 && lowest == highest;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const double tolerance = 1e-9 * std::max(1.0, std::abs(parameters[i].upper - parameters[i].lower));
    r.on_bound.push_back(std::abs(r.best[i] - parameters[i].lower) <= tolerance || std::abs(r.best[i] - parameters[i].upper) <= tolerance);
  }
  return r;
}

}  // namespace rcsim::replay
