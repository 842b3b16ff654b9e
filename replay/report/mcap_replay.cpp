#include "replay/report/mcap_replay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <variant>
#include <vector>

#include "common/pose2.hpp"
#include "common/target_colours.hpp"
#include "io/foxglove_json.hpp"
#include "io/mcap_writer.hpp"
#include "metrics/target_class.hpp"
#include "replay/store/decoded_rows.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

namespace mcap_replay_internal {

using foxglove::colour;
using foxglove::entity;
using foxglove::Json;
using foxglove::pose_json;
using foxglove::scene_update;
using foxglove::time_ns;
using foxglove::vec3;

constexpr double kBoxHeightM = 1.5;    // the boxes are 2-D: drawn 1.5 m tall
constexpr double kTargetSizeM = 0.5;   // a target's sphere or cube
// Every channel names the format (schemas/mcap-replay.md).
const std::map<std::string, std::string> kFormat = {{"format", "rcsim-mcap-replay"}, {"version", "1"}};

std::string cycle_figures_schema() {
  Json properties = Json::object();
  for (const DecodedColumn& c : decoded_columns(DecodedTable::cycles)) {
    properties[c.name] = {{"type", c.sql_type == "TEXT" ? "string" : (c.sql_type == "INTEGER" ? "integer" : "number")}};
  }
  return Json{{"title", "rcsim.CycleFigures"}, {"type", "object"}, {"properties", properties}}.dump();
}

const char* class_colour(const StoredTarget& t) {
  if (t.target_class == metrics::TargetClass::stationary_background) return colours::kBackground;
  if (t.target_class == metrics::TargetClass::other) return colours::kOther;
  return t.simulated ? colours::kSimulated : colours::kRecorded;
}

Json figures_json(const std::vector<DecodedValue>& row) {
  Json out = Json::object();
  const auto& columns = decoded_columns(DecodedTable::cycles);
  for (std::size_t i = 0; i < row.size(); ++i) out[columns[i].name] = decoded_value_json(row[i]);
  return out;
}

// The rows of one block of cycles, by cycle.
struct CycleBlock {
  std::map<int, std::vector<std::vector<DecodedValue>>> figures;  // cycle -> a row per sensor
  std::map<int, std::vector<StoredCycle>> cycles;
  std::map<int, std::vector<StoredTarget>> targets;
  std::map<int, std::vector<StoredObjectState>> boxes;
};

class McapReplayWriter {
 public:
  McapReplayWriter(ReportDatabase& db, std::int64_t run_id, std::ostream& out)
      : db_(db), run_id_(run_id), run_(report::load_run(db, run_id)), writer_(out) {
    scene_ = writer_.add_schema("foxglove.SceneUpdate", "jsonschema", foxglove::scene_update_schema());
    transform_ = writer_.add_schema("foxglove.FrameTransform", "jsonschema", foxglove::frame_transform_schema());
    figures_ = writer_.add_schema("rcsim.CycleFigures", "jsonschema", cycle_figures_schema());
    tf_channel_ = writer_.add_channel("/tf", "json", transform_, kFormat);
    boxes_channel_ = writer_.add_channel(mcap_replay_topic("", "boxes"), "json", scene_, kFormat);
    for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
      SensorChannels c;
      c.frame = foxglove::frame_name(run_.sensors[i].id, static_cast<int>(i), frames_);
      frames_.push_back(c.frame);
      c.recorded = writer_.add_channel(mcap_replay_topic(c.frame, "recorded"), "json", scene_, kFormat);
      c.simulated = writer_.add_channel(mcap_replay_topic(c.frame, "simulated"), "json", scene_, kFormat);
      c.view_field = writer_.add_channel(mcap_replay_topic(c.frame, "view_field"), "json", scene_, kFormat);
      c.figures = writer_.add_channel(mcap_replay_topic(c.frame, "figures"), "json", figures_, kFormat);
      sensor_channels_.push_back(c);
    }
    lifetime_ns_ = time_ns(run_.info.cycle_time_s);
  }

  McapReplayCounts write() {
    const int last = last_stored_cycle(db_, run_id_);
    for (int first = 0; first <= last; first += kBlockCycles) write_block(read_block({first, std::min(last, first + kBlockCycles - 1)}));
    counts_.bytes = writer_.finish();
    counts_.sensors = static_cast<int>(run_.sensors.size());
    return counts_;
  }

 private:
  struct SensorChannels {
    std::string frame;  // the sensor's frame id and its topics' middle part
    std::uint16_t recorded = 0, simulated = 0, view_field = 0, figures = 0;
  };

  CycleBlock read_block(CycleSpan span) {
    CycleBlock b;
    for_each_decoded_row(db_, DecodedTable::cycles, run_id_, span, [&](const auto& row) {
      b.figures[static_cast<int>(std::get<std::int64_t>(row[1]))].push_back(row);
    });
    for_each_cycle(db_, run_id_, span, [&](const StoredCycle& c) { b.cycles[c.cycle].push_back(c); });
    if (run_.info.has_targets()) {
      for_each_target(db_, run_id_, span, [&](const StoredTarget& t) { b.targets[t.cycle].push_back(t); });
      for_each_object_state(db_, run_id_, span, [&](const StoredObjectState& s) { b.boxes[s.cycle].push_back(s); });
    }
    return b;
  }

  void message(std::uint16_t channel, std::uint64_t ns, const Json& body) {
    writer_.write_message(channel, ns, body.dump());
    ++counts_.messages;
  }

  // What holds for the whole run, at its first cycle's time: the mountings and the view fields.
  void write_static(std::uint64_t ns) {
    for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
      const report::SensorInfo& s = run_.sensors[i];
      message(tf_channel_, ns, foxglove::frame_transform(ns, "ego", sensor_channels_[i].frame, s.X_VS));
      message(sensor_channels_[i].view_field, ns, scene_update(Json::array({foxglove::view_field_entity(sensor_channels_[i].frame, s.azimuth_half_rad, s.max_range_m, ns)})));
    }
  }

  void write_block(const CycleBlock& b) {
    for (const auto& [cycle, sensors] : b.cycles) {
      const std::uint64_t ns = time_ns(sensors.front().t_s);
      if (!static_written_) write_static(ns), static_written_ = true;
      write_ego(ns, sensors);
      write_boxes(ns, b.boxes.count(cycle) ? b.boxes.at(cycle) : std::vector<StoredObjectState>{});
      const auto targets = b.targets.find(cycle);
      for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
        write_targets(ns, static_cast<int>(i), targets == b.targets.end() ? nullptr : &targets->second);
      }
      for (const auto& row : b.figures.at(cycle)) {
        const auto sensor = static_cast<std::size_t>(std::get<std::int64_t>(row[2]));
        if (sensor < sensor_channels_.size()) message(sensor_channels_[sensor].figures, ns, figures_json(row));
      }
      ++counts_.cycles;
    }
  }

  // The ego in the world from a sensor's pose and mounting: X_WV = X_WS X_VS^-1 (a summary run
  // keeps no poses: the ego stays at the world's origin).
  void write_ego(std::uint64_t ns, const std::vector<StoredCycle>& sensors) {
    for (const StoredCycle& c : sensors) {
      if (!c.X_WS || c.sensor < 0 || static_cast<std::size_t>(c.sensor) >= run_.sensors.size()) continue;
      const Pose2 X_WV = compose(*c.X_WS, inverse(run_.sensors[static_cast<std::size_t>(c.sensor)].X_VS));
      message(tf_channel_, ns, foxglove::frame_transform(ns, "world", "ego", X_WV));
      return;
    }
    if (!ego_at_origin_) message(tf_channel_, ns, foxglove::frame_transform(ns, "world", "ego", Pose2{})), ego_at_origin_ = true;
  }

  void write_boxes(std::uint64_t ns, const std::vector<StoredObjectState>& boxes) {
    Json e = entity(ns, "world", "boxes", lifetime_ns_);
    for (const StoredObjectState& s : boxes) {
      const report::ObjectInfo* o = s.object >= 0 && static_cast<std::size_t>(s.object) < run_.objects.size() ? &run_.objects[static_cast<std::size_t>(s.object)] : nullptr;
      const Json pose = pose_json(s.X_WO.x_m, s.X_WO.y_m, 0.5 * kBoxHeightM, s.X_WO.yaw_rad);
      e["cubes"].push_back({{"pose", pose}, {"size", vec3(o ? o->length_m : 4.5, o ? o->width_m : 1.8, kBoxHeightM)},
                            {"color", colour(colours::kBackground, 0.35)}});
      e["texts"].push_back({{"pose", pose_json(s.X_WO.x_m, s.X_WO.y_m, kBoxHeightM + 0.5, 0.0)}, {"billboard", true},
                            {"font_size", 14.0}, {"scale_invariant", true}, {"color", colour(colours::kLabel)},
                            {"text", run_.object_label(s.object)}});
    }
    message(boxes_channel_, ns, scene_update(Json::array({e})));
  }

  // A sensor's recorded targets as spheres and its simulated ones as cubes, in its own frame.
  void write_targets(std::uint64_t ns, int sensor, const std::vector<StoredTarget>* targets) {
    const std::string& frame = sensor_channels_[static_cast<std::size_t>(sensor)].frame;
    Json recorded = entity(ns, frame, "recorded", lifetime_ns_), simulated = entity(ns, frame, "simulated", lifetime_ns_);
    if (targets != nullptr) {
      for (const StoredTarget& t : *targets) {
        if (t.sensor != sensor) continue;
        const Vec2 p = t.p_ST_S();
        const double z_m = std::isfinite(t.elevation_rad) ? t.range_m * std::sin(t.elevation_rad) : 0.0;
        Json shape = {{"pose", pose_json(p.x(), p.y(), z_m, 0.0)}, {"size", vec3(kTargetSizeM, kTargetSizeM, kTargetSizeM)},
                      {"color", colour(class_colour(t))}};
        (t.simulated ? simulated["cubes"] : recorded["spheres"]).push_back(std::move(shape));
      }
    }
    message(sensor_channels_[static_cast<std::size_t>(sensor)].recorded, ns, scene_update(Json::array({recorded})));
    message(sensor_channels_[static_cast<std::size_t>(sensor)].simulated, ns, scene_update(Json::array({simulated})));
  }

  ReportDatabase& db_;
  std::int64_t run_id_;
  report::RunData run_;
  mcap::Writer writer_;
  std::uint16_t scene_ = 0, transform_ = 0, figures_ = 0, tf_channel_ = 0, boxes_channel_ = 0;
  std::vector<SensorChannels> sensor_channels_;
  std::vector<std::string> frames_;
  std::uint64_t lifetime_ns_ = 0;
  bool static_written_ = false, ego_at_origin_ = false;
  McapReplayCounts counts_;
};

}  // namespace mcap_replay_internal

std::string mcap_replay_topic(const std::string& sensor_id, const std::string& what) {
  return sensor_id.empty() ? "/rcsim/" + what : "/rcsim/" + sensor_id + "/" + what;
}

McapReplayCounts write_run_mcap(ReportDatabase& db, std::int64_t run_id, std::ostream& out) {
  return mcap_replay_internal::McapReplayWriter(db, run_id, out).write();
}

}  // namespace rcsim::replay
