#pragma once
// The receiver and its processing for one frame (docs/synth.md, "Signal chain"):
//   echoes => beat signals of the sum and delta channels (chirp sequence, I/Q samples) + noise
//          => windows, range FFT, Doppler FFT (Eigen's FFT module)
//          => OS-CFAR on |sum|^2, local maxima, sidelobe blanking
//          => range, range rate (interpolated), monopulse azimuth, amplitude in dB (the sensor's scale)
#include <complex>
#include <vector>

#include <Eigen/Core>

#include "common/rng.hpp"
#include "synth/propagation.hpp"
#include "synth/synth_config.hpp"

namespace rcsim::synth {

struct Detection {
  double range_m = 0.0;
  double range_rate_mps = 0.0;
  double azimuth_rad = 0.0;
  double amplitude_db = 0.0;  // paper eq. (1) scale, or an SNR (sensor_design.cpp)
  double snr_db = 0.0;        // against the CFAR noise estimate
  int range_bin = 0;
  int doppler_bin = 0;        // 0 = -v_max, chirps/2 = 0 m/s
};

// The range-Doppler maps of one frame (only the processed range bins), kept for tests.
struct RangeDopplerMap {
  int range_bins = 0;
  int doppler_bins = 0;
  Eigen::MatrixXcf sum;    // range x Doppler (Doppler shifted: column chirps/2 is 0 m/s)
  Eigen::MatrixXcf delta;
};

class SignalChain {
 public:
  // Calibrates the amplitude scale: a unit isotropic scatterer on boresight at the calibration
  // range, in free space and without noise, reads calibration_level_db (paper eq. (1) at 10 m, or
  // its SNR for a sensor whose amplitude is one).
  explicit SignalChain(const SynthConfig& config);

  // One frame; noise drawn from rng unless add_noise is false.
  std::vector<Detection> process(const std::vector<Echo>& echoes, Rng& rng, bool add_noise = true);

  // The stages, for tests and the benchmark.
  void synthesize(const std::vector<Echo>& echoes);   // beat signals into the sample matrix
  void add_receiver_noise(Rng& rng);
  void transform();                                   // windows + 2-D FFT into map()
  std::vector<Detection> detect() const;              // CFAR + estimation on map()

  const RangeDopplerMap& map() const { return map_; }
  const Derived& derived() const { return derived_; }
  double calibration_db() const { return calibration_db_; }
  // Noise power per range-Doppler cell on the dB scale of the amplitudes.
  double noise_floor_db() const;
  // OS-CFAR: the rank k of the noise estimate among n training cells; the false-alarm rate on
  // noise alone of the test "cell > alpha min(OS_range, OS_Doppler)" with range_cells training
  // cells in range (fewer at the map's edge) (a negative factor: returns the alpha instead); the
  // alpha that meets cfar_false_alarm_probability.
  int os_rank(int training_cells) const;
  double cfar_false_alarm_rate(int range_cells, double factor) const;
  double cfar_factor(int range_cells) const;

 private:
  struct CfarCandidate;  // a local maximum above its CFAR threshold (signal_chain.cpp)
  // The stages of detect(): power map => local maxima over OS-CFAR => sidelobe blanking =>
  // range, range rate, amplitude and monopulse angle of each kept peak.
  std::vector<CfarCandidate> cfar_candidates(const Eigen::MatrixXf& power) const;
  std::vector<CfarCandidate> blank_sidelobes(std::vector<CfarCandidate> candidates) const;
  std::vector<Detection> estimate_detections(const std::vector<CfarCandidate>& kept, const Eigen::MatrixXf& power) const;

  SynthConfig config_;
  Derived derived_;
  int processed_range_bins_ = 0;
  double noise_sigma_ = 0.0;    // per complex sample and channel
  double calibration_db_ = 0.0;
  std::vector<double> cfar_factors_;  // by the number of range training cells
  std::vector<float> range_window_, doppler_window_;
  Eigen::MatrixXcf samples_;    // (2 N_s) x N_c: rows [0, N_s) sum, [N_s, 2 N_s) delta; column = chirp
  Eigen::MatrixXcf spectrum_;   // after the range FFT, same layout
  RangeDopplerMap map_;
  Eigen::MatrixXcf block_a_, block_b_;
};

}  // namespace rcsim::synth
