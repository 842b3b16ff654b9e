#pragma once
// `rcsim simulate --format mcap`: a scene's simulated target lists as one MCAP file for Foxglove
// (schemas/mcap-replay.md, "Simulated scenes"): per sensor its targets at the chosen list level
// as spheres in its own frame, the scene's objects as boxes (their ground truth), the ego per
// cycle and the sensors' mountings as transforms, and the view fields; the same frames, topics and
// messages as an exported replay, so that one Foxglove layout shows both.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "common/list_level.hpp"
#include "io/mcap_writer.hpp"
#include "sim/target_list_writer.hpp"

namespace rcsim {

class McapTargetListWriter {
 public:
  McapTargetListWriter(std::ostream& out, const Scene& scene, ListLevel level);

  // Cycle `cycle` at scene time t_s: the ego, the boxes of the objects present, and each sensor's
  // targets (states in the scene's sensor order).
  void write_cycle(const Scene& scene, int cycle, double t_s, const std::vector<const SensorCycleState*>& states);
  // Returns the file's size in bytes.
  std::uint64_t finish();
  std::uint64_t messages() const { return messages_; }

 private:
  void message(std::uint16_t channel, std::uint64_t ns, const std::string& body);

  ListLevel level_;
  mcap::Writer writer_;
  std::uint16_t tf_channel_ = 0, boxes_channel_ = 0;
  std::vector<std::string> frames_;
  std::vector<std::uint16_t> target_channels_, view_field_channels_;
  std::uint64_t lifetime_ns_ = 0, messages_ = 0;
  bool static_written_ = false;
};

}  // namespace rcsim
