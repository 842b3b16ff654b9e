#pragma once
// A recording read row by row (schemas/recording.md), in memory bounded whatever its length:
// recording.json at once; ego.csv one row per cycle; objects.csv in time order; targets.csv one
// cycle at a time. Every row gets the checks read_recording gives it (read_recording is built on
// this), and every complaint names the file, the line and the column.
#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/csv_reader.hpp"
#include "io/read_ahead.hpp"
#include "io/recording.hpp"

namespace rcsim {

// Times in a recording agree when they differ by less than this (files carry 6 decimals).
inline constexpr double kRecordingTimeTolerance_s = 2e-6;

// What an ego log's spacing must be: one row per sensor cycle (a shared clock: no step above 1.5
// cycle times), rows at most max_step_s apart (an ego log of sensors on their own clocks), or any.
struct EgoLogSpacing {
  double cycle_time_s = 0.0;  // > 0: one row per cycle of this nominal length
  double max_step_s = 0.0;    // > 0: no step longer
};

// ego.csv's (or an ego log's) rows, spaced as `spacing` says.
class EgoRowReader {
 public:
  EgoRowReader(const std::filesystem::path& path, EgoLogSpacing spacing);
  bool next(EgoSample& sample);  // false after the last row (a file with no rows is refused)

 private:
  // Counts, over the row pairs where the vehicle turns (|yaw rate| >= 0.05 rad/s), those whose
  // yaw changed 20 to 100 times faster than the yaw rate says (180/π = 57.3: a yaw in degrees
  // beside a yaw rate in rad/s). Mostly so, once 5 such pairs are in: the yaw is in degrees.
  struct DegreeYawCheck {
    int turning = 0, degree_like = 0;
    bool add(const EgoSample& previous, const EgoSample& row);
  };
  CsvReader csv_;
  EgoLogSpacing spacing_;
  int t_, x_, y_, yaw_, v_, w_;
  DegreeYawCheck degree_check_;
  std::optional<EgoSample> previous_;
};

// objects.csv's rows: rows in time order, per object strictly increasing, every listed object
// with at least one row (checked by finish(), after the last row). Parsed and checked ahead on a
// thread of their own (read_ahead.hpp).
class BoxRowReader {
 public:
  BoxRowReader(const std::filesystem::path& path, const std::vector<RecordingObject>& objects);
  bool next(std::size_t& object, AnnotatedBox& box);
  void finish() const;

 private:
  struct Row {
    std::size_t object = 0;
    AnnotatedBox box;
  };
  bool read_row(Row& row);  // on the read-ahead thread
  CsvReader csv_;
  const std::vector<RecordingObject>& objects_;
  std::unordered_map<std::string, std::size_t> index_of_;
  int t_, id_, x_, y_, yaw_, v_;
  std::vector<AnnotatedBox> last_;  // per object: its last row (line 0: none yet)
  double last_t_s_ = -std::numeric_limits<double>::infinity();
  int last_line_ = 0;
  ReadAhead<Row> ahead_;  // last: its thread starts once the rest is built
};

// cycles.csv's rows (version 4, sensors on their own clocks): row k is cycle k, `t_s` and
// `sensor`; rows in time order, each sensor's times strictly increasing, every sensor with a cycle
// (checked by finish()).
class CycleRowReader {
 public:
  CycleRowReader(const std::filesystem::path& path, const Recording& header);
  bool next(SensorCycle& cycle);
  // Refuses the last row read when its time lies beyond the ego log's [first_s, last_s] by more
  // than kEgoExtrapolationMargin_s.
  void check_within_ego_log(double first_s, double last_s) const;
  void finish() const;

 private:
  CsvReader csv_;
  const Recording& header_;
  int t_, s_;
  double last_t_s_ = -std::numeric_limits<double>::infinity();
  std::vector<double> last_of_sensor_s_;
  std::vector<int> line_of_sensor_;
};

// targets.csv's rows, one cycle at a time, cycles in order; parsed and checked ahead on a thread
// of their own.
class TargetRowReader {
 public:
  TargetRowReader(const std::filesystem::path& path, const Recording& header, int cycle_count);
  // Appends the rows of `cycle` (recorded at time t_s; by `sensor` alone, or -1: by every sensor)
  // to `out`; cycles asked for in order.
  void read_cycle(int cycle, double t_s, int sensor, std::vector<RecordedTarget>& out);
  void finish();  // refuses rows left over (cycles beyond the ego log)

 private:
  struct Row {
    RecordedTarget target;
    int line = 0;
  };
  bool read_row(Row& row);  // on the read-ahead thread
  bool next_pending();
  CsvReader csv_;
  const Recording& header_;
  int cycle_count_;
  int t_, k_, s_, id_, r_, az_, rr_, amp_, rcs_, snr_, el_;
  int previous_cycle_ = 0;
  std::optional<Row> pending_;
  bool at_end_ = false;
  ReadAhead<Row> ahead_;  // last: its thread starts once the rest is built
};

// The whole recording as a stream: the header and checksum first (one pass over the files in a
// fixed buffer, counting the cycles), then the rows.
class RecordingStream {
 public:
  explicit RecordingStream(const std::filesystem::path& dir);
  // The header: name, sensors, objects, checksum, and cycle_count() (no rows).
  const Recording& header() const { return header_; }
  EgoRowReader& ego() { return ego_; }
  BoxRowReader& boxes() { return boxes_; }
  TargetRowReader& targets() { return targets_; }
  CycleRowReader* cycles() { return cycles_ ? &*cycles_ : nullptr; }  // sensors on their own clocks only
  std::string boxes_path() const { return (dir_ / "objects.csv").string(); }

 private:
  std::filesystem::path dir_;
  Recording header_;
  EgoRowReader ego_;
  BoxRowReader boxes_;
  TargetRowReader targets_;
  std::optional<CycleRowReader> cycles_;
};

// Reads recording.json alone (no rows, checksum 0).
Recording read_recording_header(const std::filesystem::path& dir);

// FNV-1a 64 over the four files, and cycles.csv where the sensors run on their own clocks
// (schemas/recording.md), read in a fixed buffer; the first form reads the clock off recording.json.
std::uint64_t recording_checksum(const std::filesystem::path& dir);
std::uint64_t recording_checksum(const std::filesystem::path& dir, Clock clock);

}  // namespace rcsim
