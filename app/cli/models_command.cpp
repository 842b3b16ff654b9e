// rcsim models: the object model library; --sensors: the built-in sensor profiles.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "common/angles.hpp"
#include "common/atomic_file.hpp"
#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "model/model_library.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::cli {
namespace {

nlohmann::json model_to_json(const ObjectModel& m) {
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : m.points) {
    points.push_back({{"name", p.name},
                      {"x_m", p.p_OR_O.x()},
                      {"y_m", p.p_OR_O.y()},
                      {"ercs", p.ercs_max},
                      {"visibility",
                       {{"center_deg", rad_to_deg(p.visibility.center_rad())},
                        {"full_halfwidth_deg", rad_to_deg(p.visibility.full_halfwidth_rad())},
                        {"falloff_deg", rad_to_deg(p.visibility.falloff_rad())}}}});
  }
  nlohmann::json planes = nlohmann::json::array();
  for (const auto& p : m.planes) {
    planes.push_back({{"name", p.name},
                      {"center_x_m", p.center_O.x()},
                      {"center_y_m", p.center_O.y()},
                      {"radius_m", p.radius_m},
                      {"start_deg", rad_to_deg(p.start_rad)},
                      {"span_deg", rad_to_deg(p.span_rad)},
                      {"ercs", p.ercs}});
  }
  nlohmann::json out = {{"name", m.name},           {"description", m.description},   {"length_m", m.length_m},
                        {"width_m", m.width_m},     {"max_ercs", m.max_ercs()},       {"point_reflectors", points},
                        {"plane_reflectors", planes}};
  if (m.polyline) {
    const PolylineTemplate& t = *m.polyline;
    out["polyline"] = {{"spacing_m", t.spacing_m},
                       {"post_ercs", t.post_ercs},
                       {"post_visibility",
                        {{"center_deg", rad_to_deg(t.post_visibility.center_rad())},
                         {"full_halfwidth_deg", rad_to_deg(t.post_visibility.full_halfwidth_rad())},
                         {"falloff_deg", rad_to_deg(t.post_visibility.falloff_rad())}}},
                       {"face_ercs_per_m", t.face_ercs_per_m}};
  }
  return out;
}

const char* law_name(AmplitudeLawKind kind) {
  return kind == AmplitudeLawKind::radar_equation ? "radar_equation" : "paper_eq1";
}

const char* fluctuation_name(Fluctuation f) {
  switch (f) {
    case Fluctuation::none: return "none";
    case Fluctuation::swerling1: return "swerling1";
    case Fluctuation::swerling3: return "swerling3";
  }
  return "none";
}

nlohmann::json sensor_to_json(const SensorConfig& c) {
  nlohmann::json amplitude = {{"law", law_name(c.amplitude.kind)},
                              {"detection_threshold_db", c.amplitude.detection_threshold_db}};
  if (c.amplitude.kind == AmplitudeLawKind::radar_equation) {
    amplitude["snr_at_1m_for_1m2_db"] = c.amplitude.snr_at_1m_for_1m2_db;
    amplitude["reference_rcs_dbsm"] = c.amplitude.reference_rcs_dbsm;
    amplitude["range_exponent"] = c.amplitude.range_exponent;
  } else {
    amplitude["reference_level_db"] = c.amplitude.reference_level_db;
    amplitude["reference_slope_db_per_m"] = c.amplitude.reference_slope_db_per_m;
  }
  return {{"name", c.name},
          {"description", c.description},
          {"reports", list_level_name(c.reports)},
          {"carrier_frequency_hz", c.carrier_frequency_hz},
          {"cycle_time_s", c.cycle_time_s},
          {"azimuth_half_deg", rad_to_deg(c.fov.azimuth_half_rad)},
          {"min_range_m", c.fov.min_range_m},
          {"max_range_m", c.fov.max_range_m},
          {"amplitude", amplitude},
          {"fluctuation", fluctuation_name(c.detection.fluctuation)},
          {"local_maxima_only", c.detection.local_maxima_only},
          {"diffuse_relative_ercs_per_sqrt_m", c.extended_objects.diffuse_relative_ercs_per_sqrt_m},
          {"occlusion_loss_db", std::isinf(c.occlusion.loss_db) ? nlohmann::json() : nlohmann::json(c.occlusion.loss_db)},
          {"background_targets_per_cycle", c.background.targets_per_cycle},
          {"range_cell_m", c.resolution.range_cell_m},
          {"range_rate_cell_mps", c.resolution.range_rate_cell_mps}};
}

void print_sensors(bool json) {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& file : embedded_sensor_configs()) {
    const SensorConfig c = builtin_sensor_config(std::string(file.name));
    if (json) {
      all.push_back(sensor_to_json(c));
      continue;
    }
    std::cout << fmt::format("{:<14} {:4.0f} GHz  +-{:4.1f} deg  {:5.1f}-{:5.1f} m  {} law, threshold {:.1f} dB, "
                             "fluctuation {}  cells {:.2f} m x {:.2f} m/s  reports {}\n  {}\n",
                             c.name, c.carrier_frequency_hz / 1e9, rad_to_deg(c.fov.azimuth_half_rad), c.fov.min_range_m,
                             c.fov.max_range_m, law_name(c.amplitude.kind), c.amplitude.detection_threshold_db,
                             fluctuation_name(c.detection.fluctuation), c.resolution.range_cell_m,
                             c.resolution.range_rate_cell_mps,
                             list_level_name(c.reports), c.description);
  }
  if (json) std::cout << all.dump(2) << '\n';
}

// `--export NAME`: the built-in profile's file as it is compiled in, to edit and name as a
// sensor's `type` (a path) or in `rcsim profile derive --base`.
void export_sensor(const std::string& name, const std::string& output) {
  if (!is_builtin_sensor_config(name)) throw InputError("rcsim models", "--export", unknown_sensor_message(name));
  const std::string_view text = builtin_sensor_text(name);
  if (output.empty() || output == "-") {
    std::cout << text;
    return;
  }
  check_output_file(output);
  AtomicFileWriter file(output);
  file.stream() << text;
  file.commit();
  std::cerr << fmt::format("{}: the built-in profile {}, written; edit it and name the file as a sensor's type\n", output,
                           name);
}

}  // namespace

void add_models_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto sensors = std::make_shared<bool>(false);
  auto export_name = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("models", "list the built-in object models (--sensors: the sensor profiles)");
  cmd->add_flag("--json", *json, "Machine-readable output with every reflector (or every profile's main values)");
  cmd->add_flag("--sensors", *sensors, "List the built-in sensor profiles instead");
  cmd->add_option("--export", *export_name, "With --sensors: write this built-in profile as an editable rcsim-sensor file");
  cmd->add_option("-o,--output", *output, "With --export: the file to write (atomically); default: standard output");
  cmd->callback([json, sensors, export_name, output] {
    if (!export_name->empty() && !*sensors) throw InputError("rcsim models", "--export", "names a sensor profile; add --sensors");
    if (!output->empty() && export_name->empty()) throw InputError("rcsim models", "-o", "writes an exported profile; add --sensors --export NAME");
    if (!export_name->empty()) {
      export_sensor(*export_name, *output);
      return;
    }
    if (*sensors) {
      print_sensors(*json);
      return;
    }
    const auto library = ModelLibrary::builtin();
    if (*json) {
      nlohmann::json all = nlohmann::json::array();
      for (const auto& [name, model] : library.models()) all.push_back(model_to_json(model));
      std::cout << all.dump(2) << '\n';
      return;
    }
    for (const auto& [name, m] : library.models()) {
      if (m.polyline) {
        std::cout << fmt::format("{:<14} along a polyline: posts every {:.1f} m of ERCS {:.2f}, face ERCS {:.3f} per m\n  {}\n",
                                 name, m.polyline->spacing_m, m.polyline->post_ercs, m.polyline->face_ercs_per_m,
                                 m.description);
        continue;
      }
      std::cout << fmt::format("{:<14} {:5.2f} m x {:4.2f} m  {:2} point + {} plane reflectors  max ERCS {:.1f}\n  {}\n",
                               name, m.length_m, m.width_m, m.points.size(), m.planes.size(), m.max_ercs(),
                               m.description);
    }
  });
}

}  // namespace rcsim::cli
