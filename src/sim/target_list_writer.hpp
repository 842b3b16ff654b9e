#pragma once
// Target list output (schemas/target-list.md): CSV with a header, or JSON Lines with the same
// keys, one row per target; fixed decimals so that equal runs give byte-identical files.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace rcsim {

enum class TargetListFormat { Csv, Jsonl };

// One row of a sensor's cycle at a list level (schemas/target-list.md).
struct TargetListRow {
  int id;
  double range_m, azimuth_rad, range_rate_mps, amplitude_db;
  const std::string* object;  // ideal targets only
  std::string reflector;      // ideal targets only
  double elevation_rad = 0.0;  // 0 from a planar radar
};

// The rows of one sensor's cycle at `level`, in order: ideal targets, detections or reported
// tracks. Visited one by one, so that writing a cycle allocates no list.
void for_each_target_list_row(const Scene& scene, const SensorCycleState& state, ListLevel level,
                              const std::function<void(const TargetListRow&)>& visit);

// Whether a scene's target lists carry elevations: some sensor of it measures elevation.
bool rows_carry_elevation(const Scene& scene);

class TargetListWriter {
 public:
  // elevation: the scene has a radar that measures elevation; the rows then carry elevation_rad
  // (schemas/target-list.md), and a planar scene's file stays as it was.
  TargetListWriter(std::ostream& out, TargetListFormat format, ListLevel level, bool elevation = false);

  void write_header();
  // All rows of one sensor's cycle at the writer's level.
  void write_sensor_cycle(const Scene& scene, int cycle, double t_s, const std::string& sensor_id,
                          const SensorCycleState& state);
  long long rows_written() const { return rows_; }

 private:
  void write_row(int cycle, double t_s, const std::string& sensor_id, const TargetListRow& row);

  std::ostream& out_;
  TargetListFormat format_;
  ListLevel level_;
  bool elevation_;
  long long rows_ = 0;
};

}  // namespace rcsim
