#include "stream/cycle_source.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "common/input_error.hpp"
#include "io/recording_stream.hpp"
#include "model/model_library.hpp"
#include "replay/import/streaming_import.hpp"
#include "scene/scene.hpp"
#include "sim/target_list_writer.hpp"

namespace rcsim::stream {
namespace {

WireLevel list_level(ListLevel level) {
  switch (level) {
    case ListLevel::detections: return WireLevel::detections;
    case ListLevel::tracks: return WireLevel::tracks;
    case ListLevel::ideal: break;
  }
  throw std::invalid_argument("the ideal level is not streamed (its rows name objects and reflectors); use tracks or detections");
}



WirePose wire_pose(const BodyState& body) {
  return {body.X_WB.x_m, body.X_WB.y_m, body.X_WB.yaw_rad, body.heading_speed_mps()};
}

// The simulated target list of every sensor of `simulation` after its latest cycle.
void add_simulated(const Simulation& simulation, const Scene& scene, std::uint32_t cycle, const SourceOptions& options,
                   CycleFrame& frame) {
  const WireLevel level = list_level(options.simulation.level);
  for (std::size_t s = 0; s < simulation.sensor_count(); ++s) {
    TargetListMessage message;
    message.cycle = cycle;
    message.sensor_index = static_cast<std::uint16_t>(s);
    message.level = level;
    message.sensor_id = scene.sensors[s].id;
    message.elevation = rows_carry_elevation(scene);  // as `rcsim simulate` writes its rows
    const SensorCycleState& state = simulation.sensor_state(s);
    if (level == WireLevel::tracks) {
      for (const ReportedTarget& r : state.reported) {
        message.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db, r.elevation_rad});
      }
    } else {
      // The detections level numbers its rows 0, 1, 2, … (schemas/target-list.md).
      for (std::size_t i = 0; i < state.detections.size(); ++i) {
        const Detection& d = state.detections[i];
        message.targets.push_back(
            {static_cast<std::int32_t>(i), d.range_m, d.azimuth_rad, d.range_rate_mps, d.amplitude_db, d.elevation_rad});
      }
    }
    frame.messages.push_back({MessageType::simulated_targets, message.sensor_index,
                              encode_target_list(message, options.max_datagram_bytes)});
  }
}

void check_sensor_count(std::size_t count) {
  if (count > 0xFFFF) throw std::invalid_argument("more sensors than the wire format numbers (65535)");
}

class SceneSource final : public CycleSource {
 public:
  SceneSource(Scene scene, const SourceOptions& options) : scene_(std::move(scene)), options_(options) {
    check_sensor_count(scene_.sensors.size());
    list_level(options_.simulation.level);
    for (const auto& s : scene_.sensors) sensor_ids_.push_back(s.id);
    restart();
  }
  int cycle_count() const override { return scene_.cycle_count(); }
  std::uint32_t available_messages() const override { return kSimulatedBit | kTruthBit; }
  const std::vector<std::string>& sensor_ids() const override { return sensor_ids_; }
  int next_cycle() const override { return next_; }

  void seek(int cycle) override {
    if (cycle < 0 || cycle > cycle_count()) throw std::out_of_range("seek beyond the scene");
    if (cycle < next_) restart();
    // The tracker needs every cycle in order: run the skipped ones without encoding them.
    for (; next_ < cycle; ++next_) simulation_->run_cycle(next_);
  }

  CycleFrame produce() override {
    const int k = next_++;
    simulation_->run_cycle(k);
    CycleFrame frame;
    frame.cycle = static_cast<std::uint32_t>(k);
    frame.t_s = scene_.cycle_time_at(k);
    frame.timestamp_ns = to_timestamp_ns(frame.t_s);
    add_simulated(*simulation_, scene_, frame.cycle, options_, frame);
    GroundTruthMessage truth;
    truth.cycle = frame.cycle;
    truth.ego = wire_pose(simulation_->snapshot().ego);
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
      const SceneObject& object = scene_.objects[o];
      if (!object.present_at(frame.t_s)) continue;
      truth.objects.push_back({static_cast<std::uint32_t>(o), wire_pose(simulation_->object_state(o)),
                               object.model.length_m, object.model.width_m, object.id});
    }
    frame.messages.push_back({MessageType::ground_truth, 0, encode_ground_truth(truth, options_.max_datagram_bytes)});
    return frame;
  }

 private:
  void restart() {
    simulation_ = std::make_unique<Simulation>(scene_, options_.simulation);
    next_ = 0;
  }
  Scene scene_;
  SourceOptions options_;
  std::vector<std::string> sensor_ids_;
  std::unique_ptr<Simulation> simulation_;
  int next_ = 0;
};

// A recording streamed as `rcsim replay` reads it (replay/import/streaming_import.hpp): its rows
// are read, smoothed and simulated cycle by cycle, so memory does not grow with its length. The
// ground truth (the raw annotated boxes and ego rows, not the smoothed ones the simulation sees)
// is read alongside by readers of its own, a few rows at a time.
class RecordingSource final : public CycleSource {
 public:
  RecordingSource(std::filesystem::path dir, const SourceOptions& options)
      : dir_(std::move(dir)), options_(options), library_(ModelLibrary::builtin()) {
    list_level(options_.simulation.level);
    if (read_recording_header(dir_).clock == Clock::per_sensor) {
      // A frame on the wire is one cycle of every sensor, with the ego row of that cycle.
      throw InputError((dir_ / "recording.json").string(), "clock",
                       "the sensors run on their own clocks (\"per_sensor\"); rcsim stream sends one shared cycle "
                       "of every sensor per frame: replay this recording with rcsim replay");
    }
    restart();
    const Recording& header = input_->recording();
    check_sensor_count(header.sensors.size());
    cycle_count_ = header.cycle_count();
    for (const auto& s : header.sensors) sensor_ids_.push_back(s.id);
  }
  int cycle_count() const override { return cycle_count_; }
  std::uint32_t available_messages() const override { return kSimulatedBit | kRecordedBit | kTruthBit; }
  const std::vector<std::string>& sensor_ids() const override { return sensor_ids_; }
  int next_cycle() const override { return next_; }

  void seek(int cycle) override {
    if (cycle < 0 || cycle > cycle_count()) throw std::out_of_range("seek beyond the recording");
    if (cycle < next_) restart();
    while (next_ < cycle) advance();
  }

  CycleFrame produce() override {
    advance();  // read => smooth => simulate
    const Recording& header = input_->recording();
    CycleFrame frame;
    frame.cycle = static_cast<std::uint32_t>(next_ - 1);
    frame.t_s = t_rec_s_;
    frame.timestamp_ns = to_timestamp_ns(frame.t_s);
    // Recorded lists first: they are what the real sensor said in this cycle.
    for (std::size_t s = 0; s < header.sensors.size(); ++s) {
      TargetListMessage message;
      message.cycle = frame.cycle;
      message.sensor_index = static_cast<std::uint16_t>(s);
      message.level = WireLevel::recorded;
      message.sensor_id = header.sensors[s].id;
      // Recorded elevations go out where the scene's simulated lists carry them too; a target the
      // recording has none for (no elevation_rad column) is sent with 0.
      message.elevation = rows_carry_elevation(input_->scene());
      for (const RecordedTarget& r : recorded_) {
        if (r.sensor != static_cast<int>(s)) continue;
        const double elevation_rad = message.elevation && std::isfinite(r.elevation_rad) ? r.elevation_rad : 0.0;
        message.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db, elevation_rad});
      }
      frame.messages.push_back({MessageType::recorded_targets, message.sensor_index,
                                encode_target_list(message, options_.max_datagram_bytes)});
    }
    add_simulated(*simulation_, input_->scene(), frame.cycle, options_, frame);
    frame.messages.push_back({MessageType::ground_truth, 0, encode_ground_truth(truth(frame.cycle), options_.max_datagram_bytes)});
    return frame;
  }

 private:
  // The next cycle read and simulated; its recorded targets in recorded_, its time in t_rec_s_.
  void advance() {
    int cycle = 0, all_sensors = -1;
    if (!input_->next_cycle(cycle, t_rec_s_, all_sensors, recorded_)) throw std::logic_error("a recording streamed beyond its last cycle");
    if (const auto window = input_->take_moved_window()) simulation_->cull_within(window->first, window->second);
    simulation_->run_at(t_rec_s_ - input_->imported().time_offset_s);
    next_ = cycle + 1;
  }

  void restart() {
    simulation_.reset();  // it refers to the old import's scene
    input_ = std::make_unique<replay::StreamingImport>(dir_, library_, replay::ImportOptions{});
    const Recording& header = input_->recording();
    truth_ego_ = std::make_unique<EgoRowReader>(dir_ / "ego.csv", EgoLogSpacing{header.cycle_time_s});
    truth_boxes_ = std::make_unique<BoxRowReader>(dir_ / "objects.csv", header.objects);
    truth_ego_cycle_ = 0;
    boxes_ahead_.clear();
    boxes_done_ = false;
    simulation_ = std::make_unique<Simulation>(input_->scene(), options_.simulation);
    next_ = 0;
  }

  // The annotation as recorded: the ego row of the cycle and every box annotated at its time
  // (within 1 µs: the files carry 6 decimals). Rows are in time order, so the boxes of earlier
  // times are dropped and those beyond it wait for the next cycle.
  GroundTruthMessage truth(std::uint32_t cycle) {
    constexpr double kSameTimeS = 1e-6;
    EgoSample ego;
    for (; truth_ego_cycle_ <= cycle; ++truth_ego_cycle_) {  // past the cycles a seek skipped
      if (!truth_ego_->next(ego)) throw std::logic_error("ego.csv ended before its cycles");
    }
    GroundTruthMessage message;
    message.cycle = cycle;
    message.ego = {ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps};
    const auto beyond = [&ego](const AnnotatedBox& b) { return b.t_s > ego.t_s && std::abs(b.t_s - ego.t_s) > kSameTimeS; };
    while (!boxes_done_ && (boxes_ahead_.empty() || !beyond(boxes_ahead_.back().second))) {
      std::pair<std::size_t, AnnotatedBox> row;
      if (truth_boxes_->next(row.first, row.second)) boxes_ahead_.push_back(row);
      else boxes_done_ = true;
    }
    while (!boxes_ahead_.empty() && boxes_ahead_.front().second.t_s < ego.t_s - kSameTimeS) boxes_ahead_.pop_front();
    // Each object's first box from ego.t_s - 1 µs on, if it lies within 1 µs; in object order.
    std::vector<std::pair<std::size_t, const AnnotatedBox*>> at_time;
    for (const auto& [o, box] : boxes_ahead_) at_time.emplace_back(o, &box);
    std::stable_sort(at_time.begin(), at_time.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    at_time.erase(std::unique(at_time.begin(), at_time.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                  at_time.end());
    std::erase_if(at_time, [&ego](const auto& a) { return std::abs(a.second->t_s - ego.t_s) > kSameTimeS; });
    const Recording& header = input_->recording();
    for (const auto& [o, box] : at_time) {
      const RecordingObject& object = header.objects[o];
      message.objects.push_back({static_cast<std::uint32_t>(o), {box->x_m, box->y_m, box->yaw_rad, box->speed_mps},
                                 object.length_m, object.width_m, object.id});
    }
    return message;
  }

  std::filesystem::path dir_;
  SourceOptions options_;
  ModelLibrary library_;
  std::vector<std::string> sensor_ids_;
  int cycle_count_ = 0;
  std::unique_ptr<replay::StreamingImport> input_;
  std::unique_ptr<EgoRowReader> truth_ego_;
  std::uint32_t truth_ego_cycle_ = 0;  // the cycle of truth_ego_'s next row
  std::unique_ptr<BoxRowReader> truth_boxes_;
  std::deque<std::pair<std::size_t, AnnotatedBox>> boxes_ahead_;  // read, not yet older than the cycle
  bool boxes_done_ = false;
  std::unique_ptr<Simulation> simulation_;
  std::vector<RecordedTarget> recorded_;  // of the cycle last advanced to
  double t_rec_s_ = 0.0;
  int next_ = 0;
};

}  // namespace

std::int64_t to_timestamp_ns(double t_s) {
  if (!std::isfinite(t_s) || std::abs(t_s) > 9.2e9) throw std::invalid_argument("source time out of range");
  return std::llround(t_s * 1e9);
}

std::unique_ptr<CycleSource> make_scene_source(Scene scene, const SourceOptions& options) {
  return std::make_unique<SceneSource>(std::move(scene), options);
}

std::unique_ptr<CycleSource> open_source(const std::filesystem::path& path, const SourceOptions& options) {
  if (std::filesystem::is_directory(path)) return std::make_unique<RecordingSource>(path, options);
  return std::make_unique<SceneSource>(load_scene_file(path.string(), ModelLibrary::builtin()), options);
}

}  // namespace rcsim::stream
