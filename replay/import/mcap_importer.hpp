#pragma once
// A drive logged as MCAP (ROS 2 bags since Iron, or MCAP directly) as an rcsim recording:
// `rcsim import --from mcap LOG.mcap --mapping MAPPING.json -o RECORDING_DIR` (docs/importers.md).
// The mapping file (`rcsim-mcap-mapping` v1, schemas/mcap-mapping.md) says which topic carries
// which radar's detections, with its mounting and profile, which the ego motion and which the
// annotated boxes. Read:
//   detections  radar_msgs/msg/RadarScan (CDR): one message one sensor cycle at its header stamp;
//   ego         nav_msgs/msg/Odometry (CDR): pose in its frame, speed and yaw rate in the vehicle's;
//   boxes       foxglove.SceneUpdate (JSON): an entity's first cube, its class from the entity's
//               metadata `class`, its speed from `speed_mps` (else from the boxes' positions);
//               or an ASAM OpenLABEL file beside the log (openlabel.hpp);
//   ego         or a chain of /tf transforms (tf_tree.hpp), the radars' mountings from /tf_static.
// Every sensor runs on its own clock (recording v4): its cycles are its messages' stamps, the ego
// log and the boxes keep their own rates. Chunks uncompressed, zstd or lz4 (io/mcap_reader.hpp).
#include <filesystem>

#include "replay/import/dataset_importer.hpp"

namespace rcsim::replay {

// Two passes over the log: the first surveys it (the clock, the sensors' cycle times and frames,
// the objects' classes and sizes, the ego log, which is held: 48 B a pose), the second streams
// the scans and boxes in time order through a 2 s window into the rows. Memory stays flat in the
// length of the log but for the ego log (and an OpenLABEL file or a /tf tree, read whole).
DatasetRecording import_mcap(const std::filesystem::path& log, const DatasetImportOptions& options);

// The same recording written straight into `dir` (io/recording_writer.hpp): an hour's scans and
// boxes are never held.
ImportSummary import_mcap_to(const std::filesystem::path& log, const DatasetImportOptions& options, const std::filesystem::path& dir);

}  // namespace rcsim::replay
