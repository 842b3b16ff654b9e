// The streamer of a recording reads it as rcsim replay does, cycle by cycle (issue 21: memory
// flat over a long drive). Its frames must be byte-identical to those of the recording read
// whole, imported whole and simulated (the path it replaces, kept here as the oracle), on every
// bundled recording, also across seeks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/import/importer.hpp"
#include "stream/cycle_source.hpp"

namespace rcsim::stream {
namespace {

namespace fs = std::filesystem;

// The frames of a recording read whole: recorded lists, simulated lists, annotated boxes.
class WholeRecording {
 public:
  WholeRecording(const fs::path& dir, const SourceOptions& options)
      : rec_(read_recording(dir)), options_(options), library_(ModelLibrary::builtin()) {
    imported_ = replay::import_recording(rec_, library_, replay::ImportOptions{});
    scene_ = replay::build_scene(imported_, library_, rec_.dir.string());
    simulation_ = std::make_unique<Simulation>(scene_, options_.simulation);
  }

  CycleFrame frame(int k) {
    CycleFrame frame;
    const EgoSample& ego = rec_.ego[static_cast<std::size_t>(k)];
    frame.cycle = static_cast<std::uint32_t>(k);
    frame.t_s = ego.t_s;
    frame.timestamp_ns = to_timestamp_ns(ego.t_s);
    for (std::size_t s = 0; s < rec_.sensors.size(); ++s) {
      TargetListMessage m = list(k, s, WireLevel::recorded);
      for (const RecordedTarget& r : rec_.targets) {
        if (r.cycle == k && r.sensor == static_cast<int>(s)) m.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db});
      }
      frame.messages.push_back({MessageType::recorded_targets, m.sensor_index, encode_target_list(m, options_.max_datagram_bytes)});
    }
    simulation_->run_at(ego.t_s - imported_.time_offset_s);
    const bool tracks = options_.simulation.level == ListLevel::tracks;
    for (std::size_t s = 0; s < rec_.sensors.size(); ++s) {
      TargetListMessage m = list(k, s, tracks ? WireLevel::tracks : WireLevel::detections);
      const SensorCycleState& state = simulation_->sensor_state(s);
      if (tracks) {
        for (const ReportedTarget& r : state.reported) m.targets.push_back({r.id, r.range_m, r.azimuth_rad, r.range_rate_mps, r.amplitude_db});
      } else {
        for (std::size_t i = 0; i < state.detections.size(); ++i) {
          const Detection& d = state.detections[i];
          m.targets.push_back({static_cast<std::int32_t>(i), d.range_m, d.azimuth_rad, d.range_rate_mps, d.amplitude_db});
        }
      }
      frame.messages.push_back({MessageType::simulated_targets, m.sensor_index, encode_target_list(m, options_.max_datagram_bytes)});
    }
    GroundTruthMessage truth;
    truth.cycle = frame.cycle;
    truth.ego = {ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps};
    for (std::size_t o = 0; o < rec_.objects.size(); ++o) {
      const auto& boxes = rec_.boxes[o];
      const auto it = std::lower_bound(boxes.begin(), boxes.end(), ego.t_s - 1e-6,
                                       [](const AnnotatedBox& b, double t_s) { return b.t_s < t_s; });
      if (it == boxes.end() || std::abs(it->t_s - ego.t_s) > 1e-6) continue;
      truth.objects.push_back({static_cast<std::uint32_t>(o), {it->x_m, it->y_m, it->yaw_rad, it->speed_mps},
                               rec_.objects[o].length_m, rec_.objects[o].width_m, rec_.objects[o].id});
    }
    frame.messages.push_back({MessageType::ground_truth, 0, encode_ground_truth(truth, options_.max_datagram_bytes)});
    return frame;
  }

  int cycle_count() const { return rec_.cycle_count(); }
  std::size_t target_rows() const { return rec_.targets.size(); }

 private:
  TargetListMessage list(int k, std::size_t s, WireLevel level) const {
    TargetListMessage m;
    m.cycle = static_cast<std::uint32_t>(k);
    m.sensor_index = static_cast<std::uint16_t>(s);
    m.level = level;
    m.sensor_id = rec_.sensors[s].id;
    return m;
  }
  Recording rec_;
  SourceOptions options_;
  ModelLibrary library_;
  replay::ImportedScene imported_;
  Scene scene_;
  std::unique_ptr<Simulation> simulation_;
};

void expect_same_frame(const CycleFrame& streamed, const CycleFrame& whole, const std::string& where) {
  ASSERT_EQ(streamed.cycle, whole.cycle) << where;
  EXPECT_EQ(streamed.t_s, whole.t_s) << where;
  EXPECT_EQ(streamed.timestamp_ns, whole.timestamp_ns) << where;
  ASSERT_EQ(streamed.messages.size(), whole.messages.size()) << where;
  for (std::size_t m = 0; m < whole.messages.size(); ++m) {
    EXPECT_EQ(streamed.messages[m].type, whole.messages[m].type) << where << ", message " << m;
    EXPECT_EQ(streamed.messages[m].sensor_index, whole.messages[m].sensor_index) << where << ", message " << m;
    ASSERT_EQ(streamed.messages[m].fragments, whole.messages[m].fragments) << where << ", message " << m;
  }
}

std::vector<fs::path> bundled_recordings() {
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic")) {
    if (fs::exists(entry.path() / "recording.json")) dirs.push_back(entry.path());
  }
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

TEST(RecordingSource, StreamsEveryBundledRecordingByteIdenticalToTheRecordingReadWhole) {
  const auto dirs = bundled_recordings();
  ASSERT_GE(dirs.size(), 8u);
  std::size_t frames = 0, targets = 0, truth_objects = 0;
  for (const fs::path& dir : dirs) {
    SourceOptions options;
    options.simulation.seed = 21;
    WholeRecording whole(dir, options);
    auto streamed = open_source(dir, options);
    ASSERT_EQ(streamed->cycle_count(), whole.cycle_count()) << dir;
    for (int k = 0; k < whole.cycle_count(); ++k, ++frames) {
      const CycleFrame a = streamed->produce(), b = whole.frame(k);
      expect_same_frame(a, b, dir.filename().string() + ", cycle " + std::to_string(k));
      if (::testing::Test::HasFatalFailure()) return;
      for (const Bytes& fragment : b.messages.back().fragments) {
        GroundTruthFragment truth;
        ASSERT_EQ(decode_ground_truth(fragment, truth), DecodeError::none);
        truth_objects += truth.message.objects.size();
      }
    }
    targets += whole.target_rows();
  }
  std::cout << "[ figures  ] " << dirs.size() << " recordings, " << frames << " cycles, " << targets
            << " recorded targets, " << truth_objects << " annotated boxes: every frame identical\n";
  EXPECT_GT(truth_objects, frames);  // the boxes are there, not only the ego
}

TEST(RecordingSource, SeeksAndDetectionsAndSmallDatagramsStayIdentical) {
  // The city drive: 60 s, so the streamed import's window moves; seeks forward and back re-read.
  const fs::path dir = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "city_drive_60s";
  SourceOptions options;
  options.simulation.seed = 4;
  options.simulation.level = ListLevel::detections;
  options.max_datagram_bytes = 400;  // lists and ground truth in several fragments
  auto streamed = open_source(dir, options);
  const auto check = [&](std::initializer_list<std::pair<int, int>> spans) {
    for (const auto& [from, to] : spans) {
      WholeRecording whole(dir, options);
      for (int k = 0; k < from; ++k) whole.frame(k);  // the tracker needs every cycle in order
      streamed->seek(from);
      EXPECT_EQ(streamed->next_cycle(), from);
      for (int k = from; k < to; ++k) {
        expect_same_frame(streamed->produce(), whole.frame(k), "cycle " + std::to_string(k));
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  };
  check({{0, 30}, {700, 720}, {5, 10}, {1480, 1501}});
  EXPECT_EQ(streamed->next_cycle(), 1501);
  EXPECT_THROW(streamed->seek(1502), std::out_of_range);
}

}  // namespace
}  // namespace rcsim::stream
