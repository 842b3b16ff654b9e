#include "sensor/sensor_config.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/angles.hpp"
#include "common/closest_name.hpp"
#include "common/embedded_data.hpp"
#include "common/limits.hpp"

namespace rcsim {
namespace {

// No configuration value is near this (the largest, a carrier frequency, is about 1e11 Hz): 1e308
// is a broken file, not a sensor (schemas/limits.md).
constexpr double kMaxConfigValue = 1e12;
// Diffuse pieces per face: 256 cells of 7.5 cm are a 19-m face seen end-on.
constexpr int kMaxPiecesPerFace = 256;

double positive(const JsonField& f, std::string_view key, double max = kMaxConfigValue) {
  const double x = f.number_within(key, 0.0, max, "");
  require_positive(f, key, x);
  return x;
}

double non_negative(const JsonField& f, std::string_view key, double max = kMaxConfigValue) {
  return f.number_within(key, 0.0, max, "");
}

int positive_int(const JsonField& f, std::string_view key, int max = limits::kMaxCount) {
  const double x = f.number(key);
  // Checked as a double before the conversion, which would be undefined beyond INT_MAX.
  if (!(x >= 1.0 && x <= max) || x != std::floor(x)) {
    f.fail(key, fmt::format("must be a whole number from 1 to {} (schemas/limits.md), got {}", max, x));
  }
  return static_cast<int>(x);
}

// [a, b]: an array of two finite numbers.
std::pair<double, double> number_pair(const JsonField& f, std::string_view key) {
  const auto items = f.array(key);
  const auto finite = [](const JsonField& item) { return item.json().is_number() && std::isfinite(item.json().get<double>()); };
  if (items.size() != 2 || !finite(items[0]) || !finite(items[1])) f.fail(key, "must be an array of two numbers [min, max]");
  return {items[0].json().get<double>(), items[1].json().get<double>()};
}

// Amplitudes and levels in dB beyond this are no sensor's (schemas/sensor-config.md).
constexpr double kMaxLevelMagnitudeDb = limits::kMaxLevel_dB;

double level_db(const JsonField& f, std::string_view key) {
  const double x = f.number(key);
  if (std::abs(x) > kMaxLevelMagnitudeDb) f.fail(key, fmt::format("must be within +-{} dB, got {}", kMaxLevelMagnitudeDb, x));
  return x;
}

AmplitudeLaw parse_amplitude_law(const JsonField& amp) {
  AmplitudeLaw law;
  const std::string kind = amp.has("law") ? amp.string("law") : "paper_eq1";
  if (kind == "paper_eq1") {
    amp.expect_only({"law", "unit", "reference_level_db", "reference_slope_db_per_m", "detection_threshold_db", "noise_floor_db"});
    law.kind = AmplitudeLawKind::paper_eq1;
    law.reference_level_db = level_db(amp, "reference_level_db");
    law.reference_slope_db_per_m = non_negative(amp, "reference_slope_db_per_m");
  } else if (kind == "radar_equation") {
    amp.expect_only({"law", "unit", "snr_at_1m_for_1m2_db", "reference_rcs_dbsm", "range_exponent", "detection_threshold_db",
                     "noise_floor_db"});
    law.kind = AmplitudeLawKind::radar_equation;
    law.snr_at_1m_for_1m2_db = level_db(amp, "snr_at_1m_for_1m2_db");
    law.reference_rcs_dbsm = level_db(amp, "reference_rcs_dbsm");
    if (const auto n = amp.optional_number("range_exponent")) {
      if (!(*n >= 0.0 && *n <= 6.0)) {
        amp.fail("range_exponent",
                 fmt::format("must be in [0, 6] (4: the radar equation's 1/R^4; 0: a range-compensated amplitude), got {}", *n));
      }
      law.range_exponent = *n;
    }
  } else {
    amp.fail("law", fmt::format("unknown amplitude law \"{}\" (known: paper_eq1, radar_equation)", kind));
  }
  law.detection_threshold_db = level_db(amp, "detection_threshold_db");
  if (amp.has("unit")) {
    const std::string unit = amp.string("unit");
    if (unit == "relative_db") {
      law.unit = AmplitudeUnit::relative_db;
    } else if (unit != "snr_db") {
      amp.fail("unit", fmt::format("must be \"snr_db\" or \"relative_db\", got \"{}\"", unit));
    }
  }
  if (amp.has("noise_floor_db")) {
    if (law.unit != AmplitudeUnit::relative_db) {
      amp.fail("noise_floor_db", "an SNR scale's noise lies at 0 dB by definition: only a relative_db scale names its own");
    }
    law.noise_floor_db = level_db(amp, "noise_floor_db");
  }
  if (law.unit == AmplitudeUnit::relative_db && law.detection_threshold_db <= law.noise_floor_db) {
    amp.fail("detection_threshold_db",
             fmt::format("{} dB lies at or below the noise floor ({} dB, noise_floor_db): every cell would be detected on "
                         "the pointer noise. Give amplitude.noise_floor_db, where this radar's noise lies on its scale "
                         "(docs/amplitude.md)",
                         law.detection_threshold_db, law.noise_floor_db));
  }
  return law;
}

DetectionModel parse_detection_model(const JsonField& detection) {
  detection.expect_only({"fluctuation", "local_maxima_only", "reported_beams"});
  DetectionModel model;
  const std::string name = detection.string("fluctuation");
  if (name == "none" || name == "swerling0") {
    model.fluctuation = Fluctuation::none;
  } else if (name == "swerling1") {
    model.fluctuation = Fluctuation::swerling1;
  } else if (name == "swerling3") {
    model.fluctuation = Fluctuation::swerling3;
  } else {
    detection.fail("fluctuation", fmt::format("unknown fluctuation \"{}\" (known: none, swerling0, swerling1, swerling3)", name));
  }
  model.local_maxima_only = detection.boolean_or("local_maxima_only", false);
  if (detection.has("reported_beams")) {
    const std::string beams = detection.string("reported_beams");
    if (beams == "strongest_per_range_doppler_cell") {
      model.strongest_beam_per_cell = true;
    } else if (beams != "every") {
      detection.fail("reported_beams",
                     fmt::format("must be \"every\" or \"strongest_per_range_doppler_cell\", got \"{}\"", beams));
    }
  }
  return model;
}

TrackerConfig parse_tracker(const JsonField& trk) {
  TrackerConfig t;
  trk.expect_only({"confirmation_hits", "max_misses_tentative", "max_misses_confirmed", "gate_chi2", "max_tracks",
                   "process_accel_sigma_mps2", "process_azimuth_rate_sigma_radps", "process_amplitude_sigma_db",
                   "measurement_sigma_range_m", "measurement_sigma_range_rate_mps", "measurement_sigma_azimuth_rad",
                   "measurement_sigma_amplitude_db"});
  t.confirmation_hits = positive_int(trk, "confirmation_hits");
  t.max_misses_tentative = positive_int(trk, "max_misses_tentative");
  t.max_misses_confirmed = positive_int(trk, "max_misses_confirmed");
  t.gate_chi2 = positive(trk, "gate_chi2");
  t.max_tracks = positive_int(trk, "max_tracks", limits::kMaxTracks);
  t.process_accel_sigma_mps2 = positive(trk, "process_accel_sigma_mps2");
  t.process_azimuth_rate_sigma_radps = positive(trk, "process_azimuth_rate_sigma_radps");
  t.process_amplitude_sigma_db = positive(trk, "process_amplitude_sigma_db");
  t.measurement_sigma_range_m = positive(trk, "measurement_sigma_range_m");
  t.measurement_sigma_range_rate_mps = positive(trk, "measurement_sigma_range_rate_mps");
  t.measurement_sigma_azimuth_rad = positive(trk, "measurement_sigma_azimuth_rad");
  t.measurement_sigma_amplitude_db = positive(trk, "measurement_sigma_amplitude_db");
  return t;
}

ClutterConfig parse_clutter(const JsonField& clutter) {
  clutter.expect_only({"false_detections_per_cycle", "amplitude_excess_mean_db"});
  ClutterConfig c;
  c.false_detections_per_cycle = non_negative(clutter, "false_detections_per_cycle", 10'000.0);
  if (c.false_detections_per_cycle > 100.0) clutter.fail("false_detections_per_cycle", "must be at most 100");
  c.amplitude_excess_mean_db = positive(clutter, "amplitude_excess_mean_db");
  return c;
}

MultibounceConfig parse_multibounce(const JsonField& mb) {
  mb.expect_only({"max_range_m", "max_order", "loss_per_bounce_db"});
  MultibounceConfig c;
  c.max_range_m = non_negative(mb, "max_range_m");
  c.max_order = positive_int(mb, "max_order", 10);
  if (c.max_order > 8) mb.fail("max_order", "must be at most 8");
  c.loss_per_bounce_db = non_negative(mb, "loss_per_bounce_db");
  return c;
}

FieldOfView parse_field_of_view(const JsonField& fov) {
  FieldOfView out;
  fov.expect_only({"azimuth_half_deg", "elevation_half_deg", "min_range_m", "max_range_m"});
  const double half_deg = positive(fov, "azimuth_half_deg");
  if (half_deg >= 90.0) fov.fail("azimuth_half_deg", "must be below 90 (the antenna model covers the front half)");
  out.azimuth_half_rad = deg_to_rad(half_deg);
  out.min_range_m = non_negative(fov, "min_range_m");
  out.max_range_m = positive(fov, "max_range_m", limits::kMaxRange_m);
  if (out.max_range_m <= out.min_range_m) fov.fail("max_range_m", "must exceed min_range_m");
  if (fov.has("elevation_half_deg")) {
    const double elevation_deg = positive(fov, "elevation_half_deg");
    if (elevation_deg >= 90.0) fov.fail("elevation_half_deg", "must be below 90");
    out.elevation_half_rad = deg_to_rad(elevation_deg);
  }
  return out;
}

ExtendedObjects parse_extended_objects(const JsonField& extended) {
  ExtendedObjects out;
  extended.expect_only({"diffuse_relative_ercs_per_sqrt_m", "max_pieces_per_face", "diffuse_surface", "box_side_inset_m"});
  if (extended.has("diffuse_surface")) {
    const std::string surface = extended.string("diffuse_surface");
    if (surface == "box") {
      out.surface = ExtendedObjects::Surface::box;
    } else if (surface != "model_faces") {
      extended.fail("diffuse_surface", fmt::format("must be \"model_faces\" or \"box\", got \"{}\"", surface));
    }
  }
  if (extended.has("box_side_inset_m")) {
    if (out.surface != ExtendedObjects::Surface::box) {
      extended.fail("box_side_inset_m", "needs \"diffuse_surface\": \"box\"");
    }
    out.box_side_inset_m = non_negative(extended, "box_side_inset_m");
    if (out.box_side_inset_m > 1.0) extended.fail("box_side_inset_m", "must be at most 1");
  }
  if (extended.has("max_pieces_per_face")) {
    out.max_pieces_per_face = positive_int(extended, "max_pieces_per_face", kMaxPiecesPerFace);
  }
  out.diffuse_relative_ercs_per_sqrt_m = non_negative(extended, "diffuse_relative_ercs_per_sqrt_m");
  if (out.diffuse_relative_ercs_per_sqrt_m > 100.0) {
    extended.fail("diffuse_relative_ercs_per_sqrt_m", "must be at most 100");
  }
    return out;
}

// eq. (6)'s array, its spacing bounded so that eq. (7) inverts over the view field.
AntennaGeometry parse_antenna(const JsonField& antenna, const FieldOfView& fov) {
  AntennaGeometry out;
  antenna.expect_only({"dipole_length_wavelengths", "element_spacing_wavelengths", "amplitude_pattern_exponent"});
  out.dipole_length_wavelengths = positive(antenna, "dipole_length_wavelengths");
  out.element_spacing_wavelengths = positive(antenna, "element_spacing_wavelengths");
  if (const auto n = antenna.optional_number("amplitude_pattern_exponent")) {
    if (!(*n >= 1.0 && *n <= 4.0)) antenna.fail("amplitude_pattern_exponent", "must be in [1, 4] (1: the paper's |H_sum|)");
    out.amplitude_pattern_exponent = *n;
  }
  // eq. (7) inverts while u = pi (d / lambda) sin(phi) stays within pi/2 over the view field:
  // d / lambda <= 0.5 / sin(half view), 0.5 for a view field reaching +-90 deg.
  const double max_spacing = 0.5 / std::sin(fov.azimuth_half_rad);
  if (out.element_spacing_wavelengths > max_spacing) {
    antenna.fail("element_spacing_wavelengths",
                 fmt::format("must be at most 0.5 / sin(azimuth_half) = {:.4f} so that eq. (7) stays monotone over the "
                             "view field, got {}", max_spacing, out.element_spacing_wavelengths));
  }
  return out;
}

ResolutionCell parse_resolution(const JsonField& res) {
  ResolutionCell out;
  res.expect_only({"range_cell_m", "range_rate_cell_mps", "azimuth_cell_deg", "elevation_cell_deg", "unambiguous_range_rate_mps",
                   "spectral_window"});
  out.range_cell_m = positive(res, "range_cell_m");
  out.range_rate_cell_mps = positive(res, "range_rate_cell_mps");
  if (res.has("azimuth_cell_deg")) out.azimuth_cell_rad = deg_to_rad(positive(res, "azimuth_cell_deg", 30.0));
  if (res.has("elevation_cell_deg")) out.elevation_cell_rad = deg_to_rad(positive(res, "elevation_cell_deg", 30.0));
  if (res.has("unambiguous_range_rate_mps")) {
    const auto interval = number_pair(res, "unambiguous_range_rate_mps");
    if (!(interval.first < 0.0 && interval.second > 0.0 && interval.second - interval.first <= 2.0 * limits::kMaxSpeed_mps)) {
      res.fail("unambiguous_range_rate_mps",
               fmt::format("must be [min, max] with min < 0 < max and max - min at most {} m/s, got [{}, {}]",
                           2.0 * limits::kMaxSpeed_mps, interval.first, interval.second));
    }
    out.unambiguous_min_mps = interval.first;
    out.unambiguous_max_mps = interval.second;
  }
  if (res.has("spectral_window")) {
    const std::string window = res.string("spectral_window");
    if (window == "hann") {
      out.window = SpectralWindow::hann;
    } else if (window != "none") {
      res.fail("spectral_window", fmt::format("must be \"none\" or \"hann\", got \"{}\"", window));
    }
  }
  return out;
}

// The angle's noise. An array that resolves azimuth has beams, not monopulse: `array` (angle and
// pointer noise) instead of `monopulse`.
void parse_angle_noise(const JsonField& root, SensorConfig& c) {
  if (c.resolution.resolves_azimuth()) {
    const auto array = root.member("array");
    array.expect_only({"azimuth_sigma_deg", "pointer_noise_sigma"});
    c.array.azimuth_sigma_rad = deg_to_rad(non_negative(array, "azimuth_sigma_deg", 30.0));
    c.pointer_noise_sigma = non_negative(array, "pointer_noise_sigma");
  } else if (root.has("array")) {
    root.fail("array", "only for an array that resolves azimuth (resolution.azimuth_cell_deg)");
  }
  if (c.resolution.resolves_azimuth()) {
    if (root.has("monopulse")) root.fail("monopulse", "an array that resolves azimuth has beams: its noise is in `array`");
  } else {
    const auto mono = root.member("monopulse");
    mono.expect_only({"pointer_noise_sigma"});
    c.pointer_noise_sigma = non_negative(mono, "pointer_noise_sigma");
  }
}

MeasurementNoise parse_measurement_noise(const JsonField& noise) {
  MeasurementNoise out;
  noise.expect_only({"range_sigma_at_threshold_m", "range_sigma_min_m", "range_rate_sigma_at_threshold_mps",
                     "range_rate_sigma_min_mps", "elevation_sigma_deg"});
  out.range_sigma_at_threshold_m = non_negative(noise, "range_sigma_at_threshold_m");
  out.range_sigma_min_m = non_negative(noise, "range_sigma_min_m");
  out.range_rate_sigma_at_threshold_mps = non_negative(noise, "range_rate_sigma_at_threshold_mps");
  out.range_rate_sigma_min_mps = non_negative(noise, "range_rate_sigma_min_mps");
  if (noise.has("elevation_sigma_deg")) out.elevation_sigma_rad = deg_to_rad(non_negative(noise, "elevation_sigma_deg", 30.0));
  return out;
}

}  // namespace

SensorConfig parse_sensor_config(const JsonField& root) {
  root.expect_only({"format", "version", "name", "description", "reports", "carrier_frequency_hz", "cycle_time_s",
                    "field_of_view", "amplitude", "detection", "extended_objects", "occlusion", "antenna", "resolution", "array", "monopulse", "measurement_noise",
                    "tracking", "clutter", "multibounce", "background"});
  root.expect_format("rcsim-sensor", 1);
  SensorConfig c;
  c.name = root.string("name");
  c.description = root.has("description") ? root.string("description") : "";
  if (root.has("reports")) {
    const std::string reports = root.string("reports");
    if (reports == "detections") {
      c.reports = ListLevel::detections;
    } else if (reports != "tracks") {
      root.fail("reports", fmt::format("must be \"tracks\" or \"detections\", got \"{}\"", reports));
    }
  }
  c.carrier_frequency_hz = positive(root, "carrier_frequency_hz");
  c.cycle_time_s = positive(root, "cycle_time_s", limits::kMaxCycleTime_s);

  c.fov = parse_field_of_view(root.member("field_of_view"));
  c.amplitude = parse_amplitude_law(root.member("amplitude"));
  if (const auto detection = root.optional_member("detection")) c.detection = parse_detection_model(*detection);
  if (const auto occlusion = root.optional_member("occlusion")) {
    occlusion->expect_only({"loss_db"});
    c.occlusion.loss_db = non_negative(*occlusion, "loss_db");
    if (c.occlusion.loss_db > kMaxLevelMagnitudeDb) occlusion->fail("loss_db", fmt::format("must be at most {}", kMaxLevelMagnitudeDb));
  }
  if (const auto extended = root.optional_member("extended_objects")) c.extended_objects = parse_extended_objects(*extended);
  c.antenna = parse_antenna(root.member("antenna"), c.fov);
  c.resolution = parse_resolution(root.member("resolution"));
  if (c.detection.strongest_beam_per_cell && !c.resolution.resolves_azimuth()) {
    root.fail("detection.reported_beams", "needs an array that resolves azimuth (resolution.azimuth_cell_deg)");
  }
  parse_angle_noise(root, c);
  c.noise = parse_measurement_noise(root.member("measurement_noise"));
  // Elevation cells and noise belong to a radar that measures elevation (field_of_view.elevation_half_deg).
  if (!c.fov.measures_elevation()) {
    if (c.resolution.resolves_elevation()) {
      root.fail("resolution.elevation_cell_deg", "needs a radar that measures elevation (field_of_view.elevation_half_deg)");
    }
    if (c.noise.elevation_sigma_rad > 0.0) {
      root.fail("measurement_noise.elevation_sigma_deg", "needs a radar that measures elevation (field_of_view.elevation_half_deg)");
    }
  }
  // A sensor that reports detections has no tracker: its `tracking` section may be left out.
  if (c.reports == ListLevel::tracks || root.has("tracking")) c.tracker = parse_tracker(root.member("tracking"));

  c.clutter = parse_clutter(root.member("clutter"));
  c.multibounce = parse_multibounce(root.member("multibounce"));
  if (const auto background = root.optional_member("background")) c.background = parse_stationary_background(*background);
  return c;
}

SensorConfig load_sensor_config_file(const std::string& path) {
  const auto json = parse_json_file(path);
  return parse_sensor_config(JsonField(json, path, ""));
}

bool is_builtin_sensor_config(const std::string& name) {
  for (const auto& file : embedded_sensor_configs()) {
    if (file.name == name) return true;
  }
  return false;
}

std::vector<std::string> builtin_sensor_names() {
  std::vector<std::string> names;
  for (const auto& file : embedded_sensor_configs()) names.emplace_back(file.name);
  return names;
}

std::string_view builtin_sensor_text(const std::string& name) {
  for (const auto& file : embedded_sensor_configs()) {
    if (file.name == name) return file.text;
  }
  throw std::out_of_range(unknown_sensor_message(name));
}

std::string unknown_sensor_message(const std::string& name) {
  const std::vector<std::string> known = builtin_sensor_names();
  const auto meant = closest_name(name, known);
  return fmt::format("unknown sensor type \"{}\"{} (built-in: {}; or a path to an rcsim-sensor file)", name,
                     meant ? fmt::format("; did you mean \"{}\"?", *meant) : "", join_names(known));
}

SensorConfig builtin_sensor_config(const std::string& name) {
  const std::string label = "builtin:" + name + ".json";
  const auto json = parse_json_text(builtin_sensor_text(name), label);
  return parse_sensor_config(JsonField(json, label, ""));
}

}  // namespace rcsim
