#pragma once
// Target list output (schemas/target-list.md): CSV with a header, or JSON Lines with the same
// keys, one row per target; fixed decimals so that equal runs give byte-identical files.
#include <ostream>
#include <string>

#include "sim/simulation.hpp"

namespace rcsim {

enum class TargetListFormat { Csv, Jsonl };

class TargetListWriter {
 public:
  TargetListWriter(std::ostream& out, TargetListFormat format, ListLevel level);

  void write_header();
  // All rows of one sensor's cycle at the writer's level.
  void write_sensor_cycle(const Scene& scene, int cycle, double t_s, const std::string& sensor_id,
                          const SensorCycleState& state);
  long long rows_written() const { return rows_; }

 private:
  struct Row {
    int id;
    double range_m, azimuth_rad, range_rate_mps, amplitude_db;
    const std::string* object;
    std::string reflector;
  };
  void write_row(int cycle, double t_s, const std::string& sensor_id, const Row& row);

  std::ostream& out_;
  TargetListFormat format_;
  ListLevel level_;
  long long rows_ = 0;
};

}  // namespace rcsim
