#pragma once
// Sensor configuration (`rcsim-sensor` files, schemas/sensor-config.md): every parameter of the
// sensor model of paper section III, with the paper's values in the built-in `srr24`.
#include <cmath>
#include <limits>
#include <string>

#include "common/amplitude_unit.hpp"
#include "common/decibel.hpp"
#include "common/list_level.hpp"
#include "common/json_reader.hpp"
#include "sensor/stationary_background.hpp"

namespace rcsim {

struct FieldOfView {
  double azimuth_half_rad = 0.0;
  double min_range_m = 0.0;
  double max_range_m = 0.0;
  // A radar that measures elevation (a 3+1D radar, docs/model.md "Elevation"): its view's half
  // angle in elevation, > 0. 0: planar, the paper's model (no heights, no elevation).
  double elevation_half_rad = 0.0;
  bool measures_elevation() const { return elevation_half_rad > 0.0; }
};

// How the range-dependent amplitude of the reference reflector falls with range.
enum class AmplitudeLawKind {
  paper_eq1,       // paper eq. (1): a level in dB falling linearly with range
  radar_equation,  // received power ~ sigma G(phi)^2 / R^4: the SNR of the reference reflector's RCS
};

struct AmplitudeLaw {
  AmplitudeLawKind kind = AmplitudeLawKind::paper_eq1;
  AmplitudeUnit unit = AmplitudeUnit::snr_db;
  double reference_level_db = 26.5;        // paper eq. (1): level at R = 0
  double reference_slope_db_per_m = 0.75;  // paper eq. (1): fall per metre
  // Radar equation: SNR = snr_at_1m_for_1m2_db + sigma_dbsm - 10 n log10(R / 1 m) on boresight, where
  // a reflector of ERCS e stands for sigma_dbsm = reference_rcs_dbsm + 20 log10(e) (docs/amplitude.md)
  // and n = range_exponent (4: P ~ 1/R^4; down to 0 for a range-compensated amplitude).
  double snr_at_1m_for_1m2_db = 0.0;
  double reference_rcs_dbsm = 0.0;
  double range_exponent = 4.0;
  double detection_threshold_db = 6.0;  // paper III-B
  // Where the radar's noise lies on this amplitude scale: the complex pointer noise of eq. (8) has
  // amplitude pointer_noise_sigma at this level (pointer_noise_amplitude). 0 on an SNR scale, by
  // definition; a relative scale (a range-compensated level, an RCS) names its own, below its
  // threshold (docs/amplitude.md).
  double noise_floor_db = 0.0;
};

// Target fluctuation (Swerling) of a resolution cell's amplitude from cycle to cycle; with the
// pointer noise of eq. (8) it makes the threshold of III-B a detection-probability curve.
enum class Fluctuation {
  none,       // Swerling 0: a steady amplitude (with pointer noise: Rice; without: a hard threshold)
  swerling1,  // power exponentially distributed (chi-square, 2 degrees of freedom), new each cycle
  swerling3,  // power chi-square with 4 degrees of freedom (one dominant scatterer), new each cycle
};

struct DetectionModel {
  Fluctuation fluctuation = Fluctuation::none;
  // A detection is reported only where its measured amplitude is a local maximum of the
  // range/range-rate map: no stronger detection within 1.5 cells in both (the peak search of a
  // CFAR detector; docs/extended-objects.md). false: every cell above threshold (the paper's).
  bool local_maxima_only = false;
  // An array that resolves azimuth (resolution.azimuth_cell_rad > 0) reports either every beam
  // over the threshold, or in each range/range-rate cell only its strongest beam (one detection
  // per range-Doppler cell, with the angle of that beam: the Astyx HiRes).
  bool strongest_beam_per_cell = false;
};

struct AntennaGeometry {
  double dipole_length_wavelengths = 0.5;    // L / lambda in eq. (6)
  double element_spacing_wavelengths = 0.5;  // d / lambda: exp(j 2 pi d/lambda sin(phi)) in eq. (6)
  // n in A^phi = |H_sum(phi)|^n of eq. (2): 1 is the paper's one-way pattern; a sensor whose
  // amplitude falls faster off boresight (transmit and receive patterns, n near 2) fits n > 1.
  // It scales sum and delta alike, so the monopulse angle (eq. (7)) does not change.
  double amplitude_pattern_exponent = 1.0;
};

// The window of the range and Doppler FFTs, whose main lobe spreads a strong return into the
// cells beside its own (sim/spectral_leakage.hpp); none: each return in its own cell only.
enum class SpectralWindow { none, hann };

struct ResolutionCell {
  double range_cell_m = 0.30;
  double range_rate_cell_mps = 0.5;
  // An imaging array's beam width: > 0, cells are range x range rate x azimuth and each cell's
  // angle is its beam's (docs/imaging-radar.md); 0, the paper's range x range-rate cells with one
  // monopulse angle each.
  double azimuth_cell_rad = 0.0;
  // The unambiguous range-rate interval [min, max): measured radial speeds are wrapped into it
  // (Doppler aliasing); min == max: no aliasing.
  double unambiguous_min_mps = 0.0, unambiguous_max_mps = 0.0;
  SpectralWindow window = SpectralWindow::none;
  // A radar that measures elevation: > 0, its cells are that wide in elevation too (beams in
  // elevation: one range-Doppler cell may report several, one per elevation cell; docs/model.md);
  // 0: one elevation per cell, its members' amplitude-weighted mean.
  double elevation_cell_rad = 0.0;
  bool resolves_elevation() const { return elevation_cell_rad > 0.0; }
  bool aliases_range_rate() const { return unambiguous_max_mps > unambiguous_min_mps; }
  bool resolves_azimuth() const { return azimuth_cell_rad > 0.0; }
};

// The cells of a radar's range/range-rate map, as its FFTs' bins lie: cell k is centred on k
// cells (zero Doppler at a cell's centre) and spans half a cell either side. The index of the cell
// holding x, and x's offset from that cell's centre in cells, in [-0.5, 0.5].
inline double map_cell_index(double x, double cell) { return std::round(x / cell); }
inline double map_cell_offset(double x, double cell) { return x / cell - map_cell_index(x, cell); }

// The angle of an array's beam cell: the amplitude-weighted azimuth of its members plus Gaussian
// noise of this standard deviation (docs/imaging-radar.md).
struct ArrayAngleNoise {
  double azimuth_sigma_rad = 0.0;
};

struct MeasurementNoise {
  double range_sigma_at_threshold_m = 0.1;
  double range_sigma_min_m = 0.02;
  double range_rate_sigma_at_threshold_mps = 0.15;
  double range_rate_sigma_min_mps = 0.03;
  double elevation_sigma_rad = 0.0;  // a radar that measures elevation: Gaussian noise of its elevation
};

struct TrackerConfig {
  int confirmation_hits = 4;  // paper III-E
  int max_misses_tentative = 1;
  int max_misses_confirmed = 2;
  double gate_chi2 = 16.0;
  int max_tracks = 64;
  double process_accel_sigma_mps2 = 6.0;
  double process_azimuth_rate_sigma_radps = 0.6;
  double process_amplitude_sigma_db = 3.0;
  double measurement_sigma_range_m = 0.1;
  double measurement_sigma_range_rate_mps = 0.15;
  double measurement_sigma_azimuth_rad = 0.05;
  double measurement_sigma_amplitude_db = 2.0;
};

struct ClutterConfig {
  double false_detections_per_cycle = 0.3;
  double amplitude_excess_mean_db = 2.0;
};

struct MultibounceConfig {
  double max_range_m = 3.0;
  int max_order = 3;
  double loss_per_bounce_db = 6.0;
};

// How a sensor of fine range resolution sees a plane reflector's face beyond its specular point:
// each range cell the face spans returns one diffuse piece (docs/extended-objects.md).
struct ExtendedObjects {
  // ERCS of a piece of length l: this x the plane's ERCS x sqrt(l / 1 m) (power grows with l);
  // 0: no diffuse pieces (the paper's model).
  double diffuse_relative_ercs_per_sqrt_m = 0.0;
  // At most this many pieces per face and cycle (a face spanning more cells is cut into this many
  // longer pieces); an imaging radar of fine cells needs many (a car spans 60 cells of 7.5 cm).
  int max_pieces_per_face = 16;
  // Which faces return diffuse pieces: the object model's plane reflectors (the default), or the
  // four sides of the object's box (an imaging radar sees the whole body, wheels and bumpers
  // included, diffusely; docs/imaging-radar.md). The specular points stay the model's.
  enum class Surface { model_faces, box };
  Surface surface = Surface::model_faces;
  // With "box": the left and right sides this far inside the box (0 to 1 m).
  double box_side_inset_m = 0.0;
};

// What another object's box does to a line of sight it blocks (effects.occlusion). The paper's
// 2-D view hides the reflector; a 77 GHz radar still sees a car behind a car, weakened, by the
// path under and around the nearer one (docs/extended-objects.md).
struct OcclusionConfig {
  double loss_db = std::numeric_limits<double>::infinity();  // infinite: the reflector is hidden
};

struct SensorConfig {
  std::string name;
  std::string description;
  ListLevel reports = ListLevel::tracks;
  double carrier_frequency_hz = 24.0e9;
  double cycle_time_s = 0.04;
  FieldOfView fov;
  AmplitudeLaw amplitude;
  DetectionModel detection;
  ExtendedObjects extended_objects;
  OcclusionConfig occlusion;
  AntennaGeometry antenna;
  ResolutionCell resolution;
  ArrayAngleNoise array;  // only for an array that resolves azimuth
  double pointer_noise_sigma = 0.1;  // std. dev. of the complex pointer noise, eq. (8) (`monopulse` or `array`)
  MeasurementNoise noise;
  TrackerConfig tracker;
  ClutterConfig clutter;
  MultibounceConfig multibounce;
  StationaryBackground background;  // optional section; empty: none
};

// The pointer noise's amplitude on the sensor's amplitude scale: pointer_noise_sigma at the
// scale's noise floor (eq. (8); AmplitudeLaw::noise_floor_db).
inline double pointer_noise_amplitude(const SensorConfig& config) {
  return config.pointer_noise_sigma * db_to_amplitude(config.amplitude.noise_floor_db);
}

SensorConfig parse_sensor_config(const JsonField& root);
SensorConfig load_sensor_config_file(const std::string& path);
// A built-in configuration by name (`srr24`); throws std::out_of_range for an unknown name.
SensorConfig builtin_sensor_config(const std::string& name);
bool is_builtin_sensor_config(const std::string& name);
std::vector<std::string> builtin_sensor_names();
// A built-in profile's file as it is compiled in (the text `rcsim models --sensors --export` writes).
std::string_view builtin_sensor_text(const std::string& name);
// "unknown sensor type "aimotive-lrr"; did you mean "aimotive_lrr"? (built-in: aimotive_lrr,
// astyx_hires, srr24; or a path to an rcsim-sensor file)".
std::string unknown_sensor_message(const std::string& name);

}  // namespace rcsim
