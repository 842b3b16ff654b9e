#include "traffic/scene_writer.hpp"

#include <fmt/format.h>

#include <iterator>
#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"

namespace rcsim::traffic {
namespace {

// Fixed decimals: 1 mm, 1e-5 rad, 1 mm/s; the same text on every platform.
void append_samples(std::string& out, const std::vector<TrajectorySample>& samples) {
  out += "[";
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const TrajectorySample& s = samples[k];
    fmt::format_to(std::back_inserter(out),
                   "{}\n      {{\"t_s\": {:.2f}, \"x_m\": {:.3f}, \"y_m\": {:.3f}, \"yaw_rad\": {:.5f}, "
                   "\"speed_mps\": {:.3f}, \"yaw_rate_radps\": {:.5f}}}",
                   k ? "," : "", s.t_s, s.x_m, s.y_m, s.yaw_rad, s.speed_mps, s.yaw_rate_radps.value_or(0.0));
  }
  out += "]";
}

}  // namespace

std::string scene_json(const TrafficSimulation& sim) {
  const TrafficConfig& c = sim.config();
  std::string out;
  out += "{\n  \"format\": \"rcsim-scene\", \"version\": 1,\n";
  out += fmt::format("  \"name\": \"traffic {} seed {}\",\n", layout_name(c.layout), c.seed);
  out += fmt::format(
      "  \"description\": \"rcsim traffic: IDM car following and MOBIL lane changes; {} lane(s), {:.0f} m, "
      "density {} /km/lane, inflow {:.0f} /h, truck share {}, warm-up {} s\",\n",
      c.lanes, c.length_m, c.density_vpkm, c.inflow_vph.value_or(0.0), c.truck_share, c.warmup_s);
  out += fmt::format("  \"duration_s\": {},\n", c.duration_s);
  if (c.cycle_time_s > 0.0) out += fmt::format("  \"cycle_time_s\": {},\n", c.cycle_time_s);
  const VehicleTrack* ego = nullptr;
  for (const VehicleTrack& t : sim.tracks()) {
    if (t.is_ego) ego = &t;
  }
  out += "  \"ego\": {\n    \"trajectory\": ";
  append_samples(out, ego->samples);
  out += ",\n    \"sensors\": [";
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    const SensorMount& s = c.sensors[i];
    fmt::format_to(std::back_inserter(out), "{}\n      {{\"id\": {}, \"type\": {}, \"x_m\": {}, \"y_m\": {}, \"yaw_rad\": {}}}",
                   i ? "," : "", nlohmann::json(s.id).dump(), nlohmann::json(s.type).dump(), s.x_m, s.y_m, s.yaw_rad);
  }
  out += "]\n  },\n  \"objects\": [";
  bool first = true;
  for (const VehicleTrack& t : sim.tracks()) {
    if (t.is_ego || t.samples.empty()) continue;
    fmt::format_to(std::back_inserter(out), "{}\n    {{\"id\": \"{}\", \"model\": \"{}\",", first ? "" : ",", t.id, t.model);
    if (t.present_from_s) fmt::format_to(std::back_inserter(out), " \"present_from_s\": {:.2f},", *t.present_from_s);
    if (t.present_until_s) fmt::format_to(std::back_inserter(out), " \"present_until_s\": {:.2f},", *t.present_until_s);
    out += " \"trajectory\": ";
    append_samples(out, t.samples);
    out += "}";
    first = false;
  }
  out += "\n  ]\n}\n";
  return out;
}

void write_scene(const std::string& path, const TrafficSimulation& sim) {
  AtomicFileWriter file(path);
  file.stream() << scene_json(sim);
  file.commit();
}

}  // namespace rcsim::traffic
