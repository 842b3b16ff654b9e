#pragma once
// Parameters of the signal-level reference simulator (`rcsim synth`, docs/synth.md): a 24 GHz
// chirp-sequence FMCW radar with one transmit element and two receive elements forming the sum
// and delta channels, its propagation, its processing (windows, range-Doppler FFT, OS-CFAR,
// monopulse) and its own tracker. Independent of the reflection-center sensor model (src/sim).
// The defaults are the reference design, a radar with srr24's facts (carrier, +-35 deg field of
// view, 0.2-40 m, lambda/2 monopulse pair, 0.30 m x 0.5 m/s cells); sensor_design.hpp adapts it
// to each sensor's profile. Built once per sensor, passed as const&.
#include <cstdint>

namespace rcsim::synth {

inline constexpr double kSpeedOfLight_mps = 299792458.0;
inline constexpr double kBoltzmann_JpK = 1.380649e-23;

struct Waveform {
  double carrier_hz = 24.0e9;         // srr24's carrier
  double bandwidth_hz = 500.0e6;      // range bin c / 2B = 0.30 m
  double ramp_sampling_s = 80.0e-6;   // ADC window of one chirp
  double chirp_period_s = 97.6e-6;    // chirp repetition: v bin lambda / (2 N_c T_c) = 0.50 m/s
  int samples_per_chirp = 256;        // complex (I/Q) samples: 76.8 m unambiguous range
  int chirps = 128;                   // 12.5 ms frame: +-32 m/s unambiguous range rate
  int chirps_per_block = 32;          // range migration: beat frequency updated every 3.1 ms
  bool operator==(const Waveform&) const = default;
};

struct Antenna {
  double element_spacing_wavelengths = 0.5;  // lambda/2, as srr24's monopulse pair
  double dipole_length_wavelengths = 0.5;    // element pattern si(pi L/lambda sin phi) cos phi
  double elevation_half_power_deg = 12.0;    // one-way, each of TX and RX
  double elevation_sidelobe_floor = 0.12;    // one-way amplitude floor of the elevation pattern
  double mount_height_m = 0.5;               // sensor height above the road
  double azimuth_half_fov_deg = 35.0;        // detections beyond are dropped (srr24's field of view)
  double azimuth_half_illuminated_deg = 70.0;  // scatterers beyond are not synthesized (< -25 dB two-way)
  double min_range_m = 0.2;
  double max_range_m = 40.0;
  bool operator==(const Antenna&) const = default;
};

// Radar equation (one unit scatterer = sigma_ref_m2): gives the SNR per ADC sample. A low-power
// short-range sensor: -12 dBm EIRP, near what the 24 GHz UWB rules (-41.3 dBm/MHz) allow over
// 500 MHz.
struct LinkBudget {
  double tx_power_dbm = -18.0;
  double tx_gain_dbi = 6.0;   // one wide-beam element
  double rx_gain_dbi = 6.0;   // per receive element
  double noise_figure_db = 14.0;
  double system_losses_db = 7.0;  // bumper fascia two-way 5 dB, implementation 2 dB
  double temperature_k = 290.0;
  double sigma_ref_m2 = 30.0;     // the unit scatterer: about the frontal RCS of a mid-size car
  bool operator==(const LinkBudget&) const = default;
};

// IF filters. The beat frequency is proportional to range, so the IF response is a range
// response: a first-order high-pass with its corner far out (amplitude ~ R below it) and a
// second-order one at short range equalize the R^-2 amplitude law of the radar equation over the
// working range (sensitivity-time control of FMCW sensors), with the result that amplitudes fall
// about as in paper eq. (1) between 3 and 25 m; the sixth-order anti-alias low-pass ends the
// range (scatterers beyond synthesis_max_range_m are not synthesized).
struct IfFilter {
  double equalizer_corner_range_m = 30.0;  // first order
  double highpass_corner_range_m = 3.0;
  int highpass_order = 2;
  double lowpass_corner_range_m = 55.0;
  int lowpass_order = 6;
  double synthesis_max_range_m = 70.0;
  bool operator==(const IfFilter&) const = default;
};

struct Propagation {
  double ground_reflection = -0.6;       // two-ray model: asphalt at grazing incidence
  double multibounce_max_range_m = 2.5;  // ego <-> object back-and-forth reflections (paper Fig. 17)
  int multibounce_max_order = 3;
  double multibounce_ego_reflectivity = 0.5;
  double multibounce_max_incidence_deg = 15.0;
  double occluder_shrink_m = 0.05;       // boxes shrunk so that grazing rays pass
  // Curved faces are cut into facets of ds <= sqrt(lambda rho) / 2 for this wavelength (scatterers.cpp):
  // about the carrier's (12.5 mm at 24 GHz).
  double facet_wavelength_m = 0.0125;
  bool operator==(const Propagation&) const = default;
};

struct Processing {
  // OS-CFAR on |sum|^2 along range and along Doppler (the smaller estimate), threshold factor from
  // the design false-alarm rate.
  int cfar_guard_cells = 2;
  int cfar_training_cells_range = 6;     // per side: 12 cells
  int cfar_training_cells_doppler = 8;   // per side: 16 cells
  double cfar_rank_fraction = 0.75;      // noise estimate: the 9th of 12, the 12th of 16
  double cfar_false_alarm_probability = 1.0e-5;
  double sidelobe_blanking_db = 28.0;    // a peak this far below a neighbour peak is its sidelobe
  int sidelobe_blanking_cells = 5;
  int max_detections = 40;               // strongest detections passed to the tracker
  double calibration_range_m = 10.0;     // unit scatterer on boresight reads eq. (1) here
  double calibration_level_db = 19.0;    // 26.5 - 0.75 * 10
  bool operator==(const Processing&) const = default;
};

// Road clutter: small static scatterers on the road surface (drains, joints, debris), a Poisson
// field drawn per 8 m tile from the seed; on when the scene's "clutter" effect is on.
struct Clutter {
  double density_per_m2 = 0.02;
  double median_rcs_rel_db = -14.0;  // re sigma_ref
  double rcs_spread_db = 5.0;
  double tile_m = 8.0;
  bool operator==(const Clutter&) const = default;
};

// The sensor-internal tracker (alpha-beta filters, nearest-neighbour association).
struct TrackerConfig {
  int confirmation_hits = 4;        // paper III-E
  int max_misses_tentative = 1;
  int max_misses_confirmed = 2;
  double gate_range_m = 0.7;
  double gate_range_rate_mps = 1.2;
  double gate_azimuth_rad = 0.2;
  double alpha_range = 0.5, beta_range = 0.3;
  double alpha_azimuth = 0.35, beta_azimuth = 0.1;
  double alpha_range_rate = 0.6;
  double alpha_amplitude = 0.5;
  int max_tracks = 48;
  bool operator==(const TrackerConfig&) const = default;
};

// Imperfect manual annotation of the boxes in objects.csv.
struct Annotation {
  double position_bias_sigma_m = 0.04;  // per object, constant
  double yaw_bias_sigma_rad = 0.012;
  double position_jitter_sigma_m = 0.02;  // per cycle
  double yaw_jitter_sigma_rad = 0.008;
  double speed_sigma_mps = 0.05;
  double max_range_m = 60.0;  // objects are annotated while within this distance of the ego
  bool operator==(const Annotation&) const = default;
};

struct SynthConfig {
  Waveform waveform;
  Antenna antenna;
  LinkBudget link;
  IfFilter if_filter;
  Propagation propagation;
  Processing processing;
  Clutter clutter;
  TrackerConfig tracker;
  Annotation annotation;
  // The sensor reports its raw detections of each cycle (no tracker; profile "reports":
  // "detections"), not confirmed tracks.
  bool reports_detections = false;
  bool operator==(const SynthConfig&) const = default;
};

// Quantities that follow from the configuration.
struct Derived {
  double wavelength_m = 0.0;
  double chirp_slope_hzps = 0.0;
  double sample_rate_hz = 0.0;
  double range_bin_m = 0.0;        // c / 2B
  double range_rate_bin_mps = 0.0;  // lambda / (2 N_c T_c)
  double frame_s = 0.0;
  double snr_unit_per_sample = 0.0;  // linear SNR of the unit scatterer at the calibration range
};

Derived derive(const SynthConfig& config);

}  // namespace rcsim::synth
