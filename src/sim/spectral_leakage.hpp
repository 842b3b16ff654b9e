#pragma once
// Spectral leakage of a radar that reports every cell of its range/range-rate map over the
// threshold (an imaging radar, docs/imaging-radar.md): the range and Doppler FFTs are windowed, so
// one reflector's energy falls into the cells beside its own, a main lobe two cells wide. A strong
// return gives detections one cell further in range and in range rate at the window's response,
// the Astyx HiRes's most common pairs (docs/imaging-radar.md, "Spectral leakage").
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// The Hann window's amplitude response at `offset_bins` from a tone, relative to the tone's bin
// (|W(x)| = |sinc(x) / (1 - x^2)|, sinc(x) = sin(pi x) / (pi x)): 1 at 0, 0.8488 at 0.5 (the
// scalloping loss, -1.42 dB), 0.5 at 1 (-6.02 dB), 0.1698 at 1.5, 0 at 2 (the first null).
double hann_response(double offset_bins);

// How far from its own cell a detection leaks, in cells (beyond, the response is at most -30.9 dB
// relative to the detection's own cell: W(2.5) / W(0.5)).
inline constexpr int kLeakageReachCells = 2;

// Adds, for each detection at or over threshold_db, one in each cell of the range/range-rate map
// (map_cell_index, as keep_strongest_beam_per_cell's) up to kLeakageReachCells away in range and
// in range rate, where the window's separable response W(i - d_r) W(j - d_v) / (W(d_r) W(d_v))
// keeps it at or over threshold_db: d_r, d_v are the detection's offsets from its cell's centre,
// in cells. The added detection has the detection's azimuth and object and lies whole cells from
// it (at most 1e-6 cells moved off a cell's edge). Appended after the detections, in their order
// (i, then j ascending); nothing for a window of none.
void add_spectral_leakage(const ResolutionCell& cell, double threshold_db, Detections& detections);

}  // namespace rcsim
