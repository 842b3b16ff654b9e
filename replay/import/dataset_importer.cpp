#include "replay/import/dataset_importer.hpp"

#include <charconv>
#include <fmt/format.h>

#include "common/input_error.hpp"
#include "replay/import/aimotive_importer.hpp"
#include "replay/import/astyx_importer.hpp"
#include "replay/import/mcap_importer.hpp"
#include "replay/import/vod_importer.hpp"

namespace rcsim::replay {

const std::vector<DatasetImporter>& dataset_importers() {
  static const std::vector<DatasetImporter> importers{
      {"aimotive", "aiMotive Multimodal Dataset sequence (radar detections, 3D boxes, calibration)", import_aimotive, nullptr},
      {"astyx", "Astyx HiRes2019 frames (imaging radar point clouds, 3D boxes; snapshots, --frames)", import_astyx, nullptr},
      {"mcap", "an MCAP log or a ROS 2 bag directory (sqlite3 or mcap storage, split bags): radar_msgs/RadarScan, "
               "sensor_msgs/PointCloud2 or foxglove.PointCloud, nav_msgs/Odometry or /tf, foxglove.SceneUpdate or OpenLABEL; --mapping",
       import_mcap, import_mcap_to},
      {"rosbag2", "a ROS 2 bag directory (metadata.yaml): the same as --from mcap", import_mcap, import_mcap_to},
      {"vod", "View-of-Delft frames (ZF FRGen21 3+1D radar point clouds, KITTI boxes, calibration, poses; snapshots, --frames)",
       import_vod, nullptr},
  };
  return importers;
}

const DatasetImporter& find_dataset_importer(std::string_view name) {
  std::string known;
  for (const DatasetImporter& importer : dataset_importers()) {
    if (importer.name == name) return importer;
    known += (known.empty() ? "" : ", ") + std::string(importer.name);
  }
  throw InputError("--from", "", "unknown dataset '" + std::string(name) + "' (known: " + known + ")");
}

namespace {

// The largest frame number a --frames list may name: no dataset of single frames has more.
constexpr long long kMaxFrameNumber = 1'000'000'000;

long long frame_number(std::string_view list, std::string_view text) {
  long long value = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < 0 || value > kMaxFrameNumber) {
    throw InputError("--frames", "",
                     fmt::format("'{}' in '{}' is not a frame number (whole numbers 0 to {}; a list such as 0-199 or "
                                 "0-9,20)",
                                 text, list, kMaxFrameNumber));
  }
  return value;
}

}  // namespace

std::vector<FrameRange> parse_frame_list(std::string_view list) {
  if (list.empty()) throw InputError("--frames", "", "an empty list (give frames such as 0-199 or 0,4; without --frames, all)");
  std::vector<FrameRange> ranges;
  for (std::size_t begin = 0; begin <= list.size();) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string_view item = list.substr(begin, comma - begin);
    const std::size_t dash = item.find('-');
    FrameRange range;
    if (dash == std::string_view::npos) {
      range.first = range.last = frame_number(list, item);
    } else {
      range.first = frame_number(list, item.substr(0, dash));
      range.last = frame_number(list, item.substr(dash + 1));
      if (range.last < range.first) {
        throw InputError("--frames", "", fmt::format("'{}' in '{}' runs backwards (write {}-{})", item, list, range.last,
                                                     range.first));
      }
    }
    ranges.push_back(range);
    begin = comma + 1;
  }
  return ranges;
}

}  // namespace rcsim::replay
