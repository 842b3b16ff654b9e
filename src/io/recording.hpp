#pragma once
// A recorded measurement campaign (`rcsim-recording` v1 to v4, schemas/recording.md): a directory with
// recording.json, ego.csv (one row per sensor cycle, or an ego log at its own rate where the
// sensors run on their own clocks), objects.csv (annotated boxes), targets.csv (what the sensors
// reported) and, for sensors on their own clocks (v4), cycles.csv (every sensor cycle's time).
// Read once, validated, then read-only.
#include <cstdint>
#include <limits>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/amplitude_unit.hpp"
#include "common/list_level.hpp"
#include "common/pose2.hpp"

namespace rcsim {

// A radar with a small unambiguous Doppler interval reports radial speeds wrapped into it
// (version 3): a measured v lies in [min, max), and v + k (max - min) reads the same.
struct RangeRateInterval {
  double min_mps = 0.0, max_mps = 0.0;
};

// How the cycles relate (version 3): a drive (one clock, objects followed from cycle to cycle) or
// snapshots (every cycle a frame of its own, as a labelled dataset of single frames: nothing is
// carried from one cycle to the next, and `t_s` only orders them).
enum class Timeline { drive, snapshots };

// Whose clock the cycles follow (version 4): one cycle clock for every sensor, whose cycles are
// ego.csv's rows (versions 1 to 3), or each sensor on its own clock, its cycles listed in
// cycles.csv and the ego log at a rate of its own, interpolated to them.
enum class Clock { shared, per_sensor };

// A sensor cycle interpolates the ego log within its span and at most this far beyond its first or
// last row (the ego's state there is extrapolated from that row by its speed and yaw rate).
inline constexpr double kEgoExtrapolationMargin_s = 0.1;
// An ego log of sensors on their own clocks has rows at most this far apart (interpolation bridges
// no longer hole).
inline constexpr double kMaxEgoLogStep_s = 1.0;

struct RecordingSensor {
  std::string id;
  std::string type;  // built-in sensor configuration name or a path relative to the recording
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;  // pose in the ego vehicle frame
  ListLevel reports = ListLevel::tracks;  // detections or tracks (version 2; version 1 recordings report tracks); replay compares at this level by default
  AmplitudeUnit amplitude_unit = AmplitudeUnit::snr_db;     // version 3
  std::optional<RangeRateInterval> range_rate_interval_mps = std::nullopt;  // version 3: none, unambiguous
  double cycle_time_s = 0.0;  // version 4, sensors on their own clocks: this sensor's nominal cycle time (0: the recording's)
  // Version 5: the sensor's height above the road and its pitch (boresight down positive), which
  // a radar that measures elevation reads (a planar one ignores them).
  double z_m = 0.0, pitch_rad = 0.0;
};

struct RecordingObject {
  std::string id;
  std::string object_class;  // names a model of the object library
  double length_m = 0.0, width_m = 0.0;
  // Version 3: what the dataset says besides (its own class name, occlusion, certainty, height):
  // a flat object of strings and numbers, kept for reports and per-class figures.
  nlohmann::json attributes = nlohmann::json::object();
};

// One ego.csv row; row k is the ego state at sensor cycle k.
struct EgoSample {
  double t_s = 0.0, x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, speed_mps = 0.0, yaw_rate_radps = 0.0;
};

// The ego's row at t_s from its state: the yaw wrapped, the signed speed along its heading. Every
// writer of a recording from a scene (rcsim synth, model-made recordings) takes it from here.
EgoSample ego_sample(double t_s, const BodyState& ego);

// The ego between two rows a and b (a.t_s <= t_s <= b.t_s) at t_s: linear in position, speed and
// yaw rate, the yaw along the shorter arc.
EgoSample interpolate_ego(const EgoSample& a, const EgoSample& b, double t_s);

// One objects.csv row: an annotated box centre in the world frame.
struct AnnotatedBox {
  double t_s = 0.0, x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, speed_mps = 0.0;
  int line = 0;  // line in objects.csv, for messages
};

// One cycles.csv row (version 4, sensors on their own clocks): row k is cycle k, one sensor's cycle.
struct SensorCycle {
  double t_s = 0.0;
  int sensor = 0;  // index into Recording::sensors
};

// One targets.csv row.
struct RecordedTarget {
  double t_s = 0.0;
  int cycle = 0;
  int sensor = 0;  // index into Recording::sensors
  int id = -1;     // the sensor's track id, -1 when the file has no id column
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
  // Optional columns, NaN where the file has none: what real radars report besides.
  double rcs_dbsm = kNoValue, snr_db = kNoValue, elevation_rad = kNoValue;
  static constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
};

struct Recording {
  std::filesystem::path dir;
  std::string name;
  std::string description;
  double cycle_time_s = 0.0;
  Timeline timeline = Timeline::drive;  // version 3
  // Version 3: false where the dataset holds no ego motion (ego.csv's speed and yaw rate are 0
  // placeholders); replay then neither compares radial speeds nor classes targets by them.
  bool ego_motion_known = true;
  Clock clock = Clock::shared;           // version 4
  std::vector<RecordingSensor> sensors;
  std::vector<RecordingObject> objects;
  nlohmann::json source = nlohmann::json::object();  // free-form provenance (generator, seed, ...)
  std::vector<EgoSample> ego;                           // one per cycle (shared clock), else the ego log
  std::vector<SensorCycle> cycles;                      // per_sensor clock: every sensor cycle, in time order
  std::vector<std::vector<AnnotatedBox>> boxes;         // per object, time-ordered
  std::vector<RecordedTarget> targets;                  // in file order (cycle-ordered)
  std::uint64_t checksum = 0;                           // FNV-1a 64 over the four files
  // A streamed recording (recording_stream.hpp) holds no rows: its cycle count, from the header pass.
  int streamed_cycles = 0;

  int cycle_count() const;
  // Cycle k's time and sensor (-1: every sensor fires in it, a shared clock); rows in memory only.
  double cycle_t_s(int k) const;
  int cycle_sensor(int k) const;
  // The ego's row at cycle k: ego.csv's row k (shared clock) or the ego log interpolated to the
  // cycle's time (per_sensor: linear, the yaw along the shorter way).
  EgoSample ego_at_cycle(int k) const;
  // The sensor's nominal cycle time: its own (per_sensor clock) or the recording's.
  double sensor_cycle_time_s(std::size_t sensor) const;
  // The sensors' cycles in all: cycles × sensors on a shared clock, the cycles listed on their own.
  long long sensor_cycle_count() const;
  bool all_sensors_report(ListLevel level) const;
  int sensor_index(const std::string& id) const;  // -1 if unknown
};

// Reads and validates a recording directory; any problem is an InputError naming the file and
// the line or field.
Recording read_recording(const std::filesystem::path& dir);

// Writes a recording directory atomically: into a temporary sibling directory, then renamed into
// place (replacing an earlier recording of that name only once the new one is complete).
// `extra_files` (name -> content) go into the same directory, e.g. a sensor configuration file
// that a sensor's `type` names.
// An ego log on its own (an importer's --ego-log): ego.csv's columns, times increasing, any
// spacing; InputError naming the file, line and column otherwise.
std::vector<EgoSample> read_ego_log(const std::filesystem::path& path);

void write_recording(const std::filesystem::path& dir, const Recording& recording,
                     const std::map<std::string, std::string>& extra_files = {});

// FNV-1a 64-bit hash of bytes, chained; identifies a recording's content (not a security hash).
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ULL);

}  // namespace rcsim
