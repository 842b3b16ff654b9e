#pragma once
// Limited resolution (paper III-C): clustering of echoes into range x range-rate cells (and, for an
// array that resolves azimuth, x azimuth: its beams).
#include <vector>

#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Buffers of form_resolution_cells, kept by the caller so that a cycle allocates nothing.
struct ResolutionCellBuffers {
  struct Rank {
    double amplitude;
    int ideal_index;
    int echo;  // position in the echoes; -1 once the echo belongs to a cell
  };
  struct Nearest {
    double range_m;
    int rank;  // position in by_amplitude
  };
  std::vector<Rank> by_amplitude;    // the order in which echoes are taken: strongest first
  std::vector<Nearest> by_range;     // nearest first
  std::vector<int> range_position;   // of each rank in by_range
  std::vector<int> members;          // ranks of one cell's members

  void reserve(std::size_t echoes);
};

// Strongest echo first: it defines the centre of a cell of range_cell_m x range_rate_cell_mps (x
// azimuth_cell_rad where the array resolves azimuth); every remaining echo within half a cell of
// that centre in each dimension joins it. The cell's
// upper amplitude bound A_cell^u is the sum of its members' amplitudes; a cell whose bound is
// below `threshold_amplitude` yields no entry. Range, range rate and azimuth are the
// amplitude-weighted means, eqs. (4)-(5); the sum and delta pointers add up, strongest member first. Ties in
// amplitude go to the lower ideal index. The echoes stay where they are: echoes[i] still belongs to
// ideal target i afterwards. With `cell_of_echo`, (*cell_of_echo)[i] is the index in `out` of the
// cell echo i joined, or -1 when its cell yielded no entry (the harness's merge cells read it).
void form_resolution_cells(const ResolutionCell& cell, double threshold_amplitude, const Echoes& echoes,
                           ResolutionCellBuffers& buffers, ResolutionCells& out,
                           std::vector<int>* cell_of_echo = nullptr);

}  // namespace rcsim
