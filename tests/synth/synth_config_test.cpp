// derive() of synth/synth_config.hpp: the waveform's resolution cells and the radar equation's
// SNR of the unit scatterer, by hand for the reference design and as they scale.
#include "synth/synth_config.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::synth_config_test {

using synth::Derived;
using synth::SynthConfig;
using synth::derive;

// (The cells of the reference design: SynthSignalChain.DerivedResolution in signal_chain_test.cpp.)
TEST(SynthConfigDerive, ChirpSlopeAndSampleRateByHand) {
  const Derived d = derive(SynthConfig{});
  EXPECT_DOUBLE_EQ(d.chirp_slope_hzps, 500.0e6 / 80.0e-6);  // 6.25e12 Hz/s
  EXPECT_NEAR(d.sample_rate_hz, 3.2e6, 1e-3);                // 256 samples in 80 us
  // A 24.125 GHz carrier: lambda = c / f = 12.4267 mm.
  SynthConfig ism;
  ism.waveform.carrier_hz = 24.125e9;
  EXPECT_NEAR(derive(ism).wavelength_m, 0.0124267, 1e-7);
}

TEST(SynthConfigDerive, UnitScattererSnrFromTheRadarEquation) {
  // P_t = -18 dBm = 1.585e-5 W, G_t G_r / L = +5 dB, lambda = 12.49 mm, sigma = 30 m^2, R = 10 m:
  // P_r = P_t G lambda^2 sigma / ((4 pi)^3 R^4) = 1.182e-14 W; noise k 290 K 14 dB 3.2 MHz =
  // 3.218e-13 W: SNR 0.03673 per sample (-14.35 dB).
  const Derived d = derive(SynthConfig{});
  EXPECT_NEAR(d.snr_unit_per_sample, 0.036735, 1e-5);
  EXPECT_NEAR(10.0 * std::log10(d.snr_unit_per_sample), -14.349, 0.002);

  // +3 dB of transmit power doubles it; twice the calibration range divides it by 2^4.
  SynthConfig louder;
  louder.link.tx_power_dbm += 10.0 * std::log10(2.0);
  EXPECT_NEAR(derive(louder).snr_unit_per_sample / d.snr_unit_per_sample, 2.0, 1e-12);
  SynthConfig farther;
  farther.processing.calibration_range_m = 20.0;
  EXPECT_NEAR(derive(farther).snr_unit_per_sample / d.snr_unit_per_sample, 1.0 / 16.0, 1e-12);
  // Twice the samples in the same ramp: twice the noise bandwidth, half the SNR per sample.
  SynthConfig denser;
  denser.waveform.samples_per_chirp = 512;
  EXPECT_NEAR(derive(denser).snr_unit_per_sample / d.snr_unit_per_sample, 0.5, 1e-12);
}

TEST(SynthConfigDerive, CellsScaleWithBandwidthAndChirps) {
  // Twice the bandwidth: half the range bin (0.15 m); twice the chirps: half the range-rate bin
  // and twice the frame.
  SynthConfig c;
  c.waveform.bandwidth_hz = 1.0e9;
  c.waveform.chirps = 256;
  const Derived base = derive(SynthConfig{});
  const Derived d = derive(c);
  EXPECT_NEAR(d.range_bin_m, 299792458.0 / 2.0e9, 1e-12);
  EXPECT_NEAR(d.range_rate_bin_mps, 0.5 * base.range_rate_bin_mps, 1e-15);
  EXPECT_NEAR(d.frame_s, 2.0 * base.frame_s, 1e-15);
  // The configurations differ, and compare so.
  EXPECT_FALSE(c == SynthConfig{});
  EXPECT_TRUE(SynthConfig{} == SynthConfig{});
}

}  // namespace rcsim::synth_config_test
