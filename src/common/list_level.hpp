#pragma once
// What a target list holds, one word everywhere: a sensor profile's `reports`, a recording's
// sensors, `rcsim simulate --level`, what a replay compares. The ideal targets of the geometry
// (Fig. 13's input), the raw detections of each cycle (today's radars' detection interfaces), or
// the tracks confirmed by the sensor's own tracker (paper III-E).
namespace rcsim {

enum class ListLevel { ideal, detections, tracks };

inline const char* list_level_name(ListLevel level) {
  switch (level) {
    case ListLevel::ideal: return "ideal";
    case ListLevel::detections: return "detections";
    case ListLevel::tracks: return "tracks";
  }
  return "tracks";
}

}  // namespace rcsim
