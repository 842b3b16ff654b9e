#include "sim/target_list_mcap.hpp"

#include <cmath>
#include <map>

#include "common/target_colours.hpp"
#include "io/foxglove_json.hpp"

namespace rcsim {

namespace {

using foxglove::Json;

constexpr double kTargetSizeM = 0.5;  // a target's sphere
const std::map<std::string, std::string> kSimulatedFormat = {{"format", "rcsim-mcap-replay"}, {"version", "1"}, {"source", "simulate"}};

}  // namespace

McapTargetListWriter::McapTargetListWriter(std::ostream& out, const Scene& scene, ListLevel level) : level_(level), writer_(out, "", mcap::Compression::zstd) {
  const auto scene_schema = writer_.add_schema("foxglove.SceneUpdate", "jsonschema", foxglove::scene_update_schema());
  const auto transform_schema = writer_.add_schema("foxglove.FrameTransform", "jsonschema", foxglove::frame_transform_schema());
  tf_channel_ = writer_.add_channel("/tf", "json", transform_schema, kSimulatedFormat);
  boxes_channel_ = writer_.add_channel("/rcsim/boxes", "json", scene_schema, kSimulatedFormat);
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    frames_.push_back(foxglove::frame_name(scene.sensors[i].id, static_cast<int>(i), frames_));
    target_channels_.push_back(writer_.add_channel("/rcsim/" + frames_.back() + "/simulated", "json", scene_schema, kSimulatedFormat));
    view_field_channels_.push_back(writer_.add_channel("/rcsim/" + frames_.back() + "/view_field", "json", scene_schema, kSimulatedFormat));
  }
  lifetime_ns_ = foxglove::time_ns(scene.cycle_time_s);
}

void McapTargetListWriter::message(std::uint16_t channel, std::uint64_t ns, const std::string& body) {
  writer_.write_message(channel, ns, body);
  ++messages_;
}

void McapTargetListWriter::write_cycle(const Scene& scene, int cycle, double t_s, const std::vector<const SensorCycleState*>& states) {
  (void)cycle;
  const std::uint64_t ns = foxglove::time_ns(t_s);
  if (!static_written_) {
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
      const MountedSensor& s = scene.sensors[i];
      message(tf_channel_, ns, foxglove::frame_transform(ns, "ego", frames_[i], s.X_VS).dump());
      message(view_field_channels_[i], ns,
              foxglove::scene_update(Json::array({foxglove::view_field_entity(frames_[i], s.config.fov.azimuth_half_rad, s.config.fov.max_range_m, ns)})).dump());
    }
    static_written_ = true;
  }
  static const std::string world = foxglove::text::quoted("world"), ego = foxglove::text::quoted("ego");
  static const std::string simulated = foxglove::text::quoted("simulated"), boxes_id = foxglove::text::quoted("boxes");
  static const std::string simulated_colour = foxglove::text::colour(colours::kSimulated);
  message(tf_channel_, ns, foxglove::text::frame_transform(ns, world, ego, scene.ego.state_at(t_s).X_WB));
  foxglove::text::Entity boxes(ns, world, boxes_id, lifetime_ns_);
  for (const SceneObject& o : scene.objects) {
    if (o.present_at(t_s)) boxes.box(o.trajectory.state_at(t_s).X_WB, o.model.length_m, o.model.width_m, foxglove::text::quoted(o.id));
  }
  message(boxes_channel_, ns, boxes.scene_update());
  for (std::size_t i = 0; i < states.size() && i < frames_.size(); ++i) {
    foxglove::text::Entity targets(ns, foxglove::text::quoted(frames_[i]), simulated, lifetime_ns_);
    for_each_target_list_row(scene, *states[i], level_, [&](const TargetListRow& row) {
      // A radar that measures elevation: the point in 3D (its frame is the sensor's, level).
      const double horizontal_m = row.elevation_rad == 0.0 ? row.range_m : row.range_m * std::cos(row.elevation_rad);
      const Vec2 p = point_from_polar(horizontal_m, row.azimuth_rad);
      targets.sphere(p.x(), p.y(), row.range_m * std::sin(row.elevation_rad), 0.0, kTargetSizeM, kTargetSizeM, kTargetSizeM, simulated_colour);
    });
    message(target_channels_[i], ns, targets.scene_update());
  }
}

std::uint64_t McapTargetListWriter::finish() { return writer_.finish(); }

}  // namespace rcsim
