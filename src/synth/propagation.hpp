#pragma once
// From scatterers in the world to echoes at one sensor (docs/synth.md, "Propagation"): geometry
// and Doppler, occlusion by nearer bodies, the scattering response at the incidence angle, the
// two-ray ground path, the antenna patterns of the transmit element and of the sum and delta
// receive channels, the IF filters, and the ego <-> object back-and-forth reflections.
#include <complex>
#include <vector>

#include "common/pose2.hpp"
#include "synth/scatterers.hpp"
#include "synth/synth_config.hpp"

namespace rcsim::synth {

// One echo as the receiver sees it. Amplitudes are in the chain's units: the unit scatterer at the
// calibration range, on boresight, in free space and before the IF filters, has amplitude 1.
struct Echo {
  double range_m = 0.0;          // slant range at the frame's reference time
  double range_rate_mps = 0.0;   // negative when approaching
  double azimuth_rad = 0.0;      // true azimuth, sensor frame, positive to the left
  std::complex<double> sum;      // sum channel
  std::complex<double> delta;    // delta channel
};

// A body placed in the world at one instant.
struct PlacedBody {
  const ScattererBody* body = nullptr;
  BodyState state;  // X_WB is the box centre
};

// The sensor at one instant: its pose and the velocity of its origin in the world.
struct SensorState {
  Pose2 X_WS;
  Vec2 v_WS_W = Vec2::Zero();
};

class Propagator {
 public:
  explicit Propagator(const SynthConfig& config);

  // Echoes of all scatterers of all bodies (and the static world-frame scatterers, e.g. road
  // clutter) within the illuminated sector and the synthesis range.
  std::vector<Echo> echoes(const SensorState& sensor, const std::vector<PlacedBody>& bodies,
                           const std::vector<WorldScatterer>& world_scatterers) const;

  // Two-way factor of the transmit element and the receive pair: (sum, delta) for one azimuth
  // and elevation; sum = 1 on boresight.
  std::pair<std::complex<double>, std::complex<double>> antenna(double azimuth_rad, double elevation_rad) const;
  // One-way elevation pattern (amplitude), 1 in the horizontal plane.
  double elevation_pattern(double elevation_rad) const;
  // Two-way two-ray factor <F^2> of a scatterer at ground distance d, centre height h and
  // coherent vertical span H (docs/synth.md, "Two-ray ground path").
  std::complex<double> two_ray_factor(double ground_range_m, double height_m, double vertical_extent_m) const;
  // IF high-pass times anti-alias low-pass (amplitude) at the beat frequency of a range.
  double if_gain(double range_m) const;

 private:
  void add_echo(std::vector<Echo>& out, const Scatterer& s, double sqrt_sigma_rel, const Vec2& p_SP_S,
                double range_rate_2d_mps, double incidence_rad) const;

  SynthConfig config_;
  Derived derived_;
  double elevation_exponent_;
  double amplitude_floor_;  // echoes weaker than this cannot matter against the noise
};

// Does the segment from a to b (world, 2-D) cross the box of a placed body (shrunk by shrink_m)?
bool segment_crosses_box(const Vec2& a_W, const Vec2& b_W, const PlacedBody& body, double shrink_m);

}  // namespace rcsim::synth
