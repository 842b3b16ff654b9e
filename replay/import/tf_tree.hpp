#pragma once
// The transforms of a ROS 2 log's /tf and /tf_static (tf2_msgs/msg/TFMessage) as a tree of frames,
// each frame posed in its parent: static (/tf_static) or at stamped times (/tf), interpolated
// between them (translation linearly, rotation by slerp). `rcsim import --from mcap` reads the ego
// from it (the vehicle's frame in a world frame, through any chain of frames, e.g.
// odom -> base_footprint -> base_link) and the radars' mountings (a radar's frame in the vehicle's).
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/ros2_messages.hpp"

namespace rcsim::replay {

// A frame that has two parents, a chain that does not join two frames, or a time beyond what a
// moving transform covers: the message names the frames.
struct TfError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class TfTree {
 public:
  // How far beyond a moving transform's first or last stamp its end value is held (s).
  static constexpr double kHoldMargin_s = 0.1;
  // The most transforms a chain from a frame up to its tree's root may hold: a robot's tree is a
  // few frames deep; a log of 10^4 chained frames made each lookup walk them all (quadratic).
  static constexpr std::size_t kMaxChainDepth = 64;

  // Adds one message's transforms; a transform repeated at a stamp already held is ignored, as
  // tf2 does.
  void add(const std::vector<ros2::TransformStamped>& transforms, bool is_static);
  // Puts each moving transform's stamps in order once all are added; the queries below need it.
  void finish();

  // The pose of `frame` in `reference` at `t_ns`: p_reference = X * p_frame.
  Eigen::Isometry3d pose(const std::string& frame, const std::string& reference, std::int64_t t_ns) const;

  // The stamps at which the chain from `frame` up to `reference` is known anew: those of its
  // moving transform with the most stamps, within the span every moving transform of the chain
  // covers (to kHoldMargin_s); empty where the chain has no moving transform.
  std::vector<std::int64_t> chain_stamps(const std::string& frame, const std::string& reference) const;

  bool has_frame(const std::string& frame) const;
  std::vector<std::string> frames() const;

 private:
  struct Sample {
    std::int64_t t_ns;
    Eigen::Vector3d t;
    Eigen::Quaterniond q;
  };
  struct Edge {
    std::string parent;
    bool is_static = false;
    std::vector<Sample> samples;  // one where static; stamps increasing once finished
  };
  // The frame's pose in its parent at t_ns.
  Eigen::Isometry3d edge_pose(const std::string& frame, const Edge& edge, std::int64_t t_ns) const;
  // The frames from `frame` up to its tree's root, `frame` first.
  std::vector<std::string> ancestors(const std::string& frame) const;
  // The chain's frames from `frame` up to (excluding) `reference`, and from `reference` up to
  // (excluding) their common ancestor; throws if they share none.
  std::pair<std::vector<std::string>, std::vector<std::string>> chain(const std::string& frame, const std::string& reference) const;

  std::map<std::string, Edge> edges_;  // by child frame
};

}  // namespace rcsim::replay
