#include "io/recording_stream.hpp"

#include <cmath>
#include <fmt/format.h>

#include <fstream>
#include <numbers>

#include "common/limits.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"

namespace rcsim {

namespace fs = std::filesystem;

namespace {


// Limits on a target's numbers (schemas/recording.md): beyond them a value is a unit or format
// error, not a measurement (a range of 1e308 would be averaged into GOSPA).
constexpr double kMaxRange_m = limits::kMaxRange_m, kMaxRangeRate_mps = limits::kMaxSpeed_mps, kMaxLevel_db = limits::kMaxLevel_dB;

double number_within(const CsvReader& csv, int column, double limit, const char* unit) {
  const double value = csv.number(column);
  if (std::abs(value) > limit) csv.fail(column, fmt::format("|{}| exceeds the limit of {} {}", value, limit, unit));
  return value;
}

// The data rows of a CSV file as CsvReader counts them: its non-blank lines but the header.
int count_data_rows(const fs::path& path) {
  LineReader lines(path);
  int rows = -1;
  for (std::string_view line; lines.next(line);) {
    if (line.find_first_not_of(" \t") != std::string_view::npos) ++rows;
  }
  return std::max(rows, 0);
}

// A recording's CSV file cut short (a copy or a write that stopped) loses its last line's end,
// and a row cut inside its last number still reads as a row: every line of a recording's CSV ends
// with LF or CR LF (schemas/recording.md), so a file whose last byte is none is refused.
void check_ends_with_line_end(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() <= 0) return;  // a missing or empty file: its reader says what is wrong
  in.seekg(-1, std::ios::end);
  char last = 0;
  in.get(last);
  if (last != '\n') {
    throw InputError(path.string(), "its last line",
                     "no line end: the file is cut short? (every line of a recording's CSV ends with LF or CR LF)");
  }
}

std::unordered_map<std::string, std::size_t> index_by_id(const std::vector<RecordingObject>& objects) {
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < objects.size(); ++i) index.emplace(objects[i].id, i);
  return index;
}

}  // namespace

bool EgoRowReader::DegreeYawCheck::add(const EgoSample& previous, const EgoSample& row) {
  const double dt_s = row.t_s - previous.t_s;
  const double rate_radps = 0.5 * (row.yaw_rate_radps + previous.yaw_rate_radps);
  if (dt_s > 1.0 || std::abs(rate_radps) < 0.05) return false;
  ++turning;
  const double ratio = (row.yaw_rad - previous.yaw_rad) / dt_s / rate_radps;
  degree_like += ratio > 20.0 && ratio < 100.0;
  return turning >= 5 && 2 * degree_like > turning;
}

EgoRowReader::EgoRowReader(const fs::path& path, EgoLogSpacing spacing)
    : csv_(path.string(), {"t_s", "x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps"}),
      spacing_(spacing),
      t_(csv_.column("t_s")),
      x_(csv_.column("x_m")),
      y_(csv_.column("y_m")),
      yaw_(csv_.column("yaw_rad")),
      v_(csv_.column("speed_mps")),
      w_(csv_.column("yaw_rate_radps")) {}

bool EgoRowReader::next(EgoSample& s) {
  if (!csv_.next()) {
    if (!previous_) csv_.fail_line("the ego log has no rows");
    return false;
  }
  using namespace limits;
  s = {number_within(csv_, t_, kMaxTime_s, "s"), number_within(csv_, x_, kMaxCoordinate_m, "m"),
       number_within(csv_, y_, kMaxCoordinate_m, "m"), number_within(csv_, yaw_, kMaxUnwrappedYaw_rad, "rad"),
       number_within(csv_, v_, kMaxSpeed_mps, "m/s"), number_within(csv_, w_, kMaxYawRate_radps, "rad/s")};
  if (previous_ && s.t_s <= previous_->t_s) {
    csv_.fail(t_, fmt::format("time {} s does not follow the previous row's {} s (times must increase)", s.t_s,
                              previous_->t_s));
  }
  if (spacing_.cycle_time_s > 0.0 && previous_ && s.t_s - previous_->t_s > 1.5 * spacing_.cycle_time_s) {
    csv_.fail(t_, fmt::format("gap of {:.6f} s after the previous row (cycle time {} s): the ego log must have "
                              "one row per sensor cycle",
                              s.t_s - previous_->t_s, spacing_.cycle_time_s));
  }
  if (spacing_.max_step_s > 0.0 && previous_ && s.t_s - previous_->t_s > spacing_.max_step_s) {
    csv_.fail(t_, fmt::format("gap of {:.6f} s after the previous row: the ego log is interpolated to the sensors' "
                              "cycles over at most {} s",
                              s.t_s - previous_->t_s, spacing_.max_step_s));
  }
  if (!previous_ && std::abs(s.yaw_rad) > 2.0 * std::numbers::pi) {
    csv_.fail(yaw_, "yaw beyond ±2π in the first row: is it in degrees?");
  }
  if (previous_ && degree_check_.add(*previous_, s)) {
    csv_.fail(yaw_, "the yaw changes about 57 times faster than yaw_rate_radps says: is it in degrees?");
  }
  previous_ = s;
  return true;
}

BoxRowReader::BoxRowReader(const fs::path& path, const std::vector<RecordingObject>& objects)
    : csv_(path.string(), {"t_s", "object", "x_m", "y_m", "yaw_rad", "speed_mps"}),
      objects_(objects),
      index_of_(index_by_id(objects)),
      t_(csv_.column("t_s")),
      id_(csv_.column("object")),
      x_(csv_.column("x_m")),
      y_(csv_.column("y_m")),
      yaw_(csv_.column("yaw_rad")),
      v_(csv_.column("speed_mps")),
      last_(objects.size()),
      ahead_([this](Row& row) { return read_row(row); }) {}

bool BoxRowReader::next(std::size_t& object, AnnotatedBox& box) {
  Row row;
  if (!ahead_.next(row)) return false;
  object = row.object;
  box = row.box;
  return true;
}

bool BoxRowReader::read_row(Row& row) {
  if (!csv_.next()) return false;
  std::size_t& object = row.object;
  AnnotatedBox& box = row.box;
  const std::string& object_id = csv_.text(id_);
  const auto found = index_of_.find(object_id);
  if (found == index_of_.end()) csv_.fail(id_, fmt::format("object '{}' is not listed in recording.json", object_id));
  object = found->second;
  using namespace limits;
  box = {number_within(csv_, t_, kMaxTime_s, "s"), number_within(csv_, x_, kMaxCoordinate_m, "m"),
         number_within(csv_, y_, kMaxCoordinate_m, "m"), csv_.number(yaw_), number_within(csv_, v_, kMaxSpeed_mps, "m/s"),
         csv_.line()};
  // Annotated headings are wrapped: beyond ±2π they are degrees (as a target's azimuth beyond ±π).
  if (std::abs(box.yaw_rad) > kMaxYaw_rad) csv_.fail(yaw_, "yaw beyond ±2π: is it in degrees?");
  const AnnotatedBox& last = last_[object];
  if (last.line > 0 && box.t_s <= last.t_s) {
    csv_.fail(t_, fmt::format("time {} s of object '{}' does not follow its previous row's {} s (line {})", box.t_s,
                              object_id, last.t_s, last.line));
  }
  // Replay reads the annotations alongside the cycles, so the file must be in time order.
  if (box.t_s < last_t_s_) {
    csv_.fail(t_, fmt::format("time {} s precedes line {}'s {} s: rows must be in time order", box.t_s, last_line_,
                              last_t_s_));
  }
  last_t_s_ = box.t_s;
  last_line_ = box.line;
  last_[object] = box;
  return true;
}

void BoxRowReader::finish() const {
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    if (last_[i].line == 0) {
      throw InputError(csv_.path(), "", fmt::format("object '{}' of recording.json has no rows", objects_[i].id));
    }
  }
}

CycleRowReader::CycleRowReader(const fs::path& path, const Recording& header)
    : csv_(path.string(), {"t_s", "sensor"}),
      header_(header),
      t_(csv_.column("t_s")),
      s_(csv_.column("sensor")),
      last_of_sensor_s_(header.sensors.size(), -std::numeric_limits<double>::infinity()),
      line_of_sensor_(header.sensors.size(), 0) {}

bool CycleRowReader::next(SensorCycle& cycle) {
  if (!csv_.next()) return false;
  cycle.t_s = number_within(csv_, t_, limits::kMaxTime_s, "s");
  cycle.sensor = header_.sensor_index(csv_.text(s_));
  if (cycle.sensor < 0) csv_.fail(s_, fmt::format("sensor '{}' is not listed in recording.json", csv_.text(s_)));
  if (cycle.t_s < last_t_s_) {
    csv_.fail(t_, fmt::format("time {} s precedes the previous row's {} s: rows must be in time order", cycle.t_s, last_t_s_));
  }
  const auto s = static_cast<std::size_t>(cycle.sensor);
  if (cycle.t_s <= last_of_sensor_s_[s]) {
    csv_.fail(t_, fmt::format("sensor '{}' has two cycles at {} s (line {}): a sensor's cycle times strictly increase",
                              header_.sensors[s].id, cycle.t_s, line_of_sensor_[s]));
  }
  last_t_s_ = last_of_sensor_s_[s] = cycle.t_s;
  line_of_sensor_[s] = csv_.line();
  return true;
}

void CycleRowReader::check_within_ego_log(double first_s, double last_s) const {
  if (last_t_s_ < first_s - kEgoExtrapolationMargin_s || last_t_s_ > last_s + kEgoExtrapolationMargin_s) {
    csv_.fail(t_, fmt::format("cycle at {} s lies beyond the ego log's {} to {} s by more than {} s (the ego is "
                              "interpolated, not extrapolated)",
                              last_t_s_, first_s, last_s, kEgoExtrapolationMargin_s));
  }
}

void CycleRowReader::finish() const {
  if (std::isinf(last_t_s_)) csv_.fail_line("no cycles: sensors on their own clocks list every cycle here");
  for (std::size_t s = 0; s < header_.sensors.size(); ++s) {
    if (line_of_sensor_[s] == 0) {
      throw InputError(csv_.path(), "", fmt::format("sensor '{}' of recording.json has no cycles", header_.sensors[s].id));
    }
  }
}

TargetRowReader::TargetRowReader(const fs::path& path, const Recording& header, int cycle_count)
    : csv_(path.string(), {"t_s", "cycle", "sensor", "range_m", "azimuth_rad", "range_rate_mps", "amplitude_db"}),
      header_(header),
      cycle_count_(cycle_count),
      t_(csv_.column("t_s")),
      k_(csv_.column("cycle")),
      s_(csv_.column("sensor")),
      id_(csv_.column("id")),
      r_(csv_.column("range_m")),
      az_(csv_.column("azimuth_rad")),
      rr_(csv_.column("range_rate_mps")),
      amp_(csv_.column("amplitude_db")),
      rcs_(csv_.column("rcs_dbsm")),  // optional, like id and elevation
      snr_(csv_.column("snr_db")),
      el_(csv_.column("elevation_rad")),
      ahead_([this](Row& row) { return read_row(row); }) {}

bool TargetRowReader::read_row(Row& row) {
  if (!csv_.next()) return false;
  RecordedTarget& target = row.target;
  target = {};
  row.line = csv_.line();
  target.t_s = csv_.number(t_);
  const long long cycle = csv_.integer(k_);
  if (cycle < 0 || cycle >= cycle_count_) {
    csv_.fail(k_, fmt::format("cycle {} is outside {}'s cycles 0..{}", cycle,
                              header_.clock == Clock::per_sensor ? "cycles.csv" : "the ego log", cycle_count_ - 1));
  }
  target.cycle = static_cast<int>(cycle);
  if (target.cycle < previous_cycle_) {
    csv_.fail(k_, fmt::format("cycle {} after cycle {}: rows must be in cycle order", target.cycle, previous_cycle_));
  }
  previous_cycle_ = target.cycle;
  target.sensor = header_.sensor_index(csv_.text(s_));
  if (target.sensor < 0) csv_.fail(s_, fmt::format("sensor '{}' is not listed in recording.json", csv_.text(s_)));
  if (id_ >= 0) {
    const long long track_id = csv_.integer(id_);
    if (track_id < 0 || track_id > 1'000'000'000) csv_.fail(id_, "track id out of range");
    target.id = static_cast<int>(track_id);
  }
  target.range_m = number_within(csv_, r_, kMaxRange_m, "m");
  if (target.range_m < 0.0) csv_.fail(r_, "range must not be negative");
  target.azimuth_rad = csv_.number(az_);
  if (std::abs(target.azimuth_rad) > limits::kMaxAzimuth_rad) csv_.fail(az_, "azimuth beyond ±π: is it in degrees?");
  target.range_rate_mps = number_within(csv_, rr_, kMaxRangeRate_mps, "m/s");
  target.amplitude_db = number_within(csv_, amp_, kMaxLevel_db, "dB");
  if (rcs_ >= 0) target.rcs_dbsm = number_within(csv_, rcs_, kMaxLevel_db, "dBsm");
  if (snr_ >= 0) target.snr_db = number_within(csv_, snr_, kMaxLevel_db, "dB");
  if (el_ >= 0) {
    target.elevation_rad = csv_.number(el_);
    if (std::abs(target.elevation_rad) > 1.58) csv_.fail(el_, "elevation beyond ±π/2: is it in degrees?");
  }
  return true;
}

bool TargetRowReader::next_pending() {
  if (pending_) return true;
  if (at_end_) return false;
  Row row;
  if (ahead_.next(row)) {
    pending_ = std::move(row);
  } else {
    at_end_ = true;
  }
  return pending_.has_value();
}

void TargetRowReader::read_cycle(int cycle, double t_s, int sensor, std::vector<RecordedTarget>& out) {
  const char* clock_file = header_.clock == Clock::per_sensor ? "cycles.csv" : "ego.csv";
  while (next_pending() && pending_->target.cycle == cycle) {
    if (std::abs(pending_->target.t_s - t_s) > kRecordingTimeTolerance_s) {
      throw InputError(csv_.path(), fmt::format("line {}, column 't_s'", pending_->line),
                       fmt::format("time {} s differs from cycle {}'s time {} s in {}", pending_->target.t_s,
                                   cycle, t_s, clock_file));
    }
    if (sensor >= 0 && pending_->target.sensor != sensor) {
      throw InputError(csv_.path(), fmt::format("line {}, column 'sensor'", pending_->line),
                       fmt::format("sensor '{}' in cycle {}, which cycles.csv gives to sensor '{}'",
                                   header_.sensors[static_cast<std::size_t>(pending_->target.sensor)].id, cycle,
                                   header_.sensors[static_cast<std::size_t>(sensor)].id));
    }
    out.push_back(pending_->target);
    pending_.reset();
  }
}

void TargetRowReader::finish() {
  if (next_pending()) {
    throw InputError(csv_.path(), fmt::format("line {}, column 'cycle'", pending_->line),
                     fmt::format("cycle {} was not read: cycles must be asked for in order", pending_->target.cycle));
  }
}

RecordingStream::RecordingStream(const fs::path& dir)
    : dir_(dir),
      header_([&] {
        Recording header = read_recording_header(dir);
        header.checksum = recording_checksum(dir, header.clock);
        const bool own_clocks = header.clock == Clock::per_sensor;
        header.streamed_cycles = count_data_rows(dir / (own_clocks ? "cycles.csv" : "ego.csv"));
        return header;
      }()),
      ego_(dir / "ego.csv", header_.clock == Clock::per_sensor ? EgoLogSpacing{0.0, kMaxEgoLogStep_s}
                                                               : EgoLogSpacing{header_.cycle_time_s, 0.0}),
      boxes_(dir / "objects.csv", header_.objects),
      targets_(dir / "targets.csv", header_, header_.cycle_count()) {
  if (header_.clock == Clock::per_sensor) cycles_.emplace(dir / "cycles.csv", header_);
  // After the readers: they refuse a device or a pipe before anything reads to its end.
  for (const char* file : {"ego.csv", "objects.csv", "targets.csv"}) check_ends_with_line_end(dir / file);
  if (cycles_) check_ends_with_line_end(dir / "cycles.csv");
}

}  // namespace rcsim
