#pragma once
// What the streamer sends, one cycle at a time, already encoded: for a scene, the simulated
// target list of every sensor and the ground truth (ego pose, object boxes); for a recording,
// additionally the recorded target lists, with the re-simulation run at the recorded times (as
// `rcsim replay` does) and the annotated boxes as ground truth.
//
// A source is used by one thread (the streamer's producer). The sensor model's tracker carries
// state from cycle to cycle, so seeking backwards re-runs the simulation from the first cycle:
// a stream that seeks is byte-identical to one that does not.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sim/simulation.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::stream {

struct EncodedMessage {
  MessageType type = MessageType::simulated_targets;
  std::uint16_t sensor_index = 0;  // target lists only
  std::vector<Bytes> fragments;    // payloads (after the header), in fragment order
};

struct CycleFrame {
  std::uint32_t cycle = 0;
  double t_s = 0.0;               // source time: scene time, or recording time for a recording
  std::int64_t timestamp_ns = 0;  // t_s in ns, the header's timestamp
  std::vector<EncodedMessage> messages;
  std::uint64_t generation = 0;   // set by the producer; frames of an older seek are dropped
};

struct SourceOptions {
  SimulationOptions simulation;  // level tracks or detections; seed; noise
  std::size_t max_datagram_bytes = kMaxDatagramBytes;
};

class CycleSource {
 public:
  virtual ~CycleSource() = default;
  virtual int cycle_count() const = 0;
  // Message types this source has (kSimulatedBit | kTruthBit, plus kRecordedBit for recordings).
  virtual std::uint32_t available_messages() const = 0;
  virtual const std::vector<std::string>& sensor_ids() const = 0;
  // The next produce() gives `cycle` (0 ≤ cycle ≤ cycle_count()).
  virtual void seek(int cycle) = 0;
  // The next cycle, encoded; the position moves on by one. Requires next_cycle() < cycle_count().
  virtual CycleFrame produce() = 0;
  virtual int next_cycle() const = 0;
};

// A scene file (`rcsim-scene`) or a recording directory (`rcsim-recording`), by what `path` is.
// Bad input throws InputError.
std::unique_ptr<CycleSource> open_source(const std::filesystem::path& path, const SourceOptions& options);

std::unique_ptr<CycleSource> make_scene_source(Scene scene, const SourceOptions& options);

std::int64_t to_timestamp_ns(double t_s);

}  // namespace rcsim::stream
