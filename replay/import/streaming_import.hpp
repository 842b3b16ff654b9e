#pragma once
// The import of rcsim replay, streamed: the recording is read alongside the replay
// (io/recording_stream.hpp), each object's annotated boxes are smoothed as they arrive by the
// batch importer's own local fit (annotation_smoothing.hpp), over the same sliding window, and
// the scene's trajectories grow ahead of the replayed time and forget what lies behind it. A
// time is evaluated only once every sample it depends on is final, so the scene evaluates exactly
// as import_recording's whole scene does; memory stays bounded whatever the drive's length.
#include <cstddef>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "io/recording_stream.hpp"
#include "replay/import/importer.hpp"

namespace rcsim::replay {

class StreamingImport {
 public:
  StreamingImport(const std::filesystem::path& dir, const ModelLibrary& library, const ImportOptions& options);

  const Recording& recording() const { return stream_->header(); }  // the header: no rows
  const ImportedScene& imported() const { return imported_; }  // no trajectories; warnings as found
  const Scene& scene() const { return scene_; }                // trajectories over a window

  // The next cycle: its index, recording time, the sensor whose cycle it is (-1: every sensor's,
  // a shared clock) and recorded targets (replacing `targets`); the scene then holds every sample
  // that times up to the current window's end need. False after the last cycle, once every file
  // has been read to its end and checked.
  bool next_cycle(int& cycle, double& t_rec_s, int& sensor, std::vector<RecordedTarget>& targets);
  // The scene-time window [from, until] the trajectories hold in full, when it has moved since
  // the last call (for the simulations' broad phase: Simulation::cull_within).
  std::optional<std::pair<double, double>> take_moved_window();

 private:
  // One object's annotation on its way into the scene: raw boxes (unwrapped yaw) from `base`,
  // those up to next_fit already in the scene.
  struct ObjectFeed {
    std::vector<double> t_rec_s, t_s, x_m, y_m, yaw_rad, speed_mps;
    std::vector<int> line;
    std::vector<char> gap_after;
    double last_raw_yaw_rad = 0.0;
    std::size_t next_fit = 0, window_first = 0, window_last = 0;
    std::vector<TimeInterval> presence;
  };
  void read_ahead(double horizon_s);
  void add_box(std::size_t object, const AnnotatedBox& box);
  void fit_ready(std::size_t object);
  void forget_before(double t_s);
  void warn(std::string text);

  std::unique_ptr<RecordingStream> stream_;
  ImportOptions options_;
  ImportedScene imported_;
  Scene scene_;
  std::vector<ObjectFeed> objects_;
  std::deque<double> cycle_times_rec_s_;  // a shared clock: ego rows read ahead, not yet replayed
  bool own_clocks_ = false;                // the sensors' cycles come from cycles.csv
  double first_ego_rec_s_ = 0.0;
  int next_cycle_ = 0;
  bool ego_done_ = false, boxes_done_ = false;
  double front_rec_s_;                     // the latest annotation time read
  double lookahead_s_;                     // how far beyond a time the annotation must be read
  double window_until_s_;                  // the trajectories hold scene times up to here in full
  std::optional<std::pair<double, double>> moved_window_;
};

}  // namespace rcsim::replay
