#include <algorithm>
#include <stdexcept>
#include "io/recording.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <numbers>
#include <unistd.h>

#include "common/atomic_file.hpp"
#include "common/limits.hpp"
#include "common/safe_text.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/text_file.hpp"
#include "io/csv_reader.hpp"
#include "io/recording_stream.hpp"

namespace rcsim {

namespace fs = std::filesystem;

namespace {

void read_header(Recording& rec, const fs::path& path) {  // recording.json
  const std::string file = path.string();
  const nlohmann::json json = parse_json_text(read_text_file(path), file);
  const JsonField root(json, file, "");
  const int version = root.expect_format_versions("rcsim-recording", 1, 2);
  root.expect_only({"format", "version", "name", "description", "cycle_time_s", "sensors", "objects", "source"});
  rec.name = root.string("name");
  if (root.has("description")) rec.description = root.string("description");
  rec.cycle_time_s = root.number_within("cycle_time_s", 0.0, limits::kMaxCycleTime_s, "s");
  require_positive(root, "cycle_time_s", rec.cycle_time_s);
  if (const auto source = root.optional_member("source")) {
    if (!source->json().is_object()) root.fail("source", "must be an object");
    rec.source = source->json();
  }
  for (const JsonField& s : root.array("sensors")) {
    if (version >= 2) {
      s.expect_only({"id", "type", "x_m", "y_m", "yaw_rad", "reports"});
    } else {
      s.expect_only({"id", "type", "x_m", "y_m", "yaw_rad"});
    }
    using namespace limits;
    RecordingSensor sensor{s.string("id"), s.string("type"),
                           s.number_within("x_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m"),
                           s.number_within("y_m", -kMaxMountOffset_m, kMaxMountOffset_m, "m"),
                           s.angle_rad("yaw_rad", kMaxMountYaw_rad)};
    if (s.has("reports")) {
      const std::string reports = s.string("reports");
      if (reports == "detections") {
        sensor.reports = ReportedLevel::detections;
      } else if (reports != "tracks") {
        s.fail("reports", "must be \"tracks\" or \"detections\", got \"" + reports + "\"");
      }
    }
    if (sensor.id.empty()) s.fail("id", "must not be empty");
    if (rec.sensor_index(sensor.id) >= 0) s.fail("id", fmt::format("sensor '{}' is listed twice", sensor.id));
    rec.sensors.push_back(std::move(sensor));
  }
  if (rec.sensors.empty()) root.fail("sensors", "a recording needs at least one sensor");
  for (const JsonField& o : root.array("objects")) {
    o.expect_only({"id", "class", "length_m", "width_m"});
    RecordingObject object{o.string("id"), o.string("class"), o.number_within("length_m", 0.0, limits::kMaxSize_m, "m"),
                           o.number_within("width_m", 0.0, limits::kMaxSize_m, "m")};
    require_positive(o, "length_m", object.length_m);
    require_positive(o, "width_m", object.width_m);
    if (object.id.empty()) o.fail("id", "must not be empty");
    for (const RecordingObject& other : rec.objects) {
      if (other.id == object.id) o.fail("id", fmt::format("object '{}' is listed twice", object.id));
    }
    rec.objects.push_back(std::move(object));
  }
}

void write_file(const fs::path& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw InputError(path.string(), "", std::string("cannot create file: ") + std::strerror(errno));
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      ::close(fd);
      throw InputError(path.string(), "", std::string("write failed: ") + std::strerror(errno));
    }
    written += static_cast<std::size_t>(n);
  }
  ::fsync(fd);
  ::close(fd);
}

std::string header_text(const Recording& rec) {
  nlohmann::ordered_json json;
  // Version 2 only where a version 2 field is used, so that version 1 recordings are rewritten as they were.
  const bool v2 = !rec.all_sensors_report(ReportedLevel::tracks);
  json["format"] = "rcsim-recording";
  json["version"] = v2 ? 2 : 1;
  json["name"] = rec.name;
  if (!rec.description.empty()) json["description"] = rec.description;
  json["cycle_time_s"] = rec.cycle_time_s;
  json["sensors"] = nlohmann::ordered_json::array();
  for (const auto& s : rec.sensors) {
    json["sensors"].push_back({{"id", s.id}, {"type", s.type}, {"x_m", s.x_m}, {"y_m", s.y_m}, {"yaw_rad", s.yaw_rad}});
    if (v2) json["sensors"].back()["reports"] = s.reports == ReportedLevel::detections ? "detections" : "tracks";
  }
  json["objects"] = nlohmann::ordered_json::array();
  for (const auto& o : rec.objects) {
    json["objects"].push_back({{"id", o.id}, {"class", o.object_class}, {"length_m", o.length_m}, {"width_m", o.width_m}});
  }
  if (!rec.source.empty()) json["source"] = rec.source;
  return json.dump(2) + "\n";
}

}  // namespace

std::vector<EgoSample> read_ego_log(const fs::path& path) {
  std::vector<EgoSample> rows;
  EgoRowReader reader(path, 0.0);
  for (EgoSample s; reader.next(s);) rows.push_back(s);
  return rows;
}

bool Recording::all_sensors_report(ReportedLevel level) const {
  return std::all_of(sensors.begin(), sensors.end(), [&](const RecordingSensor& s) { return s.reports == level; });
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
  if (!fs::is_directory(dir)) throw InputError(dir.string(), "", "not a recording directory");
  Recording rec;
  rec.dir = dir;
  read_header(rec, dir / "recording.json");
  return rec;
}

std::uint64_t recording_checksum(const fs::path& dir) {
  std::uint64_t hash = fnv1a64("rcsim-recording/1");
  for (const char* name : {"recording.json", "ego.csv", "objects.csv", "targets.csv"}) {
    hash = fnv1a64_file(dir / name, hash);
  }
  return hash;
}

Recording read_recording(const fs::path& dir) {
  RecordingStream stream(dir);
  Recording rec = stream.header();
  rec.ego.reserve(static_cast<std::size_t>(rec.cycle_count()));
  for (EgoSample s; stream.ego().next(s);) rec.ego.push_back(s);
  rec.boxes.assign(rec.objects.size(), {});
  std::size_t object = 0;
  for (AnnotatedBox box; stream.boxes().next(object, box);) rec.boxes[object].push_back(box);
  stream.boxes().finish();
  for (int k = 0; k < rec.cycle_count(); ++k) stream.targets().read_cycle(k, rec.ego[k].t_s, rec.targets);
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

void write_recording(const fs::path& dir, const Recording& rec, const std::map<std::string, std::string>& extra_files) {
  const fs::path target = fs::absolute(dir).lexically_normal();
  const fs::path name = target.filename().empty() ? target.parent_path().filename() : target.filename();
  const fs::path parent = target.filename().empty() ? target.parent_path().parent_path() : target.parent_path();
  if (!fs::is_directory(parent)) throw InputError(dir.string(), "", "the parent directory does not exist");
  check_output_directory(target, "recording.json");
  // Ids go into CSV rows, one row per line: what the reader could not read back is not written.
  for (const auto& id : ids_of(rec)) {
    if (const auto bad = find_control_character(id)) {
      throw std::invalid_argument(fmt::format("the id '{}' holds {}: a recording's ids are one line", id, *bad));
    }
  }
  const fs::path temp = parent / fmt::format(".{}.tmp.{}", name.string(), ::getpid());
  fs::remove_all(temp);
  fs::create_directory(temp);
  try {
    write_file(temp / "recording.json", header_text(rec));

    std::string ego = "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
    for (const auto& e : rec.ego) {
      fmt::format_to(std::back_inserter(ego), "{:.6f},{:.4f},{:.4f},{:.6f},{:.4f},{:.6f}\n", e.t_s, e.x_m, e.y_m,
                     e.yaw_rad, e.speed_mps, e.yaw_rate_radps);
    }
    write_file(temp / "ego.csv", ego);

    // Rows in time order, objects in recording order within one time.
    std::vector<std::pair<std::size_t, const AnnotatedBox*>> rows;
    for (std::size_t i = 0; i < rec.boxes.size(); ++i) {
      for (const auto& b : rec.boxes[i]) rows.emplace_back(i, &b);
    }
    std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second->t_s < b.second->t_s; });
    std::string objects = "t_s,object,x_m,y_m,yaw_rad,speed_mps\n";
    for (const auto& [i, b] : rows) {
      fmt::format_to(std::back_inserter(objects), "{:.6f},{},{:.4f},{:.4f},{:.6f},{:.4f}\n", b->t_s,
                     csv_field(rec.objects[i].id), b->x_m, b->y_m, b->yaw_rad, b->speed_mps);
    }
    write_file(temp / "objects.csv", objects);

    // The id column only when the sensors report track ids (raw detections have none).
    const bool ids = std::any_of(rec.targets.begin(), rec.targets.end(), [](const RecordedTarget& t) { return t.id >= 0; });
    // The optional columns only where some target has the value.
    const auto any = [&](double RecordedTarget::*field) {
      return std::any_of(rec.targets.begin(), rec.targets.end(), [&](const RecordedTarget& t) { return std::isfinite(t.*field); });
    };
    const bool rcs = any(&RecordedTarget::rcs_dbsm), snr = any(&RecordedTarget::snr_db),
               elevation = any(&RecordedTarget::elevation_rad);
    // A column holds a number in every row (the reader refuses empty fields and nan).
    for (const auto& t : rec.targets) {
      if ((rcs && !std::isfinite(t.rcs_dbsm)) || (snr && !std::isfinite(t.snr_db)) ||
          (elevation && !std::isfinite(t.elevation_rad))) {
        throw std::invalid_argument("targets.csv: an optional column (rcs_dbsm, snr_db, elevation_rad) is given for "
                                    "some targets only");
      }
    }
    std::string targets = ids ? "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db"
                              : "t_s,cycle,sensor,range_m,azimuth_rad,range_rate_mps,amplitude_db";
    targets += std::string(rcs ? ",rcs_dbsm" : "") + (snr ? ",snr_db" : "") + (elevation ? ",elevation_rad" : "") + "\n";
    for (const auto& t : rec.targets) {
      fmt::format_to(std::back_inserter(targets), "{:.6f},{},{},", t.t_s, t.cycle, csv_field(rec.sensors[t.sensor].id));
      if (ids) fmt::format_to(std::back_inserter(targets), "{},", t.id);
      fmt::format_to(std::back_inserter(targets), "{:.4f},{:.6f},{:.4f},{:.3f}", t.range_m, t.azimuth_rad,
                     t.range_rate_mps, t.amplitude_db);
      if (rcs) fmt::format_to(std::back_inserter(targets), ",{:.3f}", t.rcs_dbsm);
      if (snr) fmt::format_to(std::back_inserter(targets), ",{:.3f}", t.snr_db);
      if (elevation) fmt::format_to(std::back_inserter(targets), ",{:.6f}", t.elevation_rad);
      targets += '\n';
    }
    write_file(temp / "targets.csv", targets);
    for (const auto& [file, content] : extra_files) write_file(temp / fs::path(file).filename(), content);

    // A directory cannot be renamed over a non-empty one: move the old one aside first.
    const fs::path old = parent / fmt::format(".{}.old.{}", name.string(), ::getpid());
    const bool replacing = fs::exists(target);
    if (replacing) fs::rename(target, old);
    fs::rename(temp, target);
    if (replacing) fs::remove_all(old);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temp, ignored);
    throw;
  }
}

}  // namespace rcsim
