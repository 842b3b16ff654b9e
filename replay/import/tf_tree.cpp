#include "replay/import/tf_tree.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

namespace rcsim::replay {
namespace {

constexpr std::int64_t kHoldMargin_ns = static_cast<std::int64_t>(TfTree::kHoldMargin_s * 1e9);

Eigen::Isometry3d isometry(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = t;
  return X;
}

}  // namespace

void TfTree::add(const std::vector<ros2::TransformStamped>& transforms, bool is_static) {
  for (const ros2::TransformStamped& tf : transforms) {
    const Eigen::Quaterniond q(tf.qw, tf.qx, tf.qy, tf.qz);
    if (!(q.norm() > 0.5 && q.norm() < 2.0)) {
      throw TfError(fmt::format("the transform of '{}' in '{}' has a rotation of norm {} (no unit quaternion)", tf.child_frame_id,
                                tf.header.frame_id, q.norm()));
    }
    if (tf.child_frame_id == tf.header.frame_id) throw TfError(fmt::format("frame '{}' is posed in itself", tf.child_frame_id));
    auto [it, added] = edges_.try_emplace(tf.child_frame_id);
    Edge& edge = it->second;
    if (added) {
      edge.parent = tf.header.frame_id, edge.is_static = is_static;
    } else if (edge.parent == tf.header.frame_id && edge.is_static != is_static) {
      throw TfError(fmt::format("the transform of '{}' in '{}' comes both on the static topic and the moving one", tf.child_frame_id,
                                edge.parent));
    } else if (edge.parent != tf.header.frame_id) {
      throw TfError(fmt::format("frame '{}' has two parents: '{}'{} and '{}'{}", tf.child_frame_id, edge.parent,
                                edge.is_static ? " (static)" : "", tf.header.frame_id, is_static ? " (static)" : ""));
    }
    const Sample sample{tf.header.stamp.ns(), Eigen::Vector3d(tf.x_m, tf.y_m, tf.z_m), q.normalized()};
    if (is_static) {
      edge.samples.assign(1, sample);  // the latest static transform holds
    } else {
      edge.samples.push_back(sample);
    }
  }
}

void TfTree::finish() {
  for (auto& [frame, edge] : edges_) {
    std::vector<Sample>& s = edge.samples;
    std::stable_sort(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.t_ns < b.t_ns; });
    s.erase(std::unique(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.t_ns == b.t_ns; }), s.end());
  }
}

Eigen::Isometry3d TfTree::edge_pose(const std::string& frame, const Edge& edge, std::int64_t t_ns) const {
  const std::vector<Sample>& samples = edge.samples;
  if (edge.is_static || samples.size() == 1) {
    if (!edge.is_static && std::abs(t_ns - samples.front().t_ns) > kHoldMargin_ns) {
      throw TfError(fmt::format("the transform of '{}' in '{}' is known only at {} ns, {:.3f} s from {} ns", frame, edge.parent,
                                samples.front().t_ns, static_cast<double>(t_ns - samples.front().t_ns) * 1e-9, t_ns));
    }
    return isometry(samples.front().t, samples.front().q);
  }
  if (t_ns < samples.front().t_ns - kHoldMargin_ns || t_ns > samples.back().t_ns + kHoldMargin_ns) {
    throw TfError(fmt::format("the transform of '{}' in '{}' is known from {} to {} ns, not at {} ns (held at most {} s beyond)", frame,
                              edge.parent, samples.front().t_ns, samples.back().t_ns, t_ns, kHoldMargin_s));
  }
  const auto after = std::lower_bound(samples.begin(), samples.end(), t_ns, [](const Sample& s, std::int64_t t) { return s.t_ns < t; });
  if (after == samples.begin()) return isometry(after->t, after->q);
  if (after == samples.end()) return isometry(samples.back().t, samples.back().q);
  const Sample& a = *(after - 1);
  const Sample& b = *after;
  const double f = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  return isometry(a.t + f * (b.t - a.t), a.q.slerp(f, b.q));
}

std::vector<std::string> TfTree::ancestors(const std::string& frame) const {
  std::vector<std::string> up{frame};
  for (auto it = edges_.find(frame); it != edges_.end(); it = edges_.find(it->second.parent)) {
    if (std::find(up.begin(), up.end(), it->second.parent) != up.end()) {
      throw TfError(fmt::format("the frames form a loop: {} -> {}", fmt::join(up, " -> "), it->second.parent));
    }
    if (up.size() > kMaxChainDepth) {
      throw TfError(fmt::format("the chain from '{}' up to its root holds more than {} transforms (schemas/limits.md)", frame, kMaxChainDepth));
    }
    up.push_back(it->second.parent);
  }
  return up;
}

std::pair<std::vector<std::string>, std::vector<std::string>> TfTree::chain(const std::string& frame, const std::string& reference) const {
  for (const std::string& f : {frame, reference}) {
    if (!has_frame(f)) throw TfError(fmt::format("no transform names frame '{}' (the frames: {})", f, fmt::join(frames(), ", ")));
  }
  std::vector<std::string> up = ancestors(frame), down = ancestors(reference);
  if (up.back() != down.back()) {
    throw TfError(fmt::format("no chain of transforms joins '{}' and '{}' (one ends at '{}', the other at '{}')", frame, reference,
                              up.back(), down.back()));
  }
  // Drop the common ancestors from both ends: what is left meets right below them.
  while (!up.empty() && !down.empty() && up.back() == down.back()) up.pop_back(), down.pop_back();
  return {up, down};
}

Eigen::Isometry3d TfTree::pose(const std::string& frame, const std::string& reference, std::int64_t t_ns) const {
  const auto [up, down] = chain(frame, reference);
  // frame in the common ancestor, and reference in it: frame in reference.
  Eigen::Isometry3d X_A_frame = Eigen::Isometry3d::Identity(), X_A_reference = Eigen::Isometry3d::Identity();
  for (const std::string& f : up) X_A_frame = edge_pose(f, edges_.at(f), t_ns) * X_A_frame;
  for (const std::string& f : down) X_A_reference = edge_pose(f, edges_.at(f), t_ns) * X_A_reference;
  return X_A_reference.inverse() * X_A_frame;
}

std::vector<std::int64_t> TfTree::chain_stamps(const std::string& frame, const std::string& reference) const {
  const auto [up, down] = chain(frame, reference);
  const Edge* densest = nullptr;
  std::int64_t from_ns = std::numeric_limits<std::int64_t>::min(), to_ns = std::numeric_limits<std::int64_t>::max();
  for (const auto* frames_of_chain : {&up, &down}) {
    for (const std::string& f : *frames_of_chain) {
      const Edge& edge = edges_.at(f);
      if (edge.is_static) continue;
      from_ns = std::max(from_ns, edge.samples.front().t_ns - kHoldMargin_ns);
      to_ns = std::min(to_ns, edge.samples.back().t_ns + kHoldMargin_ns);
      if (densest == nullptr || edge.samples.size() > densest->samples.size()) densest = &edge;
    }
  }
  std::vector<std::int64_t> stamps;
  if (densest == nullptr) return stamps;
  for (const Sample& s : densest->samples) {
    if (s.t_ns >= from_ns && s.t_ns <= to_ns) stamps.push_back(s.t_ns);
  }
  return stamps;
}

bool TfTree::has_frame(const std::string& frame) const {
  if (edges_.count(frame)) return true;
  return std::any_of(edges_.begin(), edges_.end(), [&](const auto& e) { return e.second.parent == frame; });
}

std::vector<std::string> TfTree::frames() const {
  std::vector<std::string> names;
  for (const auto& [child, edge] : edges_) names.push_back(child), names.push_back(edge.parent);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

}  // namespace rcsim::replay
