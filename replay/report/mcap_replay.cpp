#include "replay/report/mcap_replay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <variant>
#include <vector>

#include "common/pose2.hpp"
#include "common/safe_text.hpp"
#include "common/target_colours.hpp"
#include "io/foxglove_json.hpp"
#include "io/mcap_writer.hpp"
#include "metrics/target_class.hpp"
#include "replay/store/decoded_rows.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

namespace mcap_replay_internal {

using foxglove::Json;
using foxglove::scene_update;
using foxglove::time_ns;

constexpr double kTargetSizeM = 0.5;   // a target's sphere or cube
// Every channel names the format (schemas/mcap-replay.md).
const std::map<std::string, std::string> kFormat = {{"format", "rcsim-mcap-replay"}, {"version", "1"}};

std::string cycle_figures_schema() {
  Json properties = Json::object();
  for (const DecodedColumn& c : decoded_columns(DecodedTable::cycles)) {
    // A figure a run did not compute is null (a --store summary run's, a cycle without pairs).
    properties[c.name] = {{"type", Json::array({c.sql_type == "TEXT" ? "string" : (c.sql_type == "INTEGER" ? "integer" : "number"), "null"})}};
  }
  return Json{{"title", "rcsim.CycleFigures"}, {"type", "object"}, {"properties", properties}}.dump();
}

// A target's colour by its class, as JSON.
const std::string& class_colour_json(const StoredTarget& t) {
  static const std::string background = foxglove::text::colour(colours::kBackground), other = foxglove::text::colour(colours::kOther),
                           simulated = foxglove::text::colour(colours::kSimulated), recorded = foxglove::text::colour(colours::kRecorded);
  if (t.target_class == metrics::TargetClass::stationary_background) return background;
  if (t.target_class == metrics::TargetClass::other) return other;
  return t.simulated ? simulated : recorded;
}

const std::string kWorld = foxglove::text::quoted("world"), kEgo = foxglove::text::quoted("ego");

// A cycle's figures as a JSON object, one member per column of the decoded cycles table; `keys`
// the members' names quoted, with their colons.
std::string figures_json(const std::vector<DecodedValue>& row, const std::vector<std::string>& keys) {
  std::string out = "{";
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) out += ',';
    out += keys[i];
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, std::monostate>) {
            out += "null";
          } else if constexpr (std::is_same_v<T, std::string>) {
            out += foxglove::text::quoted(x);
          } else if constexpr (std::is_same_v<T, double>) {
            foxglove::text::number(out, x);
          } else {
            fmt::format_to(std::back_inserter(out), "{}", x);
          }
        },
        row[i]);
  }
  return out + "}";
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
  McapReplayWriter(ReportDatabase& db, std::int64_t run_id, std::ostream& out, McapClock clock)
      : db_(db), run_id_(run_id), run_(report::load_run(db, run_id)), writer_(out, "", mcap::Compression::zstd) {
    if (clock == McapClock::log) offset_ns_ = first_timestamp_ns(run_.info.recording_source);
    check_names_are_utf8();
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
    // On own clocks a sensor's targets stay until its next cycle replaces them (lifetime 0).
    target_lifetime_ns_ = run_.on_own_clocks() ? 0 : lifetime_ns_;
    for (const DecodedColumn& c : decoded_columns(DecodedTable::cycles)) figure_keys_.push_back(foxglove::text::quoted(c.name) + ":");
    for (std::size_t o = 0; o < run_.objects.size(); ++o) object_labels_.push_back(foxglove::text::quoted(run_.object_label(static_cast<int>(o))));
    for (SensorChannels& c : sensor_channels_) c.frame_json = foxglove::text::quoted(c.frame);
  }

  McapReplayCounts write() {
    const int last = last_stored_cycle(db_, run_id_);
    // Block by block over what is stored (64-bit spans: a damaged report may claim 2^31 - 1 cycles).
    for (std::int64_t first = next_stored_cycle(db_, run_id_, 0); first >= 0 && first <= last;) {
      const std::int64_t end = std::min<std::int64_t>(last, first + kBlockCycles - 1);
      write_block(read_block({static_cast<int>(first), static_cast<int>(end)}));
      if (end >= last) break;
      first = next_stored_cycle(db_, run_id_, end + 1);
    }
    counts_.bytes = writer_.finish();
    counts_.sensors = static_cast<int>(run_.sensors.size());
    return counts_;
  }

 private:
  struct SensorChannels {
    std::string frame;  // the sensor's frame id and its topics' middle part
    std::string frame_json;  // quoted
    std::uint16_t recorded = 0, simulated = 0, view_field = 0, figures = 0;
  };

  // The sensors' and objects' names go into JSON messages, which hold UTF-8 only (issue 51: a
  // non-UTF-8 object id threw the JSON library's type_error.316, exit 1): refused by position.
  void check_names_are_utf8() const {
    const auto check = [](const std::string& text, const std::string& what) {
      const auto bad = find_control_character(text);
      if (bad && bad->rfind("invalid UTF-8", 0) == 0) {
        throw std::invalid_argument(fmt::format("{} is not UTF-8 text ({}); an MCAP export's JSON messages hold UTF-8 only", what, *bad));
      }
    };
    for (const report::SensorInfo& s : run_.sensors) {
      check(s.id, fmt::format("sensor {}'s id", s.sensor));
      check(s.type, fmt::format("sensor {}'s type", s.sensor));
    }
    for (const report::ObjectInfo& o : run_.objects) {
      check(o.id, fmt::format("object {}'s id", o.object));
      check(o.object_class, fmt::format("object {}'s class", o.object));
    }
  }

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

  void message(std::uint16_t channel, std::uint64_t ns, const std::string& body) {
    writer_.write_message(channel, ns, body);
    ++counts_.messages;
  }

  // What holds for the whole run, at its first cycle's time: the mountings and the view fields.
  void write_static(std::uint64_t ns) {
    for (std::size_t i = 0; i < run_.sensors.size(); ++i) {
      const report::SensorInfo& s = run_.sensors[i];
      message(tf_channel_, ns, foxglove::frame_transform(ns, "ego", sensor_channels_[i].frame, s.X_VS).dump());
      message(sensor_channels_[i].view_field, ns,
              scene_update(Json::array({foxglove::view_field_entity(sensor_channels_[i].frame, s.azimuth_half_rad, s.max_range_m, ns)})).dump());
    }
  }

  // A run time on the export's clock.
  std::uint64_t ns_of(double t_s) const { return time_ns(t_s) + offset_ns_; }

  static std::uint64_t first_timestamp_ns(const std::string& source) {
    const Json json = Json::parse(source, nullptr, false);
    if (json.is_object() && json.contains("first_timestamp_ns") && json["first_timestamp_ns"].is_number_unsigned()) {
      return json["first_timestamp_ns"].get<std::uint64_t>();
    }
    throw std::invalid_argument("--clock log: the run's recording names no source.first_timestamp_ns (it was not imported from a log); "
                                "export it on the run's clock");
  }

  void write_block(const CycleBlock& b) {
    for (const auto& [cycle, sensors] : b.cycles) {
      const std::uint64_t ns = ns_of(sensors.front().t_s);
      if (!static_written_) write_static(ns), static_written_ = true;
      write_ego(ns, sensors);
      write_boxes(ns, b.boxes.count(cycle) ? b.boxes.at(cycle) : std::vector<StoredObjectState>{});
      const auto targets = b.targets.find(cycle);
      const std::vector<StoredTarget>* cycle_targets = targets == b.targets.end() ? nullptr : &targets->second;
      if (run_.on_own_clocks()) {
        // Only the sensors of this cycle: another's entities would blank its targets until its next.
        for (const StoredCycle& c : sensors) {
          if (c.sensor >= 0 && static_cast<std::size_t>(c.sensor) < run_.sensors.size()) write_targets(ns_of(c.t_s), c.sensor, cycle_targets);
        }
      } else {
        for (std::size_t i = 0; i < run_.sensors.size(); ++i) write_targets(ns, static_cast<int>(i), cycle_targets);
      }
      for (const auto& row : b.figures.at(cycle)) {
        const auto sensor = static_cast<std::size_t>(std::get<std::int64_t>(row[2]));
        if (sensor < sensor_channels_.size()) message(sensor_channels_[sensor].figures, ns, figures_json(row, figure_keys_));
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
      message(tf_channel_, ns, foxglove::text::frame_transform(ns, kWorld, kEgo, X_WV));
      return;
    }
    if (!ego_at_origin_) message(tf_channel_, ns, foxglove::text::frame_transform(ns, kWorld, kEgo, Pose2{})), ego_at_origin_ = true;
  }

  void write_boxes(std::uint64_t ns, const std::vector<StoredObjectState>& boxes) {
    static const std::string boxes_id = foxglove::text::quoted("boxes");
    foxglove::text::Entity e(ns, kWorld, boxes_id, lifetime_ns_);
    for (const StoredObjectState& s : boxes) {
      const bool known = s.object >= 0 && static_cast<std::size_t>(s.object) < run_.objects.size();
      const report::ObjectInfo* o = known ? &run_.objects[static_cast<std::size_t>(s.object)] : nullptr;
      e.box(s.X_WO, o ? o->length_m : 4.5, o ? o->width_m : 1.8,
            known ? object_labels_[static_cast<std::size_t>(s.object)] : foxglove::text::quoted(run_.object_label(s.object)));
    }
    message(boxes_channel_, ns, e.scene_update());
  }

  // A sensor's recorded targets as spheres and its simulated ones as cubes, in its own frame.
  void write_targets(std::uint64_t ns, int sensor, const std::vector<StoredTarget>* targets) {
    static const std::string recorded_id = foxglove::text::quoted("recorded"), simulated_id = foxglove::text::quoted("simulated");
    const SensorChannels& channels = sensor_channels_[static_cast<std::size_t>(sensor)];
    foxglove::text::Entity recorded(ns, channels.frame_json, recorded_id, target_lifetime_ns_),
        simulated(ns, channels.frame_json, simulated_id, target_lifetime_ns_);
    if (targets != nullptr) {
      for (const StoredTarget& t : *targets) {
        if (t.sensor != sensor) continue;
        // A radar that measures elevation: range·cos(elevation) in the sensor's horizontal plane,
        // range·sin(elevation) above it; a planar one (NaN) in the plane.
        const bool elevated = std::isfinite(t.elevation_rad);
        const Vec2 p = elevated ? Vec2(t.p_ST_S() * std::cos(t.elevation_rad)) : t.p_ST_S();
        const double z_m = elevated ? t.range_m * std::sin(t.elevation_rad) : 0.0;
        const std::string& c = class_colour_json(t);
        if (t.simulated) {
          simulated.cube(p.x(), p.y(), z_m, 0.0, kTargetSizeM, kTargetSizeM, kTargetSizeM, c);
        } else {
          recorded.sphere(p.x(), p.y(), z_m, 0.0, kTargetSizeM, kTargetSizeM, kTargetSizeM, c);
        }
      }
    }
    message(channels.recorded, ns, recorded.scene_update());
    message(channels.simulated, ns, simulated.scene_update());
  }

  ReportDatabase& db_;
  std::int64_t run_id_;
  report::RunData run_;
  mcap::Writer writer_;
  std::uint16_t scene_ = 0, transform_ = 0, figures_ = 0, tf_channel_ = 0, boxes_channel_ = 0;
  std::vector<SensorChannels> sensor_channels_;
  std::vector<std::string> frames_;
  std::vector<std::string> figure_keys_, object_labels_;  // quoted, once
  std::uint64_t lifetime_ns_ = 0, target_lifetime_ns_ = 0, offset_ns_ = 0;
  bool static_written_ = false, ego_at_origin_ = false;
  McapReplayCounts counts_;
};

}  // namespace mcap_replay_internal

std::string mcap_replay_topic(const std::string& sensor_id, const std::string& what) {
  return sensor_id.empty() ? "/rcsim/" + what : "/rcsim/" + sensor_id + "/" + what;
}

McapReplayCounts write_run_mcap(ReportDatabase& db, std::int64_t run_id, std::ostream& out, McapClock clock) {
  return mcap_replay_internal::McapReplayWriter(db, run_id, out, clock).write();
}

}  // namespace rcsim::replay
