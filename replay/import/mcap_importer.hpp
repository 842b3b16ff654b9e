#pragma once
// A drive logged as MCAP (ROS 2 bags since Iron, or MCAP directly) as an rcsim recording:
// `rcsim import --from mcap LOG.mcap --mapping MAPPING.json -o RECORDING_DIR` (docs/importers.md).
// The mapping file (`rcsim-mcap-mapping` v1, schemas/mcap-mapping.md) says which topic carries
// which radar's detections, with its mounting and profile, which the ego motion and which the
// annotated boxes. Read:
//   detections  radar_msgs/msg/RadarScan (CDR): one message one sensor cycle at its header stamp;
//   ego         nav_msgs/msg/Odometry (CDR): pose in its frame, speed and yaw rate in the vehicle's;
//   boxes       foxglove.SceneUpdate (JSON): an entity's first cube, its class from the entity's
//               metadata `class`, its speed from `speed_mps` (else from the boxes' positions).
// Every sensor runs on its own clock (recording v4): its cycles are its messages' stamps, the ego
// log and the boxes keep their own rates. Chunks uncompressed, zstd or lz4 (io/mcap_reader.hpp).
#include <filesystem>

#include "replay/import/dataset_importer.hpp"

namespace rcsim::replay {

DatasetRecording import_mcap(const std::filesystem::path& log, const DatasetImportOptions& options);

}  // namespace rcsim::replay
