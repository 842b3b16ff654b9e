#pragma once
// A bounded compass search (Kolda, Lewis & Torczon, "Optimization by direct search", SIAM Review
// 2003): from a start, each parameter in turn is tried a step up and a step down within its
// bounds; a try that lowers the objective is taken, and when none does every step halves, until
// each is below its parameter's resolution, the budget is spent or the caller stops it. Scale-free
// in the sense of `rcsim calibrate --real-drive` (issue 30): no fixed grid, the steps adapt, and an
// optimum on a bound is said as such.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace rcsim::replay {

struct SearchParameter {
  std::string name;
  double start = 0.0, lower = 0.0, upper = 0.0;
  double step = 1.0;        // the first step
  double resolution = 0.1;  // the search ends when every step is below its resolution
};

struct SearchProgress {
  int evaluations = 0, max_evaluations = 0;
  double best_objective = 0.0;
  std::vector<double> best;
};

struct SearchResult {
  std::vector<double> best;
  std::vector<bool> on_bound;  // the best value lies on its lower or upper bound
  double objective = 0.0;
  int evaluations = 0;
  bool converged = false;  // every step below its resolution
  bool stopped = false;    // the caller's stop flag ended it: the best so far
  // Every evaluation (at least two) gave the same objective: no parameter moved it, so the search
  // ended where it started and learnt nothing (not converged on an optimum).
  bool flat = false;
};

// `objective` is called at most max_evaluations times; `stop` (may be null) is read before each
// call, and after it: an evaluation during which it was set (the objective may then have returned
// anything) counts for nothing; `progress` (may be empty) after each.
SearchResult compass_search(const std::vector<SearchParameter>& parameters,
                            const std::function<double(const std::vector<double>&)>& objective, int max_evaluations,
                            const std::atomic<bool>* stop = nullptr,
                            const std::function<void(const SearchProgress&)>& progress = {});

}  // namespace rcsim::replay
