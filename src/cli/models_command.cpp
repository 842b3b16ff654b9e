// rcsim models: the object model library.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "common/angles.hpp"
#include "model/model_library.hpp"

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
  return {{"name", m.name},           {"description", m.description},   {"length_m", m.length_m},
          {"width_m", m.width_m},     {"max_ercs", m.max_ercs()},       {"point_reflectors", points},
          {"plane_reflectors", planes}};
}

}  // namespace

void add_models_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("models", "List the built-in object models");
  cmd->add_flag("--json", *json, "Machine-readable output with every reflector");
  cmd->callback([json] {
    const auto library = ModelLibrary::builtin();
    if (*json) {
      nlohmann::json all = nlohmann::json::array();
      for (const auto& [name, model] : library.models()) all.push_back(model_to_json(model));
      std::cout << all.dump(2) << '\n';
      return;
    }
    for (const auto& [name, m] : library.models()) {
      std::cout << fmt::format("{:<14} {:5.2f} m x {:4.2f} m  {:2} point + {} plane reflectors  max ERCS {:.1f}\n  {}\n",
                               name, m.length_m, m.width_m, m.points.size(), m.planes.size(), m.max_ercs(),
                               m.description);
    }
  });
}

}  // namespace rcsim::cli
