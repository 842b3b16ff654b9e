#include "synth/signal_chain.hpp"

#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/FFT>

#include "common/angles.hpp"
#include "common/decibel.hpp"

namespace rcsim::synth {
namespace {

using cfloat = std::complex<float>;

// Hann window (symmetric), w[n] = 0.5 (1 - cos(2 pi n / (N - 1))).
std::vector<float> hann(int n) {
  std::vector<float> w(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) w[i] = static_cast<float>(0.5 * (1.0 - std::cos(kTwoPi * i / (n - 1))));
  return w;
}

double sum_of_squares(const std::vector<float>& w) {
  double s = 0.0;
  for (const float x : w) s += static_cast<double>(x) * x;
  return s;
}

int wrap_index(int i, int n) { return ((i % n) + n) % n; }

// Parabola through the log magnitudes at -1, 0, +1: offset of the vertex in [-0.5, 0.5] and the
// vertex height (Gaussian interpolation, close to exact for the Hann main lobe).
std::pair<double, double> log_parabola(double lm, double l0, double lp) {
  const double denominator = lm - 2.0 * l0 + lp;
  if (denominator >= -1e-12) return {0.0, l0};
  const double offset = std::clamp(0.5 * (lm - lp) / denominator, -0.5, 0.5);
  return {offset, l0 - 0.25 * (lm - lp) * offset};
}

}  // namespace

SignalChain::SignalChain(const SynthConfig& config) : config_(config), derived_(derive(config)) {
  const Waveform& w = config_.waveform;
  const Processing& p = config_.processing;
  const int margin = p.cfar_guard_cells + p.cfar_training_cells_range + 2;
  processed_range_bins_ = std::min(
      w.samples_per_chirp, static_cast<int>(std::ceil(config_.antenna.max_range_m / derived_.range_bin_m)) + margin);
  // Receiver noise referred to the ADC: white there (after the equalizing IF filters, IF-amplifier
  // and ADC noise dominate), at the level that gives the link budget's thermal SNR at the
  // calibration range.
  const Propagator propagation(config_);
  noise_sigma_ = propagation.if_gain(p.calibration_range_m) / std::sqrt(derived_.snr_unit_per_sample);
  for (int n = 0; n <= 2 * p.cfar_training_cells_range; ++n) cfar_factors_.push_back(cfar_factor(n));
  range_window_ = hann(w.samples_per_chirp);
  doppler_window_ = hann(w.chirps);

  // Calibration with a reference target, as on the sensor's end-of-line test: a unit isotropic
  // scatterer on boresight at the calibration range, free space, no noise.
  const double r_cal = p.calibration_range_m;
  synthesize({Echo{r_cal, 0.0, 0.0, propagation.if_gain(r_cal), 0.0}});
  transform();
  int best_r = 1, best_d = 0;
  float best = -1.0f;
  for (int r = 1; r < map_.range_bins; ++r) {
    for (int d = 0; d < map_.doppler_bins; ++d) {
      if (std::norm(map_.sum(r, d)) > best) {
        best = std::norm(map_.sum(r, d));
        best_r = r;
        best_d = d;
      }
    }
  }
  const auto level = [&](int r, int d) { return 0.5 * std::log(std::max(1e-30, static_cast<double>(std::norm(map_.sum(r, wrap_index(d, map_.doppler_bins)))))); };
  const auto [dr, lr] = log_parabola(level(best_r - 1, best_d), level(best_r, best_d), level(best_r + 1, best_d));
  const auto [dd, ld] = log_parabola(level(best_r, best_d - 1), level(best_r, best_d), level(best_r, best_d + 1));
  (void)dr;
  (void)dd;
  const double peak_ln = lr + ld - level(best_r, best_d);
  calibration_db_ = p.calibration_level_db - 20.0 / std::log(10.0) * peak_ln;
}

namespace {

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// The k-th smallest of n unit exponential variates: density and distribution (David & Nagaraja,
// Order Statistics, 2.1).
double os_density(int n, int k, double z) {
  const double q = std::exp(-z);
  return k * binomial(n, k) * std::pow(1.0 - q, k - 1) * std::pow(q, n - k + 1);
}
double os_distribution(int n, int k, double z) {
  const double q = std::exp(-z);
  double f = 0.0;
  for (int j = k; j <= n; ++j) f += binomial(n, j) * std::pow(1.0 - q, j) * std::pow(q, n - j);
  return f;
}

}  // namespace

int SignalChain::os_rank(int training_cells) const {
  return std::clamp(static_cast<int>(std::lround(config_.processing.cfar_rank_fraction * training_cells)), 1,
                    training_cells);
}

double SignalChain::cfar_false_alarm_rate(int range_cells, double factor) const {
  // Noise alone (unit exponential cells): the estimate is Z = min(A, B) of the two order
  // statistics, and Pfa = E[exp(-alpha Z)] = int exp(-alpha z) (f_A (1 - F_B) + f_B (1 - F_A)) dz
  // (Rohling 1983 for one OS estimate), by Simpson's rule on the density of Z tabulated once.
  const int nd = 2 * config_.processing.cfar_training_cells_doppler;
  const int kd = os_rank(nd);
  const int kr = os_rank(std::max(range_cells, 1));
  const int steps = 1200;
  const double z_max = 12.0, h = z_max / steps;
  std::vector<double> density(steps + 1);
  for (int i = 0; i <= steps; ++i) {
    const double z = i * h;
    if (range_cells <= 0) {
      density[i] = os_density(nd, kd, z);
    } else {
      density[i] = os_density(range_cells, kr, z) * (1.0 - os_distribution(nd, kd, z)) +
                   os_density(nd, kd, z) * (1.0 - os_distribution(range_cells, kr, z));
    }
  }
  const auto pfa = [&](double alpha) {
    double sum = density[0] + std::exp(-alpha * z_max) * density[steps];
    for (int i = 1; i < steps; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * std::exp(-alpha * i * h) * density[i];
    return sum * h / 3.0;
  };
  if (factor >= 0.0) return pfa(factor);
  // factor < 0: solve Pfa(alpha) = design value by bisection on log alpha (Pfa falls with alpha).
  const double target = config_.processing.cfar_false_alarm_probability;
  double lo = 1e-2, hi = 1e5;
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(lo * hi);
    (pfa(mid) > target ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

double SignalChain::cfar_factor(int range_cells) const { return cfar_false_alarm_rate(range_cells, -1.0); }

double SignalChain::noise_floor_db() const {
  const double cell_power = noise_sigma_ * noise_sigma_ * sum_of_squares(range_window_) * sum_of_squares(doppler_window_);
  return power_to_db(cell_power) + calibration_db_;
}

void SignalChain::synthesize(const std::vector<Echo>& echoes) {
  const Waveform& w = config_.waveform;
  const int ns = w.samples_per_chirp, nc = w.chirps, nb = std::max(1, w.chirps_per_block);
  samples_.setZero(2 * ns, nc);
  const auto k_count = static_cast<Eigen::Index>(echoes.size());
  if (k_count == 0) return;
  const double lambda = derived_.wavelength_m;
  const double four_pi_over_lambda = 4.0 * kPi / lambda;
  for (int m0 = 0; m0 < nc; m0 += nb) {
    const int count = std::min(nb, nc - m0);
    block_a_.resize(2 * ns, k_count);
    block_b_.resize(k_count, count);
    const double t_block_s = (m0 + 0.5 * count - 0.5 * nc) * w.chirp_period_s;
    for (Eigen::Index k = 0; k < k_count; ++k) {
      const Echo& e = echoes[static_cast<std::size_t>(k)];
      // Beat frequency of the block (range migrates between blocks): f_b = 2 S R / c + 2 v / lambda
      // (the carrier's Doppler within the chirp couples range and range rate).
      const double range_m = e.range_m + e.range_rate_mps * t_block_s;
      const double beat_hz = 2.0 * derived_.chirp_slope_hzps * range_m / kSpeedOfLight_mps + 2.0 * e.range_rate_mps / lambda;
      // Fast time by a phase recurrence: p_{n+1} = p_n exp(j omega).
      const std::complex<double> step = std::polar(1.0, kTwoPi * beat_hz / derived_.sample_rate_hz);
      std::complex<double> phasor(1.0, 0.0);
      for (int n = 0; n < ns; ++n) {
        block_a_(n, k) = cfloat(e.sum * phasor);
        block_a_(n + ns, k) = cfloat(e.delta * phasor);
        phasor *= step;
      }
      // Slow time: the carrier phase 4 pi R_m / lambda of chirp m, R_m = R + v t_m.
      const double t0_s = (m0 - 0.5 * nc) * w.chirp_period_s;
      std::complex<double> carrier = std::polar(1.0, four_pi_over_lambda * (e.range_m + e.range_rate_mps * t0_s));
      const std::complex<double> carrier_step = std::polar(1.0, four_pi_over_lambda * e.range_rate_mps * w.chirp_period_s);
      for (int j = 0; j < count; ++j) {
        block_b_(k, j) = cfloat(carrier);
        carrier *= carrier_step;
      }
    }
    // Superposition of all echoes: one complex matrix product per block.
    samples_.middleCols(m0, count).noalias() = block_a_ * block_b_;
  }
}

void SignalChain::add_receiver_noise(Rng& rng) {
  const double s = noise_sigma_ / std::sqrt(2.0);
  for (Eigen::Index m = 0; m < samples_.cols(); ++m) {
    for (Eigen::Index n = 0; n < samples_.rows(); ++n) {
      const double re = s * rng.normal();
      const double im = s * rng.normal();
      samples_(n, m) += cfloat(static_cast<float>(re), static_cast<float>(im));
    }
  }
}

void SignalChain::transform() {
  const int ns = config_.waveform.samples_per_chirp, nc = config_.waveform.chirps;
  Eigen::FFT<float> fft;
  std::vector<cfloat> in(static_cast<std::size_t>(std::max(ns, nc))), out(in.size());
  spectrum_.resize(2 * ns, nc);
  // Range FFT of every chirp and channel.
  for (int m = 0; m < nc; ++m) {
    for (int c = 0; c < 2; ++c) {
      const cfloat* column = samples_.col(m).data() + c * ns;
      for (int n = 0; n < ns; ++n) in[n] = column[n] * range_window_[n];
      fft.fwd(out.data(), in.data(), ns);
      std::copy(out.begin(), out.begin() + ns, spectrum_.col(m).data() + c * ns);
    }
  }
  // Doppler FFT of the processed range bins; column chirps/2 holds 0 m/s.
  map_.range_bins = processed_range_bins_;
  map_.doppler_bins = nc;
  map_.sum.resize(processed_range_bins_, nc);
  map_.delta.resize(processed_range_bins_, nc);
  for (int c = 0; c < 2; ++c) {
    Eigen::MatrixXcf& target = c == 0 ? map_.sum : map_.delta;
    for (int r = 0; r < processed_range_bins_; ++r) {
      for (int m = 0; m < nc; ++m) in[m] = spectrum_(c * ns + r, m) * doppler_window_[m];
      fft.fwd(out.data(), in.data(), nc);
      for (int d = 0; d < nc; ++d) target(r, wrap_index(d + nc / 2, nc)) = out[d];
    }
  }
}

struct SignalChain::CfarCandidate {
  int r, d;
  float power;
  double noise;
};

namespace {

// Local maximum of the 3 x 3 neighbourhood (Doppler wraps; ties go to the first cell).
bool is_local_maximum(const Eigen::MatrixXf& power, int r, int d) {
  const int nr = static_cast<int>(power.rows()), nd = static_cast<int>(power.cols());
  const float cell = power(r, d);
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dd = -1; dd <= 1; ++dd) {
      if (dr == 0 && dd == 0) continue;
      const int rr = r + dr;
      if (rr < 0 || rr >= nr) continue;
      const float other = power(rr, wrap_index(d + dd, nd));
      if (other > cell || (other == cell && (dr < 0 || (dr == 0 && dd < 0)))) return false;
    }
  }
  return true;
}

}  // namespace

std::vector<SignalChain::CfarCandidate> SignalChain::cfar_candidates(const Eigen::MatrixXf& power) const {
  const Processing& p = config_.processing;
  const int nr = map_.range_bins, nd = map_.doppler_bins;
  const int r_lo = std::max(1, static_cast<int>(std::ceil(config_.antenna.min_range_m / derived_.range_bin_m)) - 1);
  const int r_hi = std::min(nr - 2, static_cast<int>(config_.antenna.max_range_m / derived_.range_bin_m) + 1);
  const double noise_cell_power = noise_sigma_ * noise_sigma_ * sum_of_squares(range_window_) * sum_of_squares(doppler_window_);
  const int g = p.cfar_guard_cells, tr = p.cfar_training_cells_range, td = p.cfar_training_cells_doppler;
  std::vector<float> range_training, doppler_training;
  const auto order_statistic = [&](std::vector<float>& v) {
    const int rank = os_rank(static_cast<int>(v.size()));
    std::nth_element(v.begin(), v.begin() + (rank - 1), v.end());
    return static_cast<double>(v[rank - 1]);
  };
  std::vector<CfarCandidate> candidates;
  for (int r = r_lo; r <= r_hi; ++r) {
    for (int d = 0; d < nd; ++d) {
      if (!is_local_maximum(power, r, d)) continue;
      // OS-CFAR along range and along Doppler, beyond the guard cells; the smaller of the two
      // estimates, so that an extended target or a row of echoes in one dimension cannot mask.
      range_training.clear();
      doppler_training.clear();
      for (int i = g + 1; i <= g + tr; ++i) {
        for (const int rr : {r - i, r + i}) {
          if (rr >= 1 && rr < nr) range_training.push_back(power(rr, d));
        }
      }
      for (int i = g + 1; i <= g + td; ++i) {
        doppler_training.push_back(power(r, wrap_index(d - i, nd)));
        doppler_training.push_back(power(r, wrap_index(d + i, nd)));
      }
      const int n = static_cast<int>(range_training.size());
      const double doppler_noise = order_statistic(doppler_training);
      // A receiver is never quieter than its thermal noise: the floor keeps noise-free test runs from
      // detecting window sidelobes far below it.
      const double noise = std::max(n > 0 ? std::min(order_statistic(range_training), doppler_noise) : doppler_noise,
                                    0.1 * noise_cell_power);
      if (power(r, d) > cfar_factors_[n] * noise) candidates.push_back({r, d, power(r, d), noise});
    }
  }
  return candidates;
}

std::vector<SignalChain::CfarCandidate> SignalChain::blank_sidelobes(std::vector<CfarCandidate> candidates) const {
  const Processing& p = config_.processing;
  const int nd = map_.doppler_bins;
  std::sort(candidates.begin(), candidates.end(), [](const CfarCandidate& a, const CfarCandidate& b) {
    return a.power != b.power ? a.power > b.power : (a.r != b.r ? a.r < b.r : a.d < b.d);
  });
  // A peak far below a stronger neighbour in its range row or Doppler column is that neighbour's
  // window sidelobe.
  const double blank = db_to_power(-p.sidelobe_blanking_db);
  const int reach = p.sidelobe_blanking_cells;
  std::vector<CfarCandidate> kept;
  for (const auto& c : candidates) {
    bool sidelobe = false;
    for (const auto& s : kept) {
      const int dr = std::abs(c.r - s.r);
      const int dd = std::min(std::abs(c.d - s.d), nd - std::abs(c.d - s.d));
      if (((dr <= reach && dd <= 1) || (dd <= reach && dr <= 1)) && c.power < s.power * blank) {
        sidelobe = true;
        break;
      }
    }
    if (!sidelobe) kept.push_back(c);
    if (static_cast<int>(kept.size()) >= p.max_detections) break;
  }
  return kept;
}

std::vector<Detection> SignalChain::estimate_detections(const std::vector<CfarCandidate>& kept,
                                                        const Eigen::MatrixXf& power) const {
  const int nd = map_.doppler_bins;
  std::vector<Detection> detections;
  const double half_fov = deg_to_rad(config_.antenna.azimuth_half_fov_deg);
  const double to_db = 20.0 / std::log(10.0);
  const auto level = [&](int r, int d) {
    return 0.5 * std::log(std::max(1e-30, static_cast<double>(power(r, wrap_index(d, nd)))));
  };
  for (const auto& c : kept) {
    const double l0 = level(c.r, c.d);
    const auto [dr, lr] = log_parabola(level(c.r - 1, c.d), l0, level(c.r + 1, c.d));
    const auto [dd, ld] = log_parabola(level(c.r, c.d - 1), l0, level(c.r, c.d + 1));
    Detection det;
    det.range_bin = c.r;
    det.doppler_bin = c.d;
    det.range_rate_mps = (c.d - nd / 2 + dd) * derived_.range_rate_bin_mps;
    // Range from the beat frequency minus the Doppler share (range-Doppler coupling).
    det.range_m = (c.r + dr) * derived_.range_bin_m -
                  det.range_rate_mps * kSpeedOfLight_mps / (derived_.wavelength_m * derived_.chirp_slope_hzps);
    det.amplitude_db = to_db * (lr + ld - l0) + calibration_db_;
    det.snr_db = power_to_db(c.power / c.noise);
    // Monopulse: delta/sum = j tan(psi/2), psi = 2 pi d/lambda sin(phi)  (sum/delta pair of eq. (6)).
    const std::complex<double> s = map_.sum(c.r, c.d), dl = map_.delta(c.r, c.d);
    const double im_ratio = (dl * std::conj(s)).imag() / std::max(std::norm(s), 1e-30);
    const double sin_phi = std::atan(im_ratio) / (kPi * config_.antenna.element_spacing_wavelengths);
    det.azimuth_rad = std::asin(std::clamp(sin_phi, -1.0, 1.0));
    if (std::abs(det.azimuth_rad) > half_fov) continue;
    if (det.range_m < config_.antenna.min_range_m || det.range_m > config_.antenna.max_range_m) continue;
    detections.push_back(det);
  }
  return detections;
}

std::vector<Detection> SignalChain::detect() const {
  const int nr = map_.range_bins, nd = map_.doppler_bins;
  Eigen::MatrixXf power(nr, nd);
  for (int r = 0; r < nr; ++r) {
    for (int d = 0; d < nd; ++d) power(r, d) = std::norm(map_.sum(r, d));
  }
  // power => CFAR peaks => sidelobes blanked => estimated detections
  return estimate_detections(blank_sidelobes(cfar_candidates(power)), power);
}

std::vector<Detection> SignalChain::process(const std::vector<Echo>& echoes, Rng& rng, bool add_noise) {
  synthesize(echoes);                 // echoes => I/Q samples, sum and delta
  if (add_noise) add_receiver_noise(rng);  // + receiver noise
  transform();                        // => range-Doppler maps
  return detect();                    // => CFAR detections with monopulse angles
}

}  // namespace rcsim::synth
