#include "sim/target_list_writer.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "io/csv_reader.hpp"
#include "sim/amplitude.hpp"
#include "sim/visibility.hpp"

namespace rcsim {

bool rows_carry_elevation(const Scene& scene) {
  return std::any_of(scene.sensors.begin(), scene.sensors.end(),
                     [](const MountedSensor& s) { return s.config.fov.measures_elevation(); });
}

TargetListWriter::TargetListWriter(std::ostream& out, TargetListFormat format, ListLevel level, bool elevation)
    : out_(out), format_(format), level_(level), elevation_(elevation) {}

void TargetListWriter::write_header() {
  if (format_ != TargetListFormat::Csv) return;
  out_ << "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db";
  if (elevation_) out_ << ",elevation_rad";
  if (level_ == ListLevel::ideal) out_ << ",object,reflector";
  out_ << '\n';
}

void TargetListWriter::write_row(int cycle, double t_s, const std::string& sensor_id, const TargetListRow& row) {
  ++rows_;
  if (format_ == TargetListFormat::Csv) {
    out_ << fmt::format("{:.6f},{},{},{},{:.4f},{:.6f},{:.4f},{:.3f}", t_s, cycle, csv_field(sensor_id), row.id,
                        row.range_m, row.azimuth_rad, row.range_rate_mps, row.amplitude_db);
    if (elevation_) out_ << fmt::format(",{:.6f}", row.elevation_rad);
    if (level_ == ListLevel::ideal) out_ << ',' << csv_field(*row.object) << ',' << csv_field(row.reflector);
    out_ << '\n';
    return;
  }
  out_ << fmt::format(
      "{{\"t_s\":{:.6f},\"cycle\":{},\"sensor\":{},\"id\":{},\"range_m\":{:.4f},\"azimuth_rad\":{:.6f},"
      "\"range_rate_mps\":{:.4f},\"amplitude_db\":{:.3f}",
      t_s, cycle, nlohmann::json(sensor_id).dump(), row.id, row.range_m, row.azimuth_rad, row.range_rate_mps,
      row.amplitude_db);
  if (elevation_) out_ << fmt::format(",\"elevation_rad\":{:.6f}", row.elevation_rad);
  if (level_ == ListLevel::ideal) {
    out_ << ",\"object\":" << nlohmann::json(*row.object).dump() << ",\"reflector\":" << nlohmann::json(row.reflector).dump();
  }
  out_ << "}\n";
}

void for_each_target_list_row(const Scene& scene, const SensorCycleState& state, ListLevel level,
                              const std::function<void(const TargetListRow&)>& visit) {
  switch (level) {
    case ListLevel::ideal:
      for (std::size_t i = 0; i < state.ideal.size(); ++i) {
        const auto& t = state.ideal[i];
        const auto& object = scene.objects[static_cast<std::size_t>(t.object_index)];
        const auto k = static_cast<std::size_t>(t.reflector_index);
        std::string reflector = t.kind == ReflectorKind::Point       ? object.model.points[k].name
                                : t.kind == ReflectorKind::BoxDiffuse ? std::string(kBoxSideNames[k])
                                                                      : object.model.planes[k].name;
        if (t.kind == ReflectorKind::PlaneDiffuse || t.kind == ReflectorKind::BoxDiffuse) reflector += "#diffuse";
        if (t.bounce_order > 1) reflector += fmt::format("#bounce{}", t.bounce_order);
        // echoes[i] belongs to ideal[i] at this level (cells are not formed).
        visit({static_cast<int>(i), t.range_m, t.azimuth_rad, t.range_rate_mps,
                        amplitude_to_db(state.echoes[i].amplitude), &object.id, std::move(reflector), t.elevation_rad});
      }
      break;
    case ListLevel::detections:
      for (std::size_t i = 0; i < state.detections.size(); ++i) {
        const auto& d = state.detections[i];
        visit({static_cast<int>(i), d.range_m, d.azimuth_rad, d.range_rate_mps, d.amplitude_db, nullptr, {}, d.elevation_rad});
      }
      break;
    case ListLevel::tracks:
      for (const auto& r : state.reported) {
        visit({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db, nullptr, {}, r.elevation_rad});
      }
      break;
  }
}

void TargetListWriter::write_sensor_cycle(const Scene& scene, int cycle, double t_s, const std::string& sensor_id,
                                          const SensorCycleState& state) {
  for_each_target_list_row(scene, state, level_, [&](const TargetListRow& row) { write_row(cycle, t_s, sensor_id, row); });
}

}  // namespace rcsim
