#include "stream/cycle_source.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/import/importer.hpp"
#include "scene/scene.hpp"

namespace rcsim::stream {
namespace {

ListLevel list_level(OutputLevel level) {
  switch (level) {
    case OutputLevel::detections: return ListLevel::detections;
    case OutputLevel::tracks: return ListLevel::tracks;
    case OutputLevel::ideal: break;
  }
  throw std::invalid_argument("the ideal level is not streamed (its rows name objects and reflectors); use tracks or detections");
}

// Along-heading speed of a body, as the recordings write it.
double heading_speed_mps(const BodyState& body) {
  return body.v_WB_W.dot(Vec2(std::cos(body.X_WB.yaw_rad), std::sin(body.X_WB.yaw_rad)));
}

WirePose wire_pose(const BodyState& body) {
  return {body.X_WB.x_m, body.X_WB.y_m, body.X_WB.yaw_rad, heading_speed_mps(body)};
}

// The simulated target list of every sensor of `simulation` after its latest cycle.
void add_simulated(const Simulation& simulation, const Scene& scene, std::uint32_t cycle, const SourceOptions& options,
                   CycleFrame& frame) {
  const ListLevel level = list_level(options.simulation.level);
  for (std::size_t s = 0; s < simulation.sensor_count(); ++s) {
    TargetListMessage message;
    message.cycle = cycle;
    message.sensor_index = static_cast<std::uint16_t>(s);
    message.level = level;
    message.sensor_id = scene.sensors[s].id;
    const SensorCycleState& state = simulation.sensor_state(s);
    if (level == ListLevel::tracks) {
      for (const ReportedTarget& r : state.reported) {
        message.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db});
      }
    } else {
      // The detections level numbers its rows 0, 1, 2, … (schemas/target-list.md).
      for (std::size_t i = 0; i < state.detections.size(); ++i) {
        const Detection& d = state.detections[i];
        message.targets.push_back({static_cast<std::int32_t>(i), d.range_m, d.azimuth_rad, d.range_rate_mps, d.amplitude_db});
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
  double time_s(int cycle) const override { return scene_.cycle_time_at(cycle); }
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
    frame.t_s = time_s(k);
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

class RecordingSource final : public CycleSource {
 public:
  RecordingSource(Recording recording, const SourceOptions& options)
      : recording_(std::move(recording)), options_(options) {
    check_sensor_count(recording_.sensors.size());
    list_level(options_.simulation.level);
    const ModelLibrary library = ModelLibrary::builtin();
    imported_ = replay::import_recording(recording_, library, replay::ImportOptions{});
    scene_ = replay::build_scene(imported_, library, recording_.dir.string());
    for (const auto& s : recording_.sensors) sensor_ids_.push_back(s.id);
    // targets.csv is in cycle order: where each cycle's rows begin.
    cycle_begin_.assign(static_cast<std::size_t>(recording_.cycle_count()) + 1, recording_.targets.size());
    for (std::size_t i = recording_.targets.size(); i-- > 0;) {
      const int c = recording_.targets[i].cycle;
      if (c >= 0 && c < recording_.cycle_count()) cycle_begin_[static_cast<std::size_t>(c)] = i;
    }
    for (std::size_t k = cycle_begin_.size() - 1; k-- > 0;) cycle_begin_[k] = std::min(cycle_begin_[k], cycle_begin_[k + 1]);
    restart();
  }
  int cycle_count() const override { return recording_.cycle_count(); }
  double time_s(int cycle) const override { return recording_.ego[static_cast<std::size_t>(cycle)].t_s; }
  std::uint32_t available_messages() const override { return kSimulatedBit | kRecordedBit | kTruthBit; }
  const std::vector<std::string>& sensor_ids() const override { return sensor_ids_; }
  int next_cycle() const override { return next_; }

  void seek(int cycle) override {
    if (cycle < 0 || cycle > cycle_count()) throw std::out_of_range("seek beyond the recording");
    if (cycle < next_) restart();
    for (; next_ < cycle; ++next_) simulation_->run_at(scene_time_s(next_));
  }

  CycleFrame produce() override {
    const int k = next_++;
    CycleFrame frame;
    frame.cycle = static_cast<std::uint32_t>(k);
    frame.t_s = time_s(k);
    frame.timestamp_ns = to_timestamp_ns(frame.t_s);
    // Recorded lists first: they are what the real sensor said in this cycle.
    for (std::size_t s = 0; s < recording_.sensors.size(); ++s) {
      TargetListMessage message;
      message.cycle = frame.cycle;
      message.sensor_index = static_cast<std::uint16_t>(s);
      message.level = ListLevel::recorded;
      message.sensor_id = recording_.sensors[s].id;
      for (std::size_t i = cycle_begin_[static_cast<std::size_t>(k)]; i < cycle_begin_[static_cast<std::size_t>(k) + 1]; ++i) {
        const RecordedTarget& r = recording_.targets[i];
        if (r.cycle != k || r.sensor != static_cast<int>(s)) continue;
        message.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db});
      }
      frame.messages.push_back({MessageType::recorded_targets, message.sensor_index,
                                encode_target_list(message, options_.max_datagram_bytes)});
    }
    simulation_->run_at(scene_time_s(k));
    add_simulated(*simulation_, scene_, frame.cycle, options_, frame);
    frame.messages.push_back({MessageType::ground_truth, 0, encode_ground_truth(truth_at(k), options_.max_datagram_bytes)});
    return frame;
  }

 private:
  double scene_time_s(int cycle) const { return time_s(cycle) - imported_.time_offset_s; }
  void restart() {
    simulation_ = std::make_unique<Simulation>(scene_, options_.simulation);
    next_ = 0;
  }
  // The annotation: the ego row of the cycle and every box annotated at its time.
  GroundTruthMessage truth_at(int k) const {
    const EgoSample& ego = recording_.ego[static_cast<std::size_t>(k)];
    GroundTruthMessage truth;
    truth.cycle = static_cast<std::uint32_t>(k);
    truth.ego = {ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps};
    constexpr double kSameTimeS = 1e-6;  // the files carry 6 decimals
    for (std::size_t o = 0; o < recording_.objects.size(); ++o) {
      const auto& boxes = recording_.boxes[o];
      const auto it = std::lower_bound(boxes.begin(), boxes.end(), ego.t_s - kSameTimeS,
                                       [](const AnnotatedBox& b, double t_s) { return b.t_s < t_s; });
      if (it == boxes.end() || std::abs(it->t_s - ego.t_s) > kSameTimeS) continue;
      const RecordingObject& object = recording_.objects[o];
      truth.objects.push_back({static_cast<std::uint32_t>(o), {it->x_m, it->y_m, it->yaw_rad, it->speed_mps},
                               object.length_m, object.width_m, object.id});
    }
    return truth;
  }

  Recording recording_;
  SourceOptions options_;
  replay::ImportedScene imported_;
  Scene scene_;
  std::vector<std::string> sensor_ids_;
  std::vector<std::size_t> cycle_begin_;
  std::unique_ptr<Simulation> simulation_;
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
  if (std::filesystem::is_directory(path)) return std::make_unique<RecordingSource>(read_recording(path), options);
  return std::make_unique<SceneSource>(load_scene_file(path.string(), ModelLibrary::builtin()), options);
}

}  // namespace rcsim::stream
