#include "io/recording.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <numbers>
#include <unistd.h>

#include "common/closest_name.hpp"
#include "common/angles.hpp"
#include "common/atomic_file.hpp"
#include "common/limits.hpp"
#include "common/safe_text.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/text_file.hpp"
#include "io/csv_reader.hpp"
#include "io/recording_stream.hpp"
#include "io/recording_writer.hpp"

namespace rcsim {

namespace fs = std::filesystem;

namespace {

// Version 3's limits (schemas/recording.md): an object's attributes are a flat record for reports,
// not a second data file; a range-rate interval is a radar's unambiguous Doppler span.
constexpr std::size_t kMaxAttributes = 32;
constexpr std::size_t kMaxAttributeText_bytes = 256;
constexpr double kMaxRangeRateIntervalWidth_mps = 2.0 * limits::kMaxSpeed_mps;

// What is wrong with an object's attributes, if anything: a flat object of at most 32 members
// whose values are strings (at most 256 bytes, one line) or finite numbers. `where` receives the
// member's name when one is at fault.
std::optional<std::string> attributes_problem(const nlohmann::json& attributes, std::string& where) {
  if (!attributes.is_object()) return "must be an object of strings and numbers";
  if (attributes.size() > kMaxAttributes) {
    return fmt::format("{} members exceed the limit of {}", attributes.size(), kMaxAttributes);
  }
  for (const auto& [key, value] : attributes.items()) {
    where = key;
    if (key.empty() || key.size() > kMaxAttributeText_bytes) {
      return fmt::format("a name must hold 1 to {} bytes", kMaxAttributeText_bytes);
    }
    if (const auto bad = find_control_character(key)) return "the name holds " + *bad;
    if (value.is_string()) {
      const auto& text = value.get_ref<const std::string&>();
      if (text.size() > kMaxAttributeText_bytes) {
        return fmt::format("a string of {} bytes exceeds the limit of {} bytes", text.size(), kMaxAttributeText_bytes);
      }
      if (const auto bad = find_control_character(text)) return "the string holds " + *bad;
    } else if (value.is_number()) {
      if (!std::isfinite(value.get<double>())) return "must be finite";
    } else {
      return std::string("must be a string or a number, got ") + value.type_name() +
             (value.is_structured() ? " (attributes do not nest)" : "");
    }
  }
  where.clear();
  return std::nullopt;
}

// What is wrong with a range-rate interval, if anything: min < 0 < max, at most 2000 m/s wide.
std::optional<std::string> interval_problem(const RangeRateInterval& interval) {
  if (!std::isfinite(interval.min_mps) || !std::isfinite(interval.max_mps)) return "[min, max] must be finite";
  if (!(interval.min_mps < 0.0 && interval.max_mps > 0.0)) {
    return fmt::format("[{}, {}]: needs min < 0 < max (m/s)", interval.min_mps, interval.max_mps);
  }
  if (interval.max_mps - interval.min_mps > kMaxRangeRateIntervalWidth_mps) {
    return fmt::format("[{}, {}] is wider than the limit of {} m/s", interval.min_mps, interval.max_mps,
                       kMaxRangeRateIntervalWidth_mps);
  }
  return std::nullopt;
}

// A choice among words: the index of `text` in `words`, else the field refused listing them.
template <std::size_t N>
std::size_t one_of(const JsonField& field, std::string_view key, const std::array<std::string_view, N>& words) {
  const std::string text = field.string(key);
  for (std::size_t i = 0; i < N; ++i) {
    if (text == words[i]) return i;
  }
  std::string expected;
  for (const auto& w : words) expected += (expected.empty() ? "\"" : "\" or \"") + std::string(w);
  field.fail(key, "must be " + expected + "\", got \"" + text + "\"");
}

constexpr std::array<std::string_view, 2> kTimelineWords{"drive", "snapshots"};
constexpr std::array<std::string_view, 2> kAmplitudeUnitWords{"snr_db", "relative_db"};
constexpr std::array<std::string_view, 2> kClockWords{"shared", "per_sensor"};

// A field of a later version than the file declares is refused by name (a reader of that
// version would ignore nothing, and neither does this one).
void refuse_newer_fields(const JsonField& field, int version, int since, std::initializer_list<std::string_view> keys) {
  if (version >= since) return;
  for (const std::string_view key : keys) {
    if (field.has(key)) {
      field.fail(key, fmt::format("is a version {} field, but the recording says version {}", since, version));
    }
  }
}

void read_header(Recording& rec, const fs::path& path) {  // recording.json
  const std::string file = path.string();
  const nlohmann::json json = parse_json_text(read_text_file(path), file);
  const JsonField root(json, file, "");
  const int version = root.expect_format_versions("rcsim-recording", 1, 5);
  refuse_newer_fields(root, version, 3, {"timeline", "ego_motion_known"});
  refuse_newer_fields(root, version, 4, {"clock"});
  root.expect_only({"format", "version", "name", "description", "cycle_time_s", "timeline", "ego_motion_known", "clock",
                    "sensors", "objects", "source"});
  rec.name = root.string("name");
  if (root.has("description")) rec.description = root.string("description");
  rec.cycle_time_s = root.number_within("cycle_time_s", 0.0, limits::kMaxCycleTime_s, "s");
  require_positive(root, "cycle_time_s", rec.cycle_time_s);
  if (root.has("timeline")) rec.timeline = static_cast<Timeline>(one_of(root, "timeline", kTimelineWords));
  rec.ego_motion_known = root.boolean_or("ego_motion_known", true);
  if (root.has("clock")) rec.clock = static_cast<Clock>(one_of(root, "clock", kClockWords));
  if (const auto source = root.optional_member("source")) {
    if (!source->json().is_object()) root.fail("source", "must be an object");
    rec.source = source->json();
  }
  for (const JsonField& s : root.array("sensors")) {
    refuse_newer_fields(s, version, 2, {"reports"});
    refuse_newer_fields(s, version, 3, {"amplitude_unit", "range_rate_interval_mps"});
    refuse_newer_fields(s, version, 4, {"cycle_time_s"});
    refuse_newer_fields(s, version, 5, {"z_m", "pitch_rad"});
    s.expect_only({"id", "type", "x_m", "y_m", "yaw_rad", "reports", "amplitude_unit", "range_rate_interval_mps",
                   "cycle_time_s", "z_m", "pitch_rad"});
    using namespace limits;
    RecordingSensor sensor{s.string("id"), s.string("type"),
                           s.number_within("x_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m"),
                           s.number_within("y_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m"),
                           s.angle_rad("yaw_rad", kMaxMountYaw_rad)};
    if (s.has("reports")) {
      const std::string reports = s.string("reports");
      if (reports == "detections") {
        sensor.reports = ListLevel::detections;
      } else if (reports != "tracks") {
        s.fail("reports", "must be \"tracks\" or \"detections\", got \"" + reports + "\"");
      }
    }
    if (s.has("amplitude_unit")) {
      sensor.amplitude_unit = static_cast<AmplitudeUnit>(one_of(s, "amplitude_unit", kAmplitudeUnitWords));
    }
    if (s.has("range_rate_interval_mps")) {
      const std::vector<JsonField> bounds = s.array("range_rate_interval_mps");
      if (bounds.size() != 2 || !bounds[0].json().is_number() || !bounds[1].json().is_number()) {
        s.fail("range_rate_interval_mps", "must be [min, max], two numbers in m/s");
      }
      const RangeRateInterval interval{bounds[0].json().get<double>(), bounds[1].json().get<double>()};
      if (const auto problem = interval_problem(interval)) s.fail("range_rate_interval_mps", *problem);
      sensor.range_rate_interval_mps = interval;
    }
    // A sensor's own cycle time goes with its own clock, and its own clock needs one.
    if (rec.clock == Clock::per_sensor) {
      if (!s.has("cycle_time_s")) s.fail("cycle_time_s", "a sensor on its own clock (clock \"per_sensor\") needs its cycle time");
      sensor.cycle_time_s = s.number_within("cycle_time_s", 0.0, limits::kMaxCycleTime_s, "s");
      require_positive(s, "cycle_time_s", sensor.cycle_time_s);
    } else if (s.has("cycle_time_s")) {
      s.fail("cycle_time_s", "a sensor's own cycle time needs the recording's \"clock\": \"per_sensor\"");
    }
    if (s.has("z_m")) sensor.z_m = s.number_within("z_m", 0.0, kMaxMountOffset_m, "m");
    if (s.has("pitch_rad")) sensor.pitch_rad = s.angle_rad("pitch_rad", kMaxMountPitch_rad);
    if (sensor.id.empty()) s.fail("id", "must not be empty");
    if (rec.sensor_index(sensor.id) >= 0) s.fail("id", fmt::format("sensor '{}' is listed twice", sensor.id));
    rec.sensors.push_back(std::move(sensor));
  }
  if (rec.sensors.empty()) root.fail("sensors", "a recording needs at least one sensor");
  for (const JsonField& o : root.array("objects")) {
    refuse_newer_fields(o, version, 3, {"attributes"});
    o.expect_only({"id", "class", "length_m", "width_m", "attributes"});
    RecordingObject object{o.string("id"), o.string("class"), o.number_within("length_m", 0.0, limits::kMaxSize_m, "m"),
                           o.number_within("width_m", 0.0, limits::kMaxSize_m, "m")};
    require_positive(o, "length_m", object.length_m);
    require_positive(o, "width_m", object.width_m);
    if (o.has("attributes")) {
      const nlohmann::json& attributes = o.json().at("attributes");
      std::string member;
      if (const auto problem = attributes_problem(attributes, member)) {
        o.fail(member.empty() ? std::string("attributes") : "attributes." + member, *problem);
      }
      object.attributes = attributes;
    }
    if (object.id.empty()) o.fail("id", "must not be empty");
    for (const RecordingObject& other : rec.objects) {
      if (other.id == object.id) o.fail("id", fmt::format("object '{}' is listed twice", object.id));
    }
    rec.objects.push_back(std::move(object));
  }
}

// A new file written through a 1 MiB buffer (an hour's recording never sits in memory as text),
// synced to disk when closed.
class FileOut {
 public:
  explicit FileOut(const fs::path& path) : path_(path), fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644)) {
    if (fd_ < 0) throw InputError(path.string(), "", std::string("cannot create file: ") + std::strerror(errno));
  }
  FileOut(const FileOut&) = delete;
  FileOut& operator=(const FileOut&) = delete;
  ~FileOut() {
    if (fd_ >= 0) ::close(fd_);
  }
  // Where rows are formatted; each row_done() writes the buffer out once it holds 1 MiB.
  std::string& text() { return buffer_; }
  auto out() { return std::back_inserter(buffer_); }
  void row_done() {
    if (buffer_.size() >= kFlushBytes) flush();
  }
  void close() {
    flush();
    ::fsync(fd_);
    ::close(fd_);
    fd_ = -1;
  }

 private:
  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
  void flush() {
    std::size_t written = 0;
    while (written < buffer_.size()) {
      const ssize_t n = ::write(fd_, buffer_.data() + written, buffer_.size() - written);
      if (n < 0) throw InputError(path_.string(), "", std::string("write failed: ") + std::strerror(errno));
      written += static_cast<std::size_t>(n);
    }
    buffer_.clear();
  }
  fs::path path_;
  int fd_;
  std::string buffer_;
};

void write_file(const fs::path& path, const std::string& text) {
  FileOut file(path);
  file.text() = text;
  file.close();
}

// Whether a version 3 field differs from its default (then the recording is written as version 3).
bool uses_version_3(const Recording& rec) {
  if (rec.timeline != Timeline::drive || !rec.ego_motion_known) return true;
  for (const auto& s : rec.sensors) {
    if (s.amplitude_unit != AmplitudeUnit::snr_db || s.range_rate_interval_mps) return true;
  }
  for (const auto& o : rec.objects) {
    if (!o.attributes.is_object() || !o.attributes.empty()) return true;
  }
  return false;
}

// Version 5: a sensor mounted at a height or pitched.
bool uses_version_5(const Recording& rec) {
  return std::any_of(rec.sensors.begin(), rec.sensors.end(), [](const RecordingSensor& s) { return s.z_m != 0.0 || s.pitch_rad != 0.0; });
}

std::string header_text(const Recording& rec) {
  nlohmann::ordered_json json;
  // The lowest version that holds the fields used, so that version 1 to 3 recordings are
  // rewritten byte for byte as they were: 4 where the sensors run on their own clocks, 3 where a
  // version 3 field differs from its default, 2 where a sensor reports detections, else 1.
  const int version = uses_version_5(rec)            ? 5
                      : rec.clock == Clock::per_sensor ? 4
                      : uses_version_3(rec)           ? 3
                      : !rec.all_sensors_report(ListLevel::tracks) ? 2
                                                                   : 1;
  json["format"] = "rcsim-recording";
  json["version"] = version;
  json["name"] = rec.name;
  if (!rec.description.empty()) json["description"] = rec.description;
  json["cycle_time_s"] = rec.cycle_time_s;
  if (version >= 3) {
    json["timeline"] = std::string(kTimelineWords[static_cast<std::size_t>(rec.timeline)]);
    json["ego_motion_known"] = rec.ego_motion_known;
  }
  if (version >= 4) json["clock"] = std::string(kClockWords[static_cast<std::size_t>(rec.clock)]);
  json["sensors"] = nlohmann::ordered_json::array();
  for (const auto& s : rec.sensors) {
    json["sensors"].push_back({{"id", s.id}, {"type", s.type}, {"x_m", s.x_m}, {"y_m", s.y_m}, {"yaw_rad", s.yaw_rad}});
    auto& sensor = json["sensors"].back();
    if (version >= 2) sensor["reports"] = list_level_name(s.reports);
    if (version >= 3) {
      sensor["amplitude_unit"] = std::string(kAmplitudeUnitWords[static_cast<std::size_t>(s.amplitude_unit)]);
      if (s.range_rate_interval_mps) {
        sensor["range_rate_interval_mps"] = {s.range_rate_interval_mps->min_mps, s.range_rate_interval_mps->max_mps};
      }
    }
    if (rec.clock == Clock::per_sensor) sensor["cycle_time_s"] = s.cycle_time_s;
    if (version >= 5) {
      sensor["z_m"] = s.z_m;
      sensor["pitch_rad"] = s.pitch_rad;
    }
  }
  json["objects"] = nlohmann::ordered_json::array();
  for (const auto& o : rec.objects) {
    json["objects"].push_back({{"id", o.id}, {"class", o.object_class}, {"length_m", o.length_m}, {"width_m", o.width_m}});
    if (version >= 3 && !o.attributes.empty()) json["objects"].back()["attributes"] = o.attributes;
  }
  if (!rec.source.empty()) json["source"] = rec.source;
  return json.dump(2) + "\n";
}

}  // namespace

std::vector<EgoSample> read_ego_log(const fs::path& path) {
  std::vector<EgoSample> rows;
  EgoRowReader reader(path, EgoLogSpacing{});
  for (EgoSample s; reader.next(s);) rows.push_back(s);
  return rows;
}

bool Recording::all_sensors_report(ListLevel level) const {
  return std::all_of(sensors.begin(), sensors.end(), [&](const RecordingSensor& s) { return s.reports == level; });
}

int Recording::cycle_count() const {
  const std::size_t rows = clock == Clock::per_sensor ? cycles.size() : ego.size();
  return rows == 0 ? streamed_cycles : static_cast<int>(rows);
}

double Recording::cycle_t_s(int k) const {
  return clock == Clock::per_sensor ? cycles.at(static_cast<std::size_t>(k)).t_s : ego.at(static_cast<std::size_t>(k)).t_s;
}

int Recording::cycle_sensor(int k) const {
  return clock == Clock::per_sensor ? cycles.at(static_cast<std::size_t>(k)).sensor : -1;
}

EgoSample Recording::ego_at_cycle(int k) const {
  if (clock == Clock::shared) return ego.at(static_cast<std::size_t>(k));
  const double t_s = cycle_t_s(k);
  const auto hi = std::lower_bound(ego.begin(), ego.end(), t_s, [](const EgoSample& e, double t) { return e.t_s < t; });
  if (hi == ego.begin() || hi == ego.end()) {  // within the margin beyond the log's ends: its end row
    EgoSample end = hi == ego.begin() ? ego.front() : ego.back();
    end.t_s = t_s;
    return end;
  }
  return interpolate_ego(*(hi - 1), *hi, t_s);
}

double Recording::sensor_cycle_time_s(std::size_t sensor) const {
  const double own_s = sensors.at(sensor).cycle_time_s;
  return clock == Clock::per_sensor && own_s > 0.0 ? own_s : cycle_time_s;
}

long long Recording::sensor_cycle_count() const {
  const long long count = cycle_count();
  return clock == Clock::per_sensor ? count : count * static_cast<long long>(sensors.size());
}

int Recording::sensor_index(const std::string& id) const {
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (sensors[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash) {
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

Recording read_recording_header(const fs::path& dir) {
  if (!fs::is_directory(dir)) {
    // A mistyped directory: the nearest recording beside it, if one is close.
    std::string hint;
    std::error_code error;
    const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
    if (!fs::exists(dir, error) && fs::is_directory(parent, error)) {
      std::vector<std::string> siblings;
      for (const auto& entry : fs::directory_iterator(parent, error)) {
        if (fs::is_regular_file(entry.path() / "recording.json", error)) siblings.push_back(entry.path().filename().string());
      }
      if (const auto meant = closest_name(dir.filename().string(), siblings)) hint = fmt::format("; did you mean '{}'?", (parent / *meant).string());
    }
    throw InputError(dir.string(), "", "not a recording directory" + hint);
  }
  Recording rec;
  rec.dir = dir;
  read_header(rec, dir / "recording.json");
  return rec;
}

std::uint64_t recording_checksum(const fs::path& dir) { return recording_checksum(dir, read_recording_header(dir).clock); }

std::uint64_t recording_checksum(const fs::path& dir, Clock clock) {
  std::uint64_t hash = fnv1a64("rcsim-recording/1");
  for (const char* name : {"recording.json", "ego.csv", "objects.csv", "targets.csv"}) {
    hash = fnv1a64_file(dir / name, hash);
  }
  if (clock == Clock::per_sensor) hash = fnv1a64_file(dir / "cycles.csv", hash);
  return hash;
}

Recording read_recording(const fs::path& dir) {
  RecordingStream stream(dir);
  Recording rec = stream.header();
  rec.ego.reserve(static_cast<std::size_t>(rec.cycle_count()));
  for (EgoSample s; stream.ego().next(s);) rec.ego.push_back(s);
  if (CycleRowReader* cycles = stream.cycles()) {
    rec.cycles.reserve(static_cast<std::size_t>(rec.cycle_count()));
    for (SensorCycle c; cycles->next(c);) {
      cycles->check_within_ego_log(rec.ego.front().t_s, rec.ego.back().t_s);
      rec.cycles.push_back(c);
    }
    cycles->finish();
  }
  rec.boxes.assign(rec.objects.size(), {});
  std::size_t object = 0;
  for (AnnotatedBox box; stream.boxes().next(object, box);) rec.boxes[object].push_back(box);
  stream.boxes().finish();
  for (int k = 0; k < rec.cycle_count(); ++k) {
    stream.targets().read_cycle(k, rec.cycle_t_s(k), rec.cycle_sensor(k), rec.targets);
  }
  stream.targets().finish();
  rec.streamed_cycles = 0;  // the rows are here
  return rec;
}

namespace {

std::vector<std::string> ids_of(const Recording& rec) {
  std::vector<std::string> ids;
  for (const auto& s : rec.sensors) ids.push_back(s.id);
  for (const auto& o : rec.objects) ids.push_back(o.id);
  return ids;
}

}  // namespace

namespace {

// What the reader could not read back is not written: ids that are not one line, version 3's
// fields as the reader takes them.
void check_writable(const Recording& rec) {
  // Ids go into CSV rows, one row per line.
  for (const auto& id : ids_of(rec)) {
    if (const auto bad = find_control_character(id)) {
      throw std::invalid_argument(fmt::format("the id '{}' holds {}: a recording's ids are one line", id, *bad));
    }
  }
  // Sensors on their own clocks: each with its cycle time, cycles listed.
  if (rec.clock == Clock::per_sensor) {
    for (const auto& s : rec.sensors) {
      if (!(s.cycle_time_s > 0.0)) throw std::invalid_argument(fmt::format("sensor '{}' on its own clock has no cycle time", s.id));
    }
  }
  // Version 3's fields as the reader takes them.
  for (const auto& s : rec.sensors) {
    if (!s.range_rate_interval_mps) continue;
    if (const auto problem = interval_problem(*s.range_rate_interval_mps)) {
      throw std::invalid_argument(fmt::format("sensor '{}': range_rate_interval_mps {}", s.id, *problem));
    }
  }
  for (const auto& o : rec.objects) {
    std::string member;
    if (const auto problem = attributes_problem(o.attributes, member)) {
      throw std::invalid_argument(
          fmt::format("object '{}': attributes{}{}: {}", o.id, member.empty() ? "" : ".", member, *problem));
    }
  }
}
}  // namespace

// The open files of a RecordingWriter.
struct RecordingWriter::Files {
  explicit Files(const fs::path& dir, bool own_clocks)
      : ego(dir / "ego.csv"), objects(dir / "objects.csv"), targets(dir / "targets.csv") {
    if (own_clocks) cycles = std::make_unique<FileOut>(dir / "cycles.csv");
  }
  FileOut ego, objects, targets;
  std::unique_ptr<FileOut> cycles;
};

RecordingWriter::RecordingWriter(const fs::path& dir, std::vector<std::string> sensor_ids, TargetColumns columns, bool own_clocks)
    : sensor_ids_(std::move(sensor_ids)), columns_(columns) {
  target_ = fs::absolute(dir).lexically_normal();
  name_ = target_.filename().empty() ? target_.parent_path().filename() : target_.filename();
  parent_ = target_.filename().empty() ? target_.parent_path().parent_path() : target_.parent_path();
  // The parent is made as `mkdir -p` would: `import ... -o out/rec` in a fresh clone just works.
  std::error_code error;
  fs::create_directories(parent_, error);
  if (!fs::is_directory(parent_)) {
    throw InputError(dir.string(), "", fmt::format("cannot make the parent directory: {}", error ? error.message() : "not a directory"));
  }
  check_output_directory(target_, "recording.json");
  temp_ = create_temp_directory(parent_ / name_, "tmp");  // a fresh name no one could plant a link at
  files_ = std::make_unique<Files>(temp_, own_clocks);
  files_->ego.text() = "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
  files_->objects.text() = "t_s,object,x_m,y_m,yaw_rad,speed_mps\n";
  files_->targets.text() = columns_.id ? "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db"
                                       : "t_s,cycle,sensor,range_m,azimuth_rad,range_rate_mps,amplitude_db";
  files_->targets.text() += std::string(columns_.rcs_dbsm ? ",rcs_dbsm" : "") + (columns_.snr_db ? ",snr_db" : "") +
                            (columns_.elevation_rad ? ",elevation_rad" : "") + "\n";
  if (files_->cycles) files_->cycles->text() = "t_s,sensor\n";
}

RecordingWriter::~RecordingWriter() {
  if (finished_) return;
  files_.reset();
  std::error_code ignored;
  fs::remove_all(temp_, ignored);
}

void RecordingWriter::ego(const EgoSample& e) {
  fmt::format_to(files_->ego.out(), "{:.6f},{:.4f},{:.4f},{:.6f},{:.4f},{:.6f}\n", e.t_s, e.x_m, e.y_m, e.yaw_rad, e.speed_mps,
                 e.yaw_rate_radps);
  files_->ego.row_done();
}

void RecordingWriter::box(const std::string& object_id, const AnnotatedBox& b) {
  fmt::format_to(files_->objects.out(), "{:.6f},{},{:.4f},{:.4f},{:.6f},{:.4f}\n", b.t_s, csv_field(object_id), b.x_m, b.y_m,
                 b.yaw_rad, b.speed_mps);
  files_->objects.row_done();
}

void RecordingWriter::target(const RecordedTarget& t) {
  // A column holds a number in every row (the reader refuses empty fields and nan).
  if ((columns_.rcs_dbsm && !std::isfinite(t.rcs_dbsm)) || (columns_.snr_db && !std::isfinite(t.snr_db)) ||
      (columns_.elevation_rad && !std::isfinite(t.elevation_rad))) {
    throw std::invalid_argument("targets.csv: an optional column (rcs_dbsm, snr_db, elevation_rad) is given for some targets only");
  }
  FileOut& out = files_->targets;
  fmt::format_to(out.out(), "{:.6f},{},{},", t.t_s, t.cycle, csv_field(sensor_ids_.at(static_cast<std::size_t>(t.sensor))));
  if (columns_.id) fmt::format_to(out.out(), "{},", t.id);
  fmt::format_to(out.out(), "{:.4f},{:.6f},{:.4f},{:.3f}", t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db);
  if (columns_.rcs_dbsm) fmt::format_to(out.out(), ",{:.3f}", t.rcs_dbsm);
  if (columns_.snr_db) fmt::format_to(out.out(), ",{:.3f}", t.snr_db);
  if (columns_.elevation_rad) fmt::format_to(out.out(), ",{:.6f}", t.elevation_rad);
  out.text() += '\n';
  out.row_done();
}

void RecordingWriter::cycle(const SensorCycle& c) {
  fmt::format_to(files_->cycles->out(), "{:.6f},{}\n", c.t_s, csv_field(sensor_ids_.at(static_cast<std::size_t>(c.sensor))));
  files_->cycles->row_done();
  ++cycles_;
}

void RecordingWriter::finish(const Recording& header, const std::map<std::string, std::string>& extra_files) {
  check_writable(header);
  if (files_->cycles && cycles_ == 0) throw std::invalid_argument("sensors on their own clocks: no cycles listed");
  files_->ego.close(), files_->objects.close(), files_->targets.close();
  if (files_->cycles) files_->cycles->close();
  write_file(temp_ / "recording.json", header_text(header));
  for (const auto& [file, content] : extra_files) write_file(temp_ / fs::path(file).filename(), content);
  // A directory cannot be renamed over a non-empty one: move the old one aside first.
  const fs::path old = random_temp_path(parent_ / name_, "old");
  const bool replacing = fs::exists(target_);
  if (replacing) fs::rename(target_, old);
  try {
    fs::rename(temp_, target_);
  } catch (...) {
    if (replacing) fs::rename(old, target_);  // the earlier recording back in place
    throw;
  }
  finished_ = true;
  std::error_code ignored;  // the new recording is in place: a leftover of the old one is no failure
  if (replacing) fs::remove_all(old, ignored);
}

TargetColumns target_columns(const Recording& rec) {
  const auto any = [&](double RecordedTarget::*field) {
    return std::any_of(rec.targets.begin(), rec.targets.end(), [&](const RecordedTarget& t) { return std::isfinite(t.*field); });
  };
  // The id column only when the sensors report track ids (raw detections have none).
  return {std::any_of(rec.targets.begin(), rec.targets.end(), [](const RecordedTarget& t) { return t.id >= 0; }),
          any(&RecordedTarget::rcs_dbsm), any(&RecordedTarget::snr_db), any(&RecordedTarget::elevation_rad)};
}

void write_recording(const fs::path& dir, const Recording& rec, const std::map<std::string, std::string>& extra_files) {
  check_writable(rec);  // before anything is made
  if (rec.clock == Clock::per_sensor && rec.cycles.empty()) throw std::invalid_argument("sensors on their own clocks: no cycles listed");
  std::vector<std::string> sensor_ids;
  for (const RecordingSensor& s : rec.sensors) sensor_ids.push_back(s.id);
  RecordingWriter writer(dir, sensor_ids, target_columns(rec), rec.clock == Clock::per_sensor);
  for (const EgoSample& e : rec.ego) writer.ego(e);
  // Boxes in time order, objects in recording order within one time.
  std::vector<std::pair<std::size_t, const AnnotatedBox*>> rows;
  for (std::size_t i = 0; i < rec.boxes.size(); ++i) {
    for (const auto& b : rec.boxes[i]) rows.emplace_back(i, &b);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second->t_s < b.second->t_s; });
  for (const auto& [i, b] : rows) writer.box(rec.objects[i].id, *b);
  for (const RecordedTarget& t : rec.targets) writer.target(t);
  for (const SensorCycle& c : rec.cycles) writer.cycle(c);
  writer.finish(rec, extra_files);
}

EgoSample interpolate_ego(const EgoSample& a, const EgoSample& b, double t_s) {
  const double f = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 0.0;
  const auto lerp = [f](double u, double v) { return u + f * (v - u); };
  return {t_s, lerp(a.x_m, b.x_m), lerp(a.y_m, b.y_m), wrap_angle_rad(a.yaw_rad + f * angle_difference_rad(b.yaw_rad, a.yaw_rad)),
          lerp(a.speed_mps, b.speed_mps), lerp(a.yaw_rate_radps, b.yaw_rate_radps)};
}

EgoSample ego_sample(double t_s, const BodyState& ego) {
  return {t_s, ego.X_WB.x_m, ego.X_WB.y_m, wrap_angle_rad(ego.X_WB.yaw_rad), ego.heading_speed_mps(), ego.yaw_rate_radps};
}

}  // namespace rcsim
