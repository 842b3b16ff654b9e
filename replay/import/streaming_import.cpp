#include "replay/import/streaming_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/angles.hpp"
#include "replay/import/annotation_smoothing.hpp"

namespace rcsim::replay {

namespace {

constexpr double kWindowStep_s = 4.0;    // the trajectories grow by this much at a time
constexpr double kKeepBehind_s = 1.0;    // samples kept behind the replayed time
constexpr double kPresenceKept_s = 10.0;  // presence spans kept after they end
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Absent until a box says otherwise (an empty presence list would mean "always").
const std::vector<TimeInterval> kNotYetPresent{{kInfinity, kInfinity}};

TrajectorySample ego_sample(const EgoSample& e, double t0_s) {
  TrajectorySample s;
  s.t_s = e.t_s - t0_s;  // as import_recording's ego_trajectory
  s.x_m = e.x_m;
  s.y_m = e.y_m;
  s.yaw_rad = e.yaw_rad;
  s.speed_mps = e.speed_mps;
  s.yaw_rate_radps = e.yaw_rate_radps;
  return s;
}

template <class T>
void erase_front(std::vector<T>& v, std::size_t n) {
  v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
}

}  // namespace

StreamingImport::StreamingImport(const std::filesystem::path& dir, const ModelLibrary& library,
                                 const ImportOptions& options)
    : stream_(std::make_unique<RecordingStream>(dir)), options_(options) {
  EgoSample first;
  stream_->ego().next(first);  // refuses an ego log without rows
  imported_ = import_header(stream_->header(), first.t_s, library, options);
  imported_.duration_s = (stream_->header().cycle_count() - 1) * stream_->header().cycle_time_s;  // nominal
  scene_ = build_scene(imported_, library, dir.string());
  for (SceneObject& object : scene_.objects) object.presence = kNotYetPresent;
  objects_.resize(scene_.objects.size());
  scene_.ego.append(ego_sample(first, imported_.time_offset_s));
  own_clocks_ = stream_->header().clock == Clock::per_sensor;
  first_ego_rec_s_ = first.t_s;
  if (!own_clocks_) cycle_times_rec_s_.push_back(first.t_s);
  front_rec_s_ = -kInfinity;
  // A time t is final once the boxes are read beyond t + this: the segment holding t has its
  // later node within max_gap, that node's fit needs the boxes within ±half window of it, and
  // whether a gap follows that node is known max_gap after it.
  lookahead_s_ = 2.0 * options.max_gap_s + std::max(options.smoothing_half_window_s, 0.0) +
                 2.0 * imported_.cycle_time_s + 0.01;
  window_until_s_ = -kInfinity;
}

void StreamingImport::warn(std::string text) {
  if (imported_.warnings.size() < ImportedScene::kMaxWarnings) {
    imported_.warnings.push_back(std::move(text));
  } else {
    ++imported_.warnings_not_kept;
  }
}

void StreamingImport::add_box(std::size_t o, const AnnotatedBox& box) {
  ObjectFeed& f = objects_[o];
  const double t0_s = imported_.time_offset_s, half_cycle_s = 0.5 * imported_.cycle_time_s;
  const double t_s = box.t_s - t0_s;
  double yaw_rad = box.yaw_rad;
  if (f.presence.empty()) {  // the object's first box
    f.presence.push_back({box.t_s - t0_s - half_cycle_s, 0.0});
  } else {
    const double previous_t_rec_s = f.t_rec_s.back();
    const double gap_s = box.t_s - previous_t_rec_s;
    if (gap_s > options_.max_gap_s) {
      warn(annotation_gap_warning(stream_->boxes_path(), f.line.back(), box.line, imported_.objects[o].id, gap_s, true));
      f.presence.back().until_s = previous_t_rec_s - t0_s + half_cycle_s;
      if (f.next_fit < f.t_s.size()) f.gap_after.back() = 1;  // else appended with its gap already
      f.presence.push_back({box.t_s - t0_s - half_cycle_s, 0.0});
    } else if (gap_s > 1.5 * imported_.cycle_time_s) {
      warn(annotation_gap_warning(stream_->boxes_path(), f.line.back(), box.line, imported_.objects[o].id, gap_s, false));
    }
    // Unwrapped, so that the fit never sees a jump of 2π.
    yaw_rad = f.yaw_rad.back() + angle_difference_rad(box.yaw_rad, f.last_raw_yaw_rad);
  }
  f.t_rec_s.push_back(box.t_s);
  f.t_s.push_back(t_s);
  f.x_m.push_back(box.x_m);
  f.y_m.push_back(box.y_m);
  f.yaw_rad.push_back(yaw_rad);
  f.speed_mps.push_back(box.speed_mps);
  f.line.push_back(box.line);
  f.gap_after.push_back(0);
  f.last_raw_yaw_rad = box.yaw_rad;
  f.presence.back().until_s = t_s + half_cycle_s;
}

void StreamingImport::fit_ready(std::size_t o) {
  ObjectFeed& f = objects_[o];
  const double h = options_.smoothing_half_window_s;
  const double front_s = front_rec_s_ - imported_.time_offset_s;
  const std::array<const double*, 4> series{f.x_m.data(), f.y_m.data(), f.yaw_rad.data(), f.speed_mps.data()};
  std::array<LocalFit, 4> fits;
  const std::size_t n = f.t_s.size();
  while (f.next_fit < n) {
    const std::size_t i = f.next_fit;
    // Every box within the window is read once a later row lies beyond it (rows in time order).
    const bool window_read = boxes_done_ || front_s - f.t_s[i] > h;
    const bool gap_known = i + 1 < n || boxes_done_ || front_rec_s_ - f.t_rec_s[i] > options_.max_gap_s;
    if (!window_read || !gap_known) break;
    if (i + 1 == n && !boxes_done_) f.gap_after[i] = 1;  // a later box, if any, follows a gap
    while (f.t_s[i] - f.t_s[f.window_first] > h) ++f.window_first;
    f.window_last = std::max(f.window_last, i + 1);
    while (f.window_last < n && f.t_s[f.window_last] - f.t_s[i] <= h) ++f.window_last;
    fit_local_quadratic(f.t_s, series, i, f.window_first, f.window_last, h, fits);
    TrajectorySample s;
    s.t_s = f.t_s[i];
    s.x_m = fits[0].value;
    s.y_m = fits[1].value;
    s.yaw_rad = fits[2].value;
    s.speed_mps = fits[3].value;
    s.yaw_rate_radps = fits[2].slope_per_s;
    s.gap_after = f.gap_after[i] != 0;
    scene_.objects[o].trajectory.append(s);
    ++f.next_fit;
  }
}

void StreamingImport::read_ahead(double horizon_s) {
  const double t0_s = imported_.time_offset_s;
  while (!ego_done_ && scene_.ego.end_s() <= horizon_s) {
    EgoSample e;
    if (!stream_->ego().next(e)) {
      ego_done_ = true;
      break;
    }
    scene_.ego.append(ego_sample(e, t0_s));
    if (!own_clocks_) cycle_times_rec_s_.push_back(e.t_s);
  }
  while (!boxes_done_ && front_rec_s_ - t0_s <= horizon_s + lookahead_s_) {
    std::size_t object = 0;
    AnnotatedBox box;
    if (!stream_->boxes().next(object, box)) {
      boxes_done_ = true;
      stream_->boxes().finish();
      break;
    }
    add_box(object, box);
    front_rec_s_ = box.t_s;
  }
  for (std::size_t o = 0; o < objects_.size(); ++o) {
    fit_ready(o);
    scene_.objects[o].presence = objects_[o].presence.empty() ? kNotYetPresent : objects_[o].presence;
  }
}

void StreamingImport::forget_before(double t_s) {
  scene_.ego.drop_before(t_s);
  for (std::size_t o = 0; o < objects_.size(); ++o) {
    scene_.objects[o].trajectory.drop_before(t_s);
    ObjectFeed& f = objects_[o];
    const std::size_t unused = std::min(f.window_first, f.next_fit);
    if (unused > 0 && 2 * unused >= f.t_s.size()) {
      for (auto* v : {&f.t_rec_s, &f.t_s, &f.x_m, &f.y_m, &f.yaw_rad, &f.speed_mps}) erase_front(*v, unused);
      erase_front(f.line, unused);
      erase_front(f.gap_after, unused);
      f.next_fit -= unused;
      f.window_first -= unused;
      f.window_last -= unused;
    }
    // Spans long over are forgotten, never the last one (a box may still extend it).
    while (f.presence.size() > 1 && f.presence.front().until_s < t_s - kPresenceKept_s) {
      f.presence.erase(f.presence.begin());
    }
  }
}

bool StreamingImport::next_cycle(int& cycle, double& t_rec_s, int& sensor, std::vector<RecordedTarget>& targets) {
  const int cycles = stream_->header().cycle_count();
  if (next_cycle_ >= cycles) {
    if (!boxes_done_ || !ego_done_) read_ahead(kInfinity);  // the rest is read for its checks
    stream_->targets().finish();
    if (own_clocks_) stream_->cycles()->finish();
    return false;
  }
  sensor = -1;
  if (own_clocks_) {  // the sensor's own cycle, the ego log interpolated to it
    SensorCycle c;
    if (!stream_->cycles()->next(c)) throw std::logic_error("cycles.csv ended before its counted rows");
    t_rec_s = c.t_s;
    sensor = c.sensor;
  } else {
    if (cycle_times_rec_s_.empty()) read_ahead(scene_.ego.end_s());
    t_rec_s = cycle_times_rec_s_.front();
    cycle_times_rec_s_.pop_front();
  }
  const double t_s = t_rec_s - imported_.time_offset_s;
  if (t_s > window_until_s_) {
    window_until_s_ = t_s + kWindowStep_s;
    read_ahead(window_until_s_);
    forget_before(t_s - kKeepBehind_s);
    moved_window_ = std::pair{t_s, window_until_s_};
  }
  if (own_clocks_) {
    // The window reads the ego log beyond t unless it ended before: then t may lie beyond its last
    // row by the margin alone.
    const double last_ego_rec_s = ego_done_ ? scene_.ego.end_s() + imported_.time_offset_s : kInfinity;
    stream_->cycles()->check_within_ego_log(first_ego_rec_s_, last_ego_rec_s);
  }
  cycle = next_cycle_++;
  targets.clear();
  stream_->targets().read_cycle(cycle, t_rec_s, sensor, targets);
  return true;
}

std::optional<std::pair<double, double>> StreamingImport::take_moved_window() {
  auto moved = moved_window_;
  moved_window_.reset();
  return moved;
}

}  // namespace rcsim::replay
