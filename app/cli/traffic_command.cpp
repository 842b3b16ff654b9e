// rcsim traffic ... -o SCENE.json: floating traffic from a microscopic traffic model (IDM car
// following, MOBIL lane changes), every vehicle including the ego driven by the model.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/seed_option.hpp"
#include "common/input_error.hpp"
#include "common/rng.hpp"
#include "traffic/scene_writer.hpp"
#include "traffic/traffic_sim.hpp"

namespace rcsim::cli {
namespace {

struct TrafficArgs {
  std::string output;
  std::string layout = "highway";
  std::optional<int> lanes;
  double length_m = 0.0;
  double lane_width_m = 3.5;
  double curve_radius_m = 0.0;
  double duration_s = 60.0;
  std::optional<double> warmup_s;
  std::optional<double> density_vpkm;
  std::optional<double> inflow_vph;
  double truck_share = 0.15;
  std::uint64_t seed = kDefaultSeed;
  double sample_interval_s = 0.3;
  double cycle_time_s = 0.0;
  std::vector<std::string> sensors;
};

traffic::SensorMount parse_sensor(const std::string& text, std::size_t index) {
  const std::string where = fmt::format("--sensor {}", index + 1);
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  if (parts.size() != 5) throw InputError("rcsim traffic", where, fmt::format("\"{}\": expected ID,TYPE,X_M,Y_M,YAW_RAD", text));
  traffic::SensorMount s{parts[0], parts[1], 0.0, 0.0, 0.0};
  double* values[3] = {&s.x_m, &s.y_m, &s.yaw_rad};
  for (int k = 0; k < 3; ++k) {
    try {
      std::size_t used = 0;
      *values[k] = std::stod(parts[2 + k], &used);
      if (used != parts[2 + k].size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw InputError("rcsim traffic", where, fmt::format("\"{}\" is not a number", parts[2 + k]));
    }
  }
  return s;
}

void run_traffic(const TrafficArgs& a) {
  traffic::TrafficConfig c;
  if (a.layout == "highway") {
    c.layout = traffic::Layout::Highway;
  } else if (a.layout == "ring") {
    c.layout = traffic::Layout::Ring;
  } else if (a.layout == "intersection") {
    c.layout = traffic::Layout::Intersection;
  } else {
    throw InputError("rcsim traffic", "--layout", fmt::format("unknown layout \"{}\" (highway, ring, intersection)", a.layout));
  }
  const bool urban = c.layout == traffic::Layout::Intersection;
  c.lanes = a.lanes.value_or(urban ? 1 : 3);
  c.length_m = a.length_m;
  c.lane_width_m = a.lane_width_m;
  c.curve_radius_m = a.curve_radius_m;
  c.duration_s = a.duration_s;
  c.warmup_s = a.warmup_s.value_or(urban ? 10.0 : 30.0);
  c.density_vpkm = a.density_vpkm.value_or(urban ? 8.0 : 20.0);
  c.inflow_vph = a.inflow_vph;
  c.truck_share = a.truck_share;
  c.seed = a.seed;
  c.sample_interval_s = a.sample_interval_s;
  c.cycle_time_s = a.cycle_time_s;
  for (std::size_t i = 0; i < a.sensors.size(); ++i) c.sensors.push_back(parse_sensor(a.sensors[i], i));
  const std::string output_dir = std::filesystem::absolute(a.output).parent_path().string();
  c = traffic::resolve_traffic_config(c, output_dir);

  Rng rng(c.seed);
  traffic::TrafficSimulation sim(c, rng);
  sim.run(rng);
  traffic::write_scene(a.output, sim);
  std::size_t written = 0;
  for (const auto& t : sim.tracks()) written += t.samples.empty() ? 0 : 1;
  std::cout << fmt::format("rcsim traffic: {} {:.0f} m, {} vehicles in {} s (ego included), {} lane changes -> {}\n",
                           traffic::layout_name(c.layout), c.length_m, written, c.duration_s,
                           sim.lane_changes().size(), a.output);
}

}  // namespace

void add_traffic_command(CLI::App& app) {
  auto a = std::make_shared<TrafficArgs>();
  auto* cmd = app.add_subcommand("traffic", "floating traffic from a microscopic traffic model (IDM + MOBIL) as a scene");
  cmd->add_option("-o,--output", a->output, "Scene file to write (rcsim-scene, written atomically)")->required();
  cmd->add_option("--layout", a->layout, "highway | ring | intersection")->capture_default_str();
  cmd->add_option("--lanes", a->lanes, "Lanes in the direction of travel (highway, ring: 3; intersection: 1)");
  cmd->add_option("--length-m", a->length_m, "Road length (intersection: each arm to the centre); 0 = automatic")
      ->capture_default_str();
  cmd->add_option("--lane-width-m", a->lane_width_m, "Lane width")->capture_default_str();
  cmd->add_option("--curve-radius-m", a->curve_radius_m, "Highway: smallest bend radius of a winding road; 0 = straight")
      ->capture_default_str();
  cmd->add_option("--duration-s", a->duration_s, "Scene duration")->capture_default_str();
  cmd->add_option("--warmup-s", a->warmup_s, "Simulated before scene time 0 (highway, ring: 30; intersection: 10)");
  cmd->add_option("--density-vpkm", a->density_vpkm, "Initial vehicles per km and lane (highway, ring: 20; intersection: 8)");
  cmd->add_option("--inflow-vph", a->inflow_vph, "Vehicles per hour entering each road; default: equilibrium flow at the density");
  cmd->add_option("--truck-share", a->truck_share, "Fraction of trucks with trailer")->capture_default_str();
  add_seed_option(*cmd, a->seed, "Seed of every random draw");
  cmd->add_option("--sample-interval-s", a->sample_interval_s, "Trajectory sample spacing (multiple of 0.1 s)")
      ->capture_default_str();
  cmd->add_option("--cycle-time-s", a->cycle_time_s, "Scene cycle time; 0 = the first sensor's")->capture_default_str();
  cmd->add_option("--sensor", a->sensors,
                  "Ego sensor ID,TYPE,X_M,Y_M,YAW_RAD (repeatable; default: srr24 front_left 3.7,0.7,0.5 and "
                  "front_right 3.7,-0.7,-0.5)");
  cmd->callback([a] { run_traffic(*a); });
}

}  // namespace rcsim::cli
