#include "synth/synth_config.hpp"

#include <cmath>

#include "common/angles.hpp"
#include "common/decibel.hpp"

namespace rcsim::synth {

Derived derive(const SynthConfig& config) {
  const Waveform& w = config.waveform;
  const LinkBudget& link = config.link;
  Derived d;
  d.wavelength_m = kSpeedOfLight_mps / w.carrier_hz;
  d.chirp_slope_hzps = w.bandwidth_hz / w.ramp_sampling_s;
  d.sample_rate_hz = w.samples_per_chirp / w.ramp_sampling_s;
  d.range_bin_m = kSpeedOfLight_mps / (2.0 * w.bandwidth_hz);
  d.range_rate_bin_mps = d.wavelength_m / (2.0 * w.chirps * w.chirp_period_s);
  d.frame_s = w.chirps * w.chirp_period_s;
  // Radar equation: P_r = P_t G_t G_r lambda^2 sigma / ((4 pi)^3 R^4 L); noise k T F B with the
  // complex sample rate as noise bandwidth.
  const double four_pi = 4.0 * kPi;
  const double p_t_w = 1e-3 * db_to_power(link.tx_power_dbm);
  const double gains = db_to_power(link.tx_gain_dbi + link.rx_gain_dbi - link.system_losses_db);
  const double r = config.processing.calibration_range_m;
  const double p_r_w = p_t_w * gains * d.wavelength_m * d.wavelength_m * link.sigma_ref_m2 /
                       (four_pi * four_pi * four_pi * r * r * r * r);
  const double noise_w =
      kBoltzmann_JpK * link.temperature_k * db_to_power(link.noise_figure_db) * d.sample_rate_hz;
  d.snr_unit_per_sample = p_r_w / noise_w;
  return d;
}

}  // namespace rcsim::synth
