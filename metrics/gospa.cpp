#include "metrics/gospa.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "metrics/assignment.hpp"
#include "metrics/sparse_assignment.hpp"

namespace rcsim::metrics {

namespace {

void check_gospa_parameters(const GospaParameters& parameters) {
  const double c = parameters.cutoff_m, p = parameters.order_p;
  if (!(c > 0.0) || !(p >= 1.0) || !std::isfinite(c) || !std::isfinite(p)) {
    throw std::invalid_argument("gospa: needs cutoff_m > 0 and order_p >= 1");
  }
}

bool all_coordinates_finite(const std::vector<Vec2>& points) {
  return std::all_of(points.begin(), points.end(), [](const Vec2& v) { return v.allFinite(); });
}

// Up to this many recorded × simulated pairs every pair is tested; beyond, the grid finds the
// candidates (bench/bench_gospa.cpp: the grid pays from about 20 × 20 targets on).
constexpr std::size_t kGospaAllPairsUpTo = 400;
// Grid cells slightly larger than c: a pair closer than c then lies in neighbouring cells even
// after the rounding of the cell index, for up to kGospaMaxCells cells per axis.
constexpr double kGospaCellMargin = 1e-6;
constexpr double kGospaMaxCells = 1 << 30;
// Up to this many grid cells per target (both sides) the cells are one array, beyond sorted keys.
constexpr double kGospaDenseCellsPerTarget = 8.0;
// Up to this many targets (both sides) the union-find works in a buffer on the stack.
constexpr int kGospaStackTargets = 64;

// |a − b| < c, decided exactly as the full assignment decides it, (a − b).norm() < c, but with
// the square root taken only near c: sqrt is correctly rounded and monotone, so away from c^2
// (by far more than rounding) the squared norm decides alike.
class WithinCutoff {
 public:
  explicit WithinCutoff(double c) : c_(c), below_(c * c * (1.0 - 1e-9)), above_(c * c * (1.0 + 1e-9)) {
    squares_ = c >= 1e-100 && c <= 1e100;  // c^2 neither underflows nor overflows
  }
  bool operator()(const Vec2& a, const Vec2& b) const {
    const double squared = (a - b).squaredNorm();
    if (squares_ && squared < below_) return true;
    if (squares_ && squared > above_) return false;
    return std::sqrt(squared) < c_;  // Eigen's norm(): the square root of squaredNorm()
  }

 private:
  double c_, below_, above_;
  bool squares_ = false;
};

// Calls close_pair(i, j) for every recorded i and simulated j with |x_i − y_j| < c, each pair
// once: all pairs when there are few, else the simulated targets sorted by the cell of a grid
// and each recorded target looking into its own cell and the 8 around it.
template <class ClosePair>
void for_each_pair_within_cutoff(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c,
                                 ClosePair&& close_pair) {
  const WithinCutoff within(c);
  const auto test_all_pairs = [&] {
    for (std::size_t i = 0; i < x.size(); ++i) {
      for (std::size_t j = 0; j < y.size(); ++j) {
        if (within(x[i], y[j])) close_pair(static_cast<int>(i), static_cast<int>(j));
      }
    }
  };
  if (x.size() * y.size() <= kGospaAllPairsUpTo) return test_all_pairs();
  Eigen::Vector2d lo = x.front(), hi = x.front();
  for (const auto* set : {&x, &y}) {
    for (const Vec2& v : *set) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  }
  const double cell_m = c * (1.0 + kGospaCellMargin);
  const double columns = std::floor((hi.x() - lo.x()) / cell_m) + 1.0;
  const double rows = std::floor((hi.y() - lo.y()) / cell_m) + 1.0;
  if (!(columns <= kGospaMaxCells && rows <= kGospaMaxCells)) return test_all_pairs();  // spread too far
  // Cell key row * stride + column + 1: the three cells column − 1 .. column + 1 of one row are
  // one contiguous range of keys.
  const auto stride = static_cast<std::int64_t>(columns) + 2;
  const auto column_of = [&](const Vec2& v) { return static_cast<std::int64_t>(std::floor((v.x() - lo.x()) / cell_m)); };
  const auto row_of = [&](const Vec2& v) { return static_cast<std::int64_t>(std::floor((v.y() - lo.y()) / cell_m)); };
  const auto last_row = static_cast<std::int64_t>(rows) - 1;
  const auto key_of = [&](const Vec2& v) { return row_of(v) * stride + column_of(v) + 1; };
  if (rows * static_cast<double>(stride) <= kGospaDenseCellsPerTarget * static_cast<double>(x.size() + y.size())) {
    // Few cells: the simulated targets bucketed by a counting sort (in ascending order within a
    // cell, as the sort below leaves them), each cell's first place in cell_start.
    const auto keys = static_cast<std::size_t>(rows * static_cast<double>(stride));
    std::vector<int> cell_start(keys + 2, 0), by_cell(y.size());
    for (const Vec2& v : y) ++cell_start[static_cast<std::size_t>(key_of(v)) + 1];
    for (std::size_t k = 0; k + 1 < cell_start.size(); ++k) cell_start[k + 1] += cell_start[k];
    std::vector<int> cursor(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t j = 0; j < y.size(); ++j) by_cell[static_cast<std::size_t>(cursor[static_cast<std::size_t>(key_of(y[j]))]++)] = static_cast<int>(j);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::int64_t column = column_of(x[i]), row = row_of(x[i]);
      for (std::int64_t r = std::max<std::int64_t>(row - 1, 0); r <= std::min(row + 1, last_row); ++r) {
        const auto first_key = static_cast<std::size_t>(r * stride + column);  // column − 1, shifted by one
        for (int t = cell_start[first_key]; t < cell_start[first_key + 3]; ++t) {
          const int j = by_cell[static_cast<std::size_t>(t)];
          if (within(x[i], y[static_cast<std::size_t>(j)])) close_pair(static_cast<int>(i), j);
        }
      }
    }
    return;
  }
  std::vector<std::pair<std::int64_t, int>> cells(y.size());
  for (std::size_t j = 0; j < y.size(); ++j) cells[j] = {key_of(y[j]), static_cast<int>(j)};
  std::sort(cells.begin(), cells.end());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::int64_t column = column_of(x[i]), row = row_of(x[i]);
    for (std::int64_t r = std::max<std::int64_t>(row - 1, 0); r <= std::min(row + 1, last_row); ++r) {
      const std::int64_t first_key = r * stride + column;  // column − 1, shifted by one
      auto it = std::lower_bound(cells.begin(), cells.end(), std::pair(first_key, std::numeric_limits<int>::min()));
      for (; it != cells.end() && it->first <= first_key + 2; ++it) {
        if (within(x[i], y[static_cast<std::size_t>(it->second)])) close_pair(static_cast<int>(i), it->second);
      }
    }
  }
}

// min(d, c)^p with d < c, as both assignments price a pair (and the dense one a pair beyond c).
double pair_cost(const Vec2& a, const Vec2& b, double c, double p, double c_p) {
  const double d = (a - b).norm();
  return d < c ? std::pow(d, p) : c_p;
}

// For each recorded target, its simulated partner closer than c in an optimal assignment on
// min(d, c)^p, or -1, and that pair's d^p, by the sparse exact assignment over the pairs closer
// than c alone (metrics/sparse_assignment.hpp): each target paired at d^p or left at c^p/2. The
// smaller side are the rows (their searches then mostly end at a free column nearby). The solver
// prices a pair at p = 2 by its squared norm, which differs from pow(norm, 2) by rounding alone;
// the figures take each assigned pair's d^p as the dense way does.
void assign_sparse(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c, double p,
                   std::vector<int>& simulated_of_recorded, double* partner_cost) {
  const double c_p = std::pow(c, p);
  const bool transpose = y.size() < x.size();
  const std::vector<Vec2>& row_points = transpose ? y : x;
  const std::vector<Vec2>& column_points = transpose ? x : y;
  SparseCosts costs;
  costs.rows = static_cast<int>(row_points.size());
  costs.columns = static_cast<int>(column_points.size());
  costs.row_start.assign(row_points.size() + 1, 0);
  // The grid hands the pairs row by row (the first argument's points in ascending order).
  for_each_pair_within_cutoff(row_points, column_points, c, [&](int r, int k) {
    const Vec2 delta = row_points[static_cast<std::size_t>(r)] - column_points[static_cast<std::size_t>(k)];
    costs.column.push_back(k);
    costs.cost.push_back(p == 2.0 ? delta.squaredNorm() : p == 1.0 ? delta.norm() : std::pow(delta.norm(), p));
    ++costs.row_start[static_cast<std::size_t>(r) + 1];
  });
  if (costs.column.empty()) return;
  for (std::size_t r = 0; r < row_points.size(); ++r) costs.row_start[r + 1] += costs.row_start[r];
  const SparseAssignment assignment = solve_sparse_assignment(costs, 0.5 * c_p, 0.5 * c_p);
  for (int r = 0; r < costs.rows; ++r) {
    const int k = assignment.column_of_row[static_cast<std::size_t>(r)];
    if (k < 0) continue;
    const int i = transpose ? k : r, j = transpose ? r : k;
    simulated_of_recorded[static_cast<std::size_t>(i)] = j;
    partner_cost[i] = pair_cost(x[static_cast<std::size_t>(i)], y[static_cast<std::size_t>(j)], c, p, c_p);
  }
}

// The same by the dense assignment (metrics/assignment.hpp) on each connected component of the
// pairs closer than c (the way before issue 52): the reference of the tests and the benchmark.
void assign_dense_by_components(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c, double p,
                          std::vector<int>& simulated_of_recorded, double* partner_cost) {
  const int n_x = static_cast<int>(x.size());
  const int n = n_x + static_cast<int>(y.size());
  // One buffer: the union-find's parents (recorded i is node i, simulated j node n_x + j), the
  // nodes ordered by component, each component's first place in that order, and a cursor.
  std::array<int, 4 * kGospaStackTargets + 1> stack_work;
  std::vector<int> heap_work;
  if (n > kGospaStackTargets) heap_work.resize(static_cast<std::size_t>(4 * n + 1));
  int* const parent = n > kGospaStackTargets ? heap_work.data() : stack_work.data();
  int* const order = parent + n;
  int* const first = order + n;  // n + 1 entries
  int* const cursor = first + n + 1;
  for (int v = 0; v < n; ++v) parent[v] = v;
  const auto root = [parent](int v) {
    while (parent[v] != v) {
      parent[v] = parent[parent[v]];  // path halving
      v = parent[v];
    }
    return v;
  };
  bool any_pair = false;
  for_each_pair_within_cutoff(x, y, c, [&](int i, int j) {
    any_pair = true;
    const int a = root(i), b = root(n_x + j);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // a root is its component's smallest node
  });
  if (!any_pair) return;
  // Counting sort of the nodes by root: each component's recorded targets, then its simulated
  // ones, each in ascending order (the order of the full assignment's rows and columns).
  std::fill(first, first + n + 1, 0);
  for (int v = 0; v < n; ++v) {
    parent[v] = root(v);
    ++first[parent[v] + 1];
  }
  for (int r = 0; r < n; ++r) first[r + 1] += first[r];
  std::copy(first, first + n, cursor);
  for (int v = 0; v < n; ++v) order[cursor[parent[v]]++] = v;

  const double c_p = std::pow(c, p);
  const auto cost_of = [&](const Vec2& a, const Vec2& b) { return pair_cost(a, b, c, p, c_p); };
  Eigen::MatrixXd cost;
  for (int r = 0; r < n; ++r) {
    const int size = first[r + 1] - first[r];
    if (size < 2) continue;  // no partner closer than c: unassigned
    const int* const nodes = order + first[r];
    const int rows = static_cast<int>(std::find_if(nodes, nodes + size, [n_x](int v) { return v >= n_x; }) - nodes);
    const int cols = size - rows;
    const auto recorded = [&](int a) -> const Vec2& { return x[static_cast<std::size_t>(nodes[a])]; };
    const auto simulated = [&](int b) -> const Vec2& { return y[static_cast<std::size_t>(nodes[rows + b] - n_x)]; };
    if (rows == 1 && cols == 1) {  // one pair, and it is closer than c
      simulated_of_recorded[static_cast<std::size_t>(nodes[0])] = nodes[1] - n_x;
      partner_cost[nodes[0]] = cost_of(recorded(0), simulated(0));
      continue;
    }
    cost.resize(rows, cols);
    for (int a = 0; a < rows; ++a) {
      for (int b = 0; b < cols; ++b) cost(a, b) = cost_of(recorded(a), simulated(b));
    }
    const Assignment assignment = solve_assignment(cost);
    for (int a = 0; a < rows; ++a) {
      const int b = assignment.column_of_row[static_cast<std::size_t>(a)];
      if (b >= 0 && (recorded(a) - simulated(b)).norm() < c) {
        simulated_of_recorded[static_cast<std::size_t>(nodes[a])] = nodes[rows + b] - n_x;
        partner_cost[nodes[a]] = cost(a, b);
      }
    }
  }
}

// From the assignment's pairs (result.assigned, result.localisation_mp) and ospa_sum = Σ min(d, c)^p
// over the assignment: the missed and false parts, GOSPA (c^p / 2 per unassigned target, alpha 2)
// and OSPA: (1/n (Σ min(d,c)^p + c^p (n − m)))^(1/p), m = min(|X|,|Y|), n = max(|X|,|Y|).
void finish_gospa(int n_x, int n_y, double ospa_sum, double c_p, double p, GospaResult& result) {
  result.missed = n_x - result.assigned;
  result.false_targets = n_y - result.assigned;
  result.missed_mp = 0.5 * c_p * result.missed;
  result.false_mp = 0.5 * c_p * result.false_targets;
  result.gospa_m = std::pow(result.localisation_mp + result.missed_mp + result.false_mp, 1.0 / p);
  const int n = std::max(n_x, n_y), m = std::min(n_x, n_y);
  if (n > 0) result.ospa_m = std::pow((ospa_sum + c_p * static_cast<double>(n - m)) / static_cast<double>(n), 1.0 / p);
}

// GOSPA and OSPA from the partners that assign(x, y, c, p, partners, partner_cost) finds.
template <class Assign>
GospaResult gospa_by(Assign&& assign, const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                     const GospaParameters& parameters) {
  check_gospa_parameters(parameters);
  if (!all_coordinates_finite(recorded_S) || !all_coordinates_finite(simulated_S)) {
    return detail::gospa_full_assignment(recorded_S, simulated_S, parameters);  // as it always did
  }
  const double c = parameters.cutoff_m, p = parameters.order_p;
  const double c_p = std::pow(c, p);
  const auto n_x = static_cast<int>(recorded_S.size());
  const auto n_y = static_cast<int>(simulated_S.size());
  GospaResult result;
  result.simulated_of_recorded.assign(recorded_S.size(), -1);
  // d^p of each recorded target's pair, on the stack for few targets.
  std::array<double, kGospaStackTargets> stack_cost;
  std::vector<double> heap_cost;
  if (n_x > kGospaStackTargets) heap_cost.resize(recorded_S.size());
  double* const partner_cost = n_x > kGospaStackTargets ? heap_cost.data() : stack_cost.data();
  if (n_x > 0 && n_y > 0) assign(recorded_S, simulated_S, c, p, result.simulated_of_recorded, partner_cost);

  const auto& partner = result.simulated_of_recorded;
  for (int i = 0; i < n_x; ++i) result.assigned += partner[static_cast<std::size_t>(i)] >= 0 ? 1 : 0;
  // The sums in the full assignment's order, row by row. There every row has a column when
  // |X| <= |Y|, and a row without a partner closer than c has one at or beyond c: c^p. When
  // |X| > |Y|, |Y| − assigned such rows: taken here as the first rows without a partner (the sum
  // is the same up to the order of its terms).
  int far_rows = std::min(n_x, n_y) - result.assigned;
  double ospa_sum = 0.0;  // Σ min(d, c)^p over the optimal (cut-off) assignment
  for (int i = 0; i < n_x; ++i) {
    const int j = partner[static_cast<std::size_t>(i)];
    if (j >= 0) {
      const double d_p = partner_cost[i];
      result.localisation_mp += d_p;
      ospa_sum += d_p;
    } else if (far_rows > 0) {
      ospa_sum += c_p;
      --far_rows;
    }
  }
  finish_gospa(n_x, n_y, ospa_sum, c_p, p, result);
  return result;
}

}  // namespace

GospaResult gospa(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                  const GospaParameters& parameters) {
  return gospa_by(assign_sparse, recorded_S, simulated_S, parameters);
}

namespace detail {

GospaResult gospa_dense_components(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                                   const GospaParameters& parameters) {
  return gospa_by(assign_dense_by_components, recorded_S, simulated_S, parameters);
}

GospaResult gospa_full_assignment(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                                  const GospaParameters& parameters) {
  check_gospa_parameters(parameters);
  const double c = parameters.cutoff_m, p = parameters.order_p;
  const auto n_x = static_cast<Eigen::Index>(recorded_S.size());
  const auto n_y = static_cast<Eigen::Index>(simulated_S.size());
  const double c_p = std::pow(c, p);
  GospaResult result;
  result.simulated_of_recorded.assign(recorded_S.size(), -1);

  Eigen::MatrixXd cost(n_x, n_y);
  Eigen::MatrixXd distance(n_x, n_y);
  for (Eigen::Index i = 0; i < n_x; ++i) {
    for (Eigen::Index j = 0; j < n_y; ++j) {
      distance(i, j) = (recorded_S[i] - simulated_S[j]).norm();
      cost(i, j) = std::pow(std::min(distance(i, j), c), p);  // min(d, c)^p
    }
  }
  const Assignment assignment = solve_assignment(cost);
  double ospa_sum = 0.0;  // Σ min(d, c)^p over the optimal (cut-off) assignment
  for (Eigen::Index i = 0; i < n_x; ++i) {
    const int j = assignment.column_of_row[i];
    if (j < 0) continue;
    ospa_sum += cost(i, j);
    if (distance(i, j) < c) {
      result.simulated_of_recorded[i] = j;
      result.localisation_mp += std::pow(distance(i, j), p);
      ++result.assigned;
    }
  }
  finish_gospa(static_cast<int>(n_x), static_cast<int>(n_y), ospa_sum, c_p, p, result);
  return result;
}

}  // namespace detail

}  // namespace rcsim::metrics
