#include "sim/resolution_cells.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim {

void ResolutionCellBuffers::reserve(std::size_t echoes) {
  by_amplitude.reserve(echoes);
  by_range.reserve(echoes);
  range_position.reserve(echoes);
  members.reserve(echoes);
}

void form_resolution_cells(const ResolutionCell& cell, double threshold_amplitude, const Echoes& echoes,
                           ResolutionCellBuffers& buffers, ResolutionCells& out, std::vector<int>* cell_of_echo) {
  out.clear();
  if (cell_of_echo != nullptr) cell_of_echo->assign(echoes.size(), -1);
  auto& by_amplitude = buffers.by_amplitude;
  auto& by_range = buffers.by_range;
  auto& members = buffers.members;
  by_amplitude.clear();
  for (std::size_t i = 0; i < echoes.size(); ++i) {
    by_amplitude.push_back({echoes[i].amplitude, echoes[i].ideal_index, static_cast<int>(i)});
  }
  std::sort(by_amplitude.begin(), by_amplitude.end(), [](const auto& a, const auto& b) {
    if (a.amplitude != b.amplitude) return a.amplitude > b.amplitude;
    return a.ideal_index < b.ideal_index;  // a total order: same input, same cells
  });
  // A cell's candidates are its centre's neighbours in range: O(n log n) per cycle, not O(n^2).
  by_range.clear();
  for (std::size_t r = 0; r < by_amplitude.size(); ++r) {
    by_range.push_back({echoes[static_cast<std::size_t>(by_amplitude[r].echo)].range_m, static_cast<int>(r)});
  }
  std::sort(by_range.begin(), by_range.end(), [](const auto& a, const auto& b) { return a.range_m < b.range_m; });
  buffers.range_position.resize(by_range.size());
  for (std::size_t p = 0; p < by_range.size(); ++p) {
    buffers.range_position[static_cast<std::size_t>(by_range[p].rank)] = static_cast<int>(p);
  }

  const double half_range_m = 0.5 * cell.range_cell_m;
  const double half_rate_mps = 0.5 * cell.range_rate_cell_mps;
  // An array that resolves azimuth: cells are range x range rate x azimuth (one beam wide).
  const double half_azimuth_rad = cell.resolves_azimuth() ? 0.5 * cell.azimuth_cell_rad : kPi;
  // A radar with cells in elevation: one beam high too (several per range-Doppler cell).
  const double half_elevation_rad = cell.resolves_elevation() ? 0.5 * cell.elevation_cell_rad : kPi;
  // Gathers the echo at by_range[p] if it is free and within half a cell of the centre.
  const auto gather = [&](std::size_t p, const Echo& centre) {
    const int rank = by_range[p].rank;
    const int echo = by_amplitude[static_cast<std::size_t>(rank)].echo;
    if (echo < 0) return;
    const Echo& e = echoes[static_cast<std::size_t>(echo)];
    if (std::abs(e.range_m - centre.range_m) > half_range_m ||
        std::abs(e.range_rate_mps - centre.range_rate_mps) > half_rate_mps ||
        std::abs(angle_difference_rad(e.azimuth_rad, centre.azimuth_rad)) > half_azimuth_rad ||
        std::abs(e.elevation_rad - centre.elevation_rad) > half_elevation_rad) {
      return;
    }
    members.push_back(rank);
  };
  for (std::size_t i = 0; i < by_amplitude.size(); ++i) {
    if (by_amplitude[i].echo < 0) continue;  // already in a cell
    const Echo& centre = echoes[static_cast<std::size_t>(by_amplitude[i].echo)];
    // Out from the centre's place in range order, over a window twice the cell (so that rounding
    // cannot leave a member out); the exact test is in gather.
    const double reach_m = 2.0 * half_range_m;
    const auto centre_p = static_cast<std::size_t>(buffers.range_position[i]);
    members.clear();
    for (std::size_t p = centre_p; p-- > 0 && by_range[p].range_m >= centre.range_m - reach_m;) gather(p, centre);
    for (std::size_t p = centre_p; p < by_range.size() && by_range[p].range_m <= centre.range_m + reach_m; ++p) {
      gather(p, centre);
    }
    if (members.size() > 1) std::sort(members.begin(), members.end());  // strongest first: sums in a fixed order
    ResolutionCellSum c;
    c.strongest_ideal_index = centre.ideal_index;
    // Sums of A_n R_n and A_n v_n (amplitude times metres, times metres per second), eqs. (4)-(5).
    double amplitude_range_sum_m = 0.0, amplitude_rate_sum_mps = 0.0, amplitude_azimuth_offset_sum_rad = 0.0;
    double amplitude_elevation_sum_rad = 0.0;
    for (const int r : members) {
      const auto& rank = by_amplitude[static_cast<std::size_t>(r)];
      const Echo& e = echoes[static_cast<std::size_t>(rank.echo)];
      c.amplitude_upper += e.amplitude;
      amplitude_range_sum_m += e.amplitude * e.range_m;
      amplitude_rate_sum_mps += e.amplitude * e.range_rate_mps;
      amplitude_azimuth_offset_sum_rad += e.amplitude * angle_difference_rad(e.azimuth_rad, centre.azimuth_rad);
      amplitude_elevation_sum_rad += e.amplitude * e.elevation_rad;
      c.sum_pointer += e.sum_pointer;
      c.delta_pointer += e.delta_pointer;
      ++c.member_count;
    }
    const bool enters = c.amplitude_upper >= threshold_amplitude;  // paper III-C: else no entry for this cell
    for (const int r : members) {
      auto& rank = by_amplitude[static_cast<std::size_t>(r)];
      if (cell_of_echo != nullptr && enters) (*cell_of_echo)[static_cast<std::size_t>(rank.echo)] = static_cast<int>(out.size());
      rank.echo = -1;
    }
    if (!enters) continue;
    c.range_m = amplitude_range_sum_m / c.amplitude_upper;         // eqs. (4)-(5)
    c.range_rate_mps = amplitude_rate_sum_mps / c.amplitude_upper;
    c.azimuth_rad = wrap_angle_rad(centre.azimuth_rad + amplitude_azimuth_offset_sum_rad / c.amplitude_upper);
    c.elevation_rad = amplitude_elevation_sum_rad / c.amplitude_upper;  // eq. (4) on the elevation
    out.push_back(c);
  }
}

}  // namespace rcsim
