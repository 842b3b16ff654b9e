#include "synth/propagation.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim::synth {
namespace {

double si(double x) { return std::abs(x) < 1e-9 ? 1.0 : std::sin(x) / x; }

}  // namespace

bool segment_crosses_box(const Vec2& a_W, const Vec2& b_W, const PlacedBody& placed, double shrink_m) {
  const double hx = 0.5 * placed.body->length_m - shrink_m;
  const double hy = 0.5 * placed.body->width_m - shrink_m;
  if (hx <= 0.0 || hy <= 0.0) return false;
  const Vec2 a = inverse_transform_point(placed.state.X_WB, a_W);
  const Vec2 b = inverse_transform_point(placed.state.X_WB, b_W);
  // Slab test (Liang-Barsky) on the segment a + t (b - a), t in [0, 1].
  const Vec2 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() + hx, hx - a.x(), a.y() + hy, hy - a.y()};
  for (int i = 0; i < 4; ++i) {
    if (std::abs(p[i]) < 1e-15) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

Propagator::Propagator(const SynthConfig& config) : config_(config), derived_(derive(config)) {
  // cos(e)^q = 1/sqrt(2) at the half-power elevation.
  elevation_exponent_ = std::log(std::sqrt(0.5)) / std::log(std::cos(deg_to_rad(config.antenna.elevation_half_power_deg)));
  // After the range-Doppler FFT an echo of amplitude a has SNR ~ |a|^2 snr N_s N_c 0.44 (two Hann
  // windows); echoes 20 dB below the noise there cannot change a detection.
  const double n = static_cast<double>(config.waveform.samples_per_chirp) * config.waveform.chirps;
  amplitude_floor_ = if_gain(config.processing.calibration_range_m) * std::sqrt(1e-2 / (derived_.snr_unit_per_sample * n * 0.44));
}

double Propagator::elevation_pattern(double elevation_rad) const {
  const double c = std::cos(elevation_rad);
  return std::max(std::pow(std::max(c, 0.0), elevation_exponent_), config_.antenna.elevation_sidelobe_floor);
}

std::pair<std::complex<double>, std::complex<double>> Propagator::antenna(double azimuth_rad, double elevation_rad) const {
  const Antenna& a = config_.antenna;
  const double s = std::sin(azimuth_rad);
  // Half-wave dipole element pattern si(pi L/lambda sin phi) cos phi (paper eq. (6), element part),
  // used for the transmit element and each receive element.
  const double element = si(kPi * a.dipole_length_wavelengths * s) * std::cos(azimuth_rad);
  // Receive elements at y = +-d/2: phases +-psi/2, psi = 2 pi d/lambda sin(phi) cos(e).
  // sum = (left + right)/2 = cos(psi/2), delta = (left - right)/2 = j sin(psi/2).
  const double half_psi = kPi * a.element_spacing_wavelengths * s * std::cos(elevation_rad);
  const double two_way = element * element;
  return {two_way * std::cos(half_psi), std::complex<double>(0.0, two_way * std::sin(half_psi))};
}

std::complex<double> Propagator::two_ray_factor(double ground_range_m, double height_m, double vertical_extent_m) const {
  const double hs = config_.antenna.mount_height_m;
  const double gamma = config_.propagation.ground_reflection;
  const double k = kTwoPi / derived_.wavelength_m;
  const double r_direct = std::hypot(ground_range_m, height_m - hs);
  const double r_image = std::hypot(ground_range_m, height_m + hs);
  const double g_direct = elevation_pattern(std::atan2(height_m - hs, ground_range_m));
  const double g_image = elevation_pattern(std::atan2(height_m + hs, ground_range_m));
  if (gamma == 0.0) return g_direct * g_direct;
  // One way F(h) = g_d + Gamma g_i exp(-j k (R_i - R_d)); two way F^2, averaged over the span
  // [h - H/2, h + H/2] with the path difference linear in h: <exp(-j n k D(h))> =
  // exp(-j n k D(h_c)) si(n k D'(h_c) H / 2).
  const double path_difference_m = r_image - r_direct;
  const double slope = (height_m + hs) / r_image - (height_m - hs) / r_direct;  // dD/dh
  const double x = k * slope * vertical_extent_m / 2.0;
  const std::complex<double> e1 = std::polar(si(x), -k * path_difference_m);
  const std::complex<double> e2 = std::polar(si(2.0 * x), -2.0 * k * path_difference_m);
  return g_direct * g_direct + 2.0 * gamma * g_direct * g_image * e1 + gamma * gamma * g_image * g_image * e2;
}

double Propagator::if_gain(double range_m) const {
  const IfFilter& f = config_.if_filter;
  const double xh = std::pow(range_m / f.highpass_corner_range_m, f.highpass_order);
  const double xl = std::pow(range_m / f.lowpass_corner_range_m, f.lowpass_order);
  const double xe = range_m / f.equalizer_corner_range_m;
  return xe / std::sqrt(1.0 + xe * xe) * xh / std::sqrt(1.0 + xh * xh) / std::sqrt(1.0 + xl * xl);
}

void Propagator::add_echo(std::vector<Echo>& out, const Scatterer& s, double sqrt_sigma_rel, const Vec2& p_SP_S,
                           double range_rate_2d_mps, double incidence_rad) const {
  const double hs = config_.antenna.mount_height_m;
  const double ground_m = p_SP_S.norm();
  const double range_m = std::hypot(ground_m, s.height_m - hs);
  const double azimuth_rad = std::atan2(p_SP_S.y(), p_SP_S.x());
  const double elevation_rad = std::atan2(s.height_m - hs, ground_m);
  const double r_cal = config_.processing.calibration_range_m;
  // Radar equation in amplitude: sqrt(sigma) / R^2, relative to the unit scatterer at r_cal.
  const double spreading = (r_cal / range_m) * (r_cal / range_m);
  const std::complex<double> a = sqrt_sigma_rel * spreading * two_ray_factor(ground_m, s.height_m, s.vertical_extent_m);
  const auto [h_sum, h_delta] = antenna(azimuth_rad, elevation_rad);
  const double rate_mps = range_rate_2d_mps * ground_m / range_m;
  const double gain = if_gain(range_m);
  const std::complex<double> sum = a * h_sum * gain;
  const std::complex<double> delta = a * h_delta * gain;
  if (std::abs(sum) + std::abs(delta) < amplitude_floor_) return;
  out.push_back({range_m, rate_mps, azimuth_rad, sum, delta});
  // Back-and-forth reflections between a face and the ego's front (paper Fig. 17): image echoes at
  // n R with n times the range rate; a mirror-like pair of faces spreads as 1/(n R) (image source),
  // so relative to the direct echo rho^(n-1) / n, and the IF high-pass passes them more.
  const auto& mb = config_.propagation;
  if (!s.mirrors || range_m > mb.multibounce_max_range_m ||
      std::abs(incidence_rad) > deg_to_rad(mb.multibounce_max_incidence_deg)) {
    return;
  }
  double loss = 1.0;
  for (int n = 2; n <= mb.multibounce_max_order; ++n) {
    loss *= mb.multibounce_ego_reflectivity;
    const double range_n = n * range_m;
    const double factor = loss / n * if_gain(range_n) / gain;
    out.push_back({range_n, n * rate_mps, azimuth_rad, sum * factor, delta * factor});
  }
}

std::vector<Echo> Propagator::echoes(const SensorState& sensor, const std::vector<PlacedBody>& bodies,
                                      const std::vector<WorldScatterer>& world_scatterers) const {
  std::vector<Echo> out;
  const double max_range_m = config_.if_filter.synthesis_max_range_m;
  const double cos_half_sector = std::cos(deg_to_rad(config_.antenna.azimuth_half_illuminated_deg));
  const double shrink_m = config_.propagation.occluder_shrink_m;
  const Vec2 p_WS = sensor.X_WS.translation();
  const Vec2 boresight_W = rotate(sensor.X_WS.yaw_rad, Vec2(1.0, 0.0));
  const double sqrt_sigma_ref = std::sqrt(config_.link.sigma_ref_m2);

  // Is the ray sensor -> scatterer blocked by another body at least as tall as the scatterer?
  const auto occluded = [&](const Vec2& p_WP, double height_m, const PlacedBody* own) {
    for (const auto& other : bodies) {
      if (&other == own || other.body->height_m < height_m) continue;
      if (segment_crosses_box(p_WS, p_WP, other, shrink_m)) return true;
    }
    return false;
  };
  const auto visit = [&](const Scatterer& s, const Vec2& p_WP, const Vec2& v_WP_W, double body_yaw_rad,
                         const PlacedBody* own) {
    const Vec2 los_W = p_WP - p_WS;
    const double ground_m = los_W.norm();
    if (ground_m < 0.05 || ground_m > max_range_m) return;
    const Vec2 u_W = los_W / ground_m;
    if (u_W.dot(boresight_W) < cos_half_sector) return;
    // Incidence from the scatterer's axis to the direction back to the sensor.
    double incidence_rad = 0.0;
    double sqrt_sigma_rel = s.strength;
    if (s.kind != ScattererKind::isotropic) {
      const Vec2 axis_W = rotate(body_yaw_rad + s.axis_rad, Vec2(1.0, 0.0));
      const double c = -u_W.dot(axis_W);
      if (c <= 0.0) return;  // seen from behind
      incidence_rad = std::atan2(-u_W.x() * axis_W.y() + u_W.y() * axis_W.x(), c);
      sqrt_sigma_rel = s.kind == ScattererKind::facet
                           ? facet_sqrt_rcs_m(s, incidence_rad, derived_.wavelength_m) / sqrt_sigma_ref
                           : s.strength * std::pow(c, s.lobe_exponent);
    }
    if (std::abs(sqrt_sigma_rel) < 1e-7) return;
    if (occluded(p_WP, s.elevated ? s.height_m : 0.0, own)) return;
    const double rate_mps = (v_WP_W - sensor.v_WS_W).dot(u_W);
    add_echo(out, s, sqrt_sigma_rel, inverse_transform_point(sensor.X_WS, p_WP), rate_mps, incidence_rad);
  };

  for (const auto& placed : bodies) {
    const double reach_m = 0.5 * std::hypot(placed.body->length_m, placed.body->width_m);
    if ((placed.state.X_WB.translation() - p_WS).norm() - reach_m > max_range_m) continue;
    for (const auto& s : placed.body->scatterers) {
      const Vec2 p_WP = transform_point(placed.state.X_WB, s.p_O);
      visit(s, p_WP, placed.state.point_velocity_W(p_WP), placed.state.X_WB.yaw_rad, &placed);
    }
  }
  for (const auto& w : world_scatterers) visit(w.scatterer, w.p_WC_W, Vec2::Zero(), 0.0, nullptr);
  return out;
}

}  // namespace rcsim::synth
