#include "replay/run/run_kind.hpp"

namespace rcsim::replay {

std::string run_level_of(const Recording& recording) {
  for (const ListLevel level : {ListLevel::tracks, ListLevel::detections}) {
    if (recording.all_sensors_report(level)) return list_level_name(level);
  }
  return "mixed";
}

ListLevel compared_level(std::string_view level, std::string_view fidelity_level) {
  if (level == "detections" || level == "mixed") return ListLevel::detections;
  return fidelity_level == "no_tracking" ? ListLevel::detections : ListLevel::tracks;
}

}  // namespace rcsim::replay
