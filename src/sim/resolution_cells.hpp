#pragma once
// Limited resolution (paper III-C): clustering of echoes into range x range-rate cells.
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Strongest echo first: it defines the centre of a cell of range_cell_m x range_rate_cell_mps;
// every remaining echo within half a cell of that centre in both dimensions joins it. The cell's
// upper amplitude bound A_cell^u is the sum of its members' amplitudes; a cell whose bound is
// below `threshold_amplitude` yields no entry. Range and range rate are the amplitude-weighted
// means, eqs. (4)-(5); the sum and delta pointers add up. Sorts `echoes` (strongest first).
void form_resolution_cells(const ResolutionCell& cell, double threshold_amplitude, Echoes& echoes,
                           ResolutionCells& out);

}  // namespace rcsim
