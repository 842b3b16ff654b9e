#include "sensor/stationary_background.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/angles.hpp"
#include "common/limits.hpp"

namespace rcsim {
namespace {

constexpr double kMaxTargetsPerCycle = 20000.0;  // an imaging radar reports thousands; schemas/limits.md
constexpr std::size_t kMaxBins = 1000;

std::vector<double> increasing_edges(const JsonField& f, std::string_view key, double scale) {
  std::vector<double> edges;
  for (const JsonField& e : f.array(key)) {
    if (!e.json().is_number() || !std::isfinite(e.json().get<double>())) f.fail(key, "must hold finite numbers");
    edges.push_back(scale * e.json().get<double>());
    if (edges.size() > 1 && !(edges.back() > edges[edges.size() - 2])) f.fail(key, "must increase strictly");
  }
  if (edges.size() < 2 || edges.size() > kMaxBins + 1) f.fail(key, fmt::format("must hold 2 to {} edges", kMaxBins + 1));
  return edges;
}

// Rows of numbers, `columns` each, every one checked with `valid`.
template <typename Valid>
std::vector<std::vector<double>> number_rows(const JsonField& f, std::string_view key, std::size_t rows, std::size_t columns,
                                             Valid&& valid, const char* what) {
  const std::vector<JsonField> list = f.array(key);
  if (list.size() != rows) f.fail(key, fmt::format("must hold {} rows (one per range bin), got {}", rows, list.size()));
  std::vector<std::vector<double>> out;
  for (std::size_t r = 0; r < rows; ++r) {
    const auto& row = list[r].json();
    if (!row.is_array() || row.size() != columns) f.fail(key, fmt::format("row {} must hold {} numbers", r, columns));
    auto& values = out.emplace_back();
    for (const auto& v : row) {
      if (!v.is_number() || !std::isfinite(v.get<double>()) || !valid(v.get<double>())) {
        f.fail(key, fmt::format("row {}: {}", r, what));
      }
      values.push_back(v.get<double>());
    }
  }
  return out;
}

}  // namespace

StationaryBackground parse_stationary_background(const JsonField& f) {
  f.expect_only({"fitted_on", "targets_per_cycle", "range_edges_m", "azimuth_edges_deg", "weights", "amplitude_deciles_db"});
  StationaryBackground b;
  b.fitted_on = f.has("fitted_on") ? f.string("fitted_on") : "";
  b.targets_per_cycle = f.number("targets_per_cycle");
  if (!(b.targets_per_cycle >= 0.0 && b.targets_per_cycle <= kMaxTargetsPerCycle)) {
    f.fail("targets_per_cycle", fmt::format("must be in [0, {}]", kMaxTargetsPerCycle));
  }
  b.range_edges_m = increasing_edges(f, "range_edges_m", 1.0);
  if (b.range_edges_m.front() < 0.0) f.fail("range_edges_m", "must not be negative");
  b.azimuth_edges_rad = increasing_edges(f, "azimuth_edges_deg", deg_to_rad(1.0));
  if (std::abs(b.azimuth_edges_rad.front()) >= 0.5 * kPi || std::abs(b.azimuth_edges_rad.back()) >= 0.5 * kPi) {
    f.fail("azimuth_edges_deg", "must lie within +-90 deg");
  }
  const auto weights = number_rows(f, "weights", b.range_bins(), b.azimuth_bins(), [](double w) { return w >= 0.0; },
                                   "weights must not be negative");
  double total = 0.0;
  for (const auto& row : weights) {
    for (const double w : row) b.weights.push_back(w), total += w;
  }
  if (!(total > 0.0)) f.fail("weights", "must not all be 0");
  for (double& w : b.weights) w /= total;
  const auto deciles = number_rows(f, "amplitude_deciles_db", b.range_bins(), kAmplitudeQuantiles,
                                   [](double a) { return std::abs(a) <= limits::kMaxLevel_dB; }, "amplitudes must be within +-1000 dB");
  for (std::size_t r = 0; r < deciles.size(); ++r) {
    auto& q = b.amplitude_deciles_db.emplace_back();
    for (int k = 0; k < kAmplitudeQuantiles; ++k) {
      q[static_cast<std::size_t>(k)] = deciles[r][static_cast<std::size_t>(k)];
      if (k > 0 && q[static_cast<std::size_t>(k)] < q[static_cast<std::size_t>(k - 1)]) {
        f.fail("amplitude_deciles_db", fmt::format("row {} must not decrease", r));
      }
    }
  }
  return b;
}

nlohmann::ordered_json stationary_background_to_json(const StationaryBackground& b) {
  nlohmann::ordered_json out;
  if (!b.fitted_on.empty()) out["fitted_on"] = b.fitted_on;
  out["targets_per_cycle"] = b.targets_per_cycle;
  out["range_edges_m"] = b.range_edges_m;
  nlohmann::ordered_json azimuth = nlohmann::ordered_json::array();
  for (const double a : b.azimuth_edges_rad) azimuth.push_back(rad_to_deg(a));
  out["azimuth_edges_deg"] = azimuth;
  nlohmann::ordered_json weights = nlohmann::ordered_json::array(), deciles = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < b.range_bins(); ++r) {
    weights.push_back(std::vector<double>(b.weights.begin() + static_cast<std::ptrdiff_t>(r * b.azimuth_bins()),
                                          b.weights.begin() + static_cast<std::ptrdiff_t>((r + 1) * b.azimuth_bins())));
    deciles.push_back(b.amplitude_deciles_db[r]);
  }
  out["weights"] = weights;
  out["amplitude_deciles_db"] = deciles;
  return out;
}

}  // namespace rcsim
