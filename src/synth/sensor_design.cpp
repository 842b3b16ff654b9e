#include "synth/sensor_design.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "common/angles.hpp"
#include "common/decibel.hpp"
#include "synth/propagation.hpp"

namespace rcsim::synth {
namespace {

// A frame's values on the grid a radar's synthesiser and timer work on (and that the design's
// figures lie on): the bandwidth to the whole MHz, chirp times to 0.1 us, angles to 1e-9 deg.
double to_whole_mhz(double hz) { return std::round(hz / 1e6) * 1e6; }
double to_tenth_us(double s) { return std::round(s * 1e7) / 1e7; }
double to_nano_deg(double deg) { return std::round(deg * 1e9) / 1e9; }

[[noreturn]] void refuse(const SensorConfig& profile, const std::string& why) {
  throw std::invalid_argument(fmt::format("sensor profile \"{}\" cannot be synthesised: {}", profile.name, why));
}

// The waveform: carrier from the profile; bandwidth from its range cell, chirp count and period
// from its range-rate cell, with the design's unambiguous range rate and ADC duty cycle.
Waveform waveform_for(const SensorConfig& profile, const SynthConfig& design, double synthesis_max_range_m) {
  const Waveform& d = design.waveform;
  Waveform w = d;
  w.carrier_hz = profile.carrier_frequency_hz;
  const double lambda_m = kSpeedOfLight_mps / w.carrier_hz;
  // FMCW range resolution dR = c / (2 B)  =>  B = c / (2 dR).
  w.bandwidth_hz = to_whole_mhz(kSpeedOfLight_mps / (2.0 * profile.resolution.range_cell_m));
  if (w.bandwidth_hz <= 0.0) refuse(profile, fmt::format("its range cell of {} m needs a bandwidth below 1 MHz", profile.resolution.range_cell_m));
  // Chirp sequence: Doppler resolution dv = lambda / (2 N_c T_c), unambiguous +-lambda / (4 T_c) =
  // +-dv N_c / 2. The fewest chirps (a power of two, for the FFT) that cover the design's
  // unambiguous range rate, then T_c from dv.
  const double design_lambda_m = kSpeedOfLight_mps / d.carrier_hz;
  const double v_unambiguous_mps = design_lambda_m / (4.0 * d.chirp_period_s);
  const double dv_mps = profile.resolution.range_rate_cell_mps;
  w.chirps = 16;
  while (dv_mps * w.chirps / 2.0 < v_unambiguous_mps && w.chirps < 4096) w.chirps *= 2;
  if (dv_mps * w.chirps / 2.0 < v_unambiguous_mps) {
    refuse(profile, fmt::format("its range-rate cell of {} m/s needs more than 4096 chirps for +-{:.0f} m/s", dv_mps, v_unambiguous_mps));
  }
  w.chirp_period_s = to_tenth_us(lambda_m / (2.0 * dv_mps * w.chirps));
  w.ramp_sampling_s = to_tenth_us(w.chirp_period_s * (d.ramp_sampling_s / d.chirp_period_s));  // the design's duty cycle
  if (w.ramp_sampling_s < 1e-6) {
    refuse(profile, fmt::format("its range-rate cell of {} m/s at {} GHz needs chirps shorter than 1 us", dv_mps,
                                w.carrier_hz / 1e9));
  }
  w.chirps_per_block = std::min(d.chirps_per_block, w.chirps);
  // Complex sampling: N_s samples over the ramp reach N_s dR unambiguously; enough for the
  // synthesis range (beyond it nothing is synthesised, so nothing folds back).
  const double range_bin_m = kSpeedOfLight_mps / (2.0 * w.bandwidth_hz);
  while (w.samples_per_chirp * range_bin_m < synthesis_max_range_m && w.samples_per_chirp < 8192) w.samples_per_chirp *= 2;
  if (w.samples_per_chirp * range_bin_m < synthesis_max_range_m) {
    refuse(profile, fmt::format("its range of {} m needs more than 8192 samples per chirp", profile.fov.max_range_m));
  }
  return w;
}

// The antenna: the profile's receive pair, field of view and range.
Antenna antenna_for(const SensorConfig& profile, const SynthConfig& design) {
  Antenna a = design.antenna;
  a.element_spacing_wavelengths = profile.antenna.element_spacing_wavelengths;
  a.dipole_length_wavelengths = profile.antenna.dipole_length_wavelengths;
  a.azimuth_half_fov_deg = to_nano_deg(rad_to_deg(profile.fov.azimuth_half_rad));
  a.min_range_m = profile.fov.min_range_m;
  a.max_range_m = profile.fov.max_range_m;
  // Monopulse: Im(delta/sum) = tan(psi/2), psi = 2 pi d/lambda sin(phi), is unambiguous while
  // |psi| < pi, i.e. |sin(phi)| < lambda / (2 d).
  const double d = a.element_spacing_wavelengths;
  const double sin_fov = std::sin(deg_to_rad(a.azimuth_half_fov_deg));
  if (d * sin_fov >= 0.5) {
    refuse(profile, fmt::format("its receive pair {} wavelengths apart is ambiguous within its +-{} deg field of view", d,
                                a.azimuth_half_fov_deg));
  }
  // The illuminated sector: the design's share of the field of view, but short of the angles
  // whose psi differs by 2 pi from one inside it (sin(phi') = lambda/d - sin(fov)): a grating
  // lobe would fold them into the field of view at a wrong angle.
  a.azimuth_half_illuminated_deg =
      std::min(a.azimuth_half_fov_deg * (design.antenna.azimuth_half_illuminated_deg / design.antenna.azimuth_half_fov_deg), 89.0);
  if (const double sin_alias = 1.0 / d - sin_fov; sin_alias < 1.0) {
    a.azimuth_half_illuminated_deg = std::min(a.azimuth_half_illuminated_deg, rad_to_deg(std::asin(sin_alias)));
  }
  return a;
}

}  // namespace

double unit_scatterer_snr_db(const SynthConfig& config, double range_m) {
  const Derived derived = derive(config);
  const Propagator propagation(config);
  const double r_cal = config.processing.calibration_range_m;
  // Radar equation: power ~ 1/R^4, through the IF filters (the receiver noise is white at the ADC).
  const double spreading = std::pow(r_cal / range_m, 4.0);
  const double filter = std::pow(propagation.if_gain(range_m) / propagation.if_gain(r_cal), 2.0);
  // Coherent gain of an N-point symmetric Hann window: (sum w)^2 / sum w^2 = 2 (N - 1) / 3.
  const double window_gain = 2.0 * (config.waveform.samples_per_chirp - 1) / 3.0 * 2.0 * (config.waveform.chirps - 1) / 3.0;
  return power_to_db(derived.snr_unit_per_sample * spreading * filter * window_gain);
}

SynthConfig sensor_design(const SensorConfig& profile, const SynthConfig& design) {
  if (!(profile.carrier_frequency_hz > 0.0) || !(profile.resolution.range_cell_m > 0.0) ||
      !(profile.resolution.range_rate_cell_mps > 0.0) || !(profile.fov.max_range_m > 0.0) ||
      !(profile.fov.azimuth_half_rad > 0.0) || !(profile.cycle_time_s > 0.0)) {
    refuse(profile, "it lacks a carrier, a range or range-rate cell, a field of view or a cycle time");
  }
  SynthConfig c = design;
  // Ranges scale with the profile's maximum range: the IF equalizer and anti-alias corners and
  // the synthesis range (design: 30, 55 and 70 m for 40 m), the annotator's reach (60 m). The
  // high-pass corner (3 m) shapes the near field and stays.
  const double range_scale = profile.fov.max_range_m / design.antenna.max_range_m;
  c.if_filter.equalizer_corner_range_m = design.if_filter.equalizer_corner_range_m * range_scale;
  c.if_filter.lowpass_corner_range_m = design.if_filter.lowpass_corner_range_m * range_scale;
  c.if_filter.synthesis_max_range_m = design.if_filter.synthesis_max_range_m * range_scale;
  c.annotation.max_range_m = design.annotation.max_range_m * range_scale;
  c.waveform = waveform_for(profile, design, c.if_filter.synthesis_max_range_m);
  c.antenna = antenna_for(profile, design);
  // Facets fine enough for the carrier: the design's facet wavelength scaled with the wavelength.
  c.propagation.facet_wavelength_m = design.propagation.facet_wavelength_m * (design.waveform.carrier_hz / c.waveform.carrier_hz);
  const double frame_s = c.waveform.chirps * c.waveform.chirp_period_s;
  if (frame_s > profile.cycle_time_s) {
    refuse(profile, fmt::format("its frame of {:.2f} ms ({} chirps of {} us) does not fit its cycle time of {} s",
                                frame_s * 1e3, c.waveform.chirps, c.waveform.chirp_period_s * 1e6, profile.cycle_time_s));
  }
  // The CFAR keeps the design's false alarms per frame: its false-alarm probability per cell
  // scales with the design's cells (range bins to the maximum range x Doppler bins) over these.
  const auto cells = [](const SynthConfig& config) {
    return config.antenna.max_range_m / derive(config).range_bin_m * config.waveform.chirps;
  };
  c.processing.cfar_false_alarm_probability = design.processing.cfar_false_alarm_probability * (cells(design) / cells(c));
  // Link budget: the unit scatterer (a car) reaches the profile's maximum range with the design's
  // SNR at its own maximum range; the transmit power (EIRP with the design's gains) makes it so.
  const double design_snr_db = unit_scatterer_snr_db(design, design.antenna.max_range_m);
  c.link.tx_power_dbm = design.link.tx_power_dbm + (design_snr_db - unit_scatterer_snr_db(c, c.antenna.max_range_m));
  // Amplitude scale: a sensor whose amplitude is an SNR (its profile's law is the radar
  // equation) reads the unit scatterer at the calibration range at its SNR, so that noise reads
  // 0 dB; otherwise the design's end-of-line calibration to paper eq. (1).
  if (profile.amplitude.kind == AmplitudeLawKind::radar_equation) {
    c.processing.calibration_level_db = unit_scatterer_snr_db(c, c.processing.calibration_range_m);
  }
  c.tracker.confirmation_hits = profile.tracker.confirmation_hits;  // paper III-E
  c.tracker.max_misses_tentative = profile.tracker.max_misses_tentative;
  c.tracker.max_misses_confirmed = profile.tracker.max_misses_confirmed;
  c.reports_detections = profile.reports == ListLevel::detections;
  return c;
}

std::vector<SynthConfig> sensor_designs(const Scene& scene, const SynthConfig& design) {
  std::vector<SynthConfig> designs;
  for (const MountedSensor& sensor : scene.sensors) {
    try {
      designs.push_back(sensor_design(sensor.config, design));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("sensor \"{}\": {}", sensor.id, e.what()));
    }
  }
  return designs;
}

void require_one_recording(const Scene& scene, const SynthConfig& design) {
  const std::vector<SynthConfig> designs = sensor_designs(scene, design);
  // One cycle clock (schemas/recording.md): every sensor at its own cycle time, which must then be
  // the scene's.
  const auto own_clock = [&](const MountedSensor& s) {
    return std::abs(s.config.cycle_time_s - scene.cycle_time_s) <= 1e-9 * scene.cycle_time_s;
  };
  if (!std::all_of(scene.sensors.begin(), scene.sensors.end(), own_clock)) {
    std::string list;
    for (const MountedSensor& s : scene.sensors) {
      list += fmt::format("{}\"{}\" ({}) {} s", list.empty() ? "" : ", ", s.id, s.config.name, s.config.cycle_time_s);
    }
    throw std::invalid_argument(fmt::format(
        "sensors whose cycle times are not the scene's {} s: {}. A recording has one cycle clock and synth runs each "
        "sensor at its own cycle time: synthesise sensors of different cycle times from separate scenes, without "
        "cycle_time_s or with theirs",
        scene.cycle_time_s, list));
  }
  // One targets.csv: track ids for all sensors or for none.
  for (std::size_t s = 1; s < designs.size(); ++s) {
    if (designs[s].reports_detections != designs[0].reports_detections) {
      const auto level = [](const SynthConfig& c) { return c.reports_detections ? "raw detections" : "tracks"; };
      throw std::invalid_argument(fmt::format(
          "sensor \"{}\" ({}) reports {} and sensor \"{}\" ({}) {}: a recording's targets.csv has track ids for all its "
          "sensors or for none; synthesise them from separate scenes",
          scene.sensors[0].id, scene.sensors[0].config.name, level(designs[0]), scene.sensors[s].id,
          scene.sensors[s].config.name, level(designs[s])));
    }
  }
}

}  // namespace rcsim::synth
