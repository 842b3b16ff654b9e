#pragma once
// The colours of targets and view fields, one palette for the report's pictures
// (replay/report/svg_*.cpp) and the MCAP files for Foxglove (schemas/mcap-replay.md).
namespace rcsim::colours {

inline constexpr const char* kRecorded = "#1f5fbf";    // blue: recorded targets of an annotated object
inline constexpr const char* kSimulated = "#d9480f";   // orange-red: simulated ones
inline constexpr const char* kBackground = "#868e96";  // grey: the stationary background, and the boxes
inline constexpr const char* kOther = "#0ca678";       // teal: other targets on no box
inline constexpr const char* kViewField = "#2b8a3e";   // green: sensors and their view fields
inline constexpr const char* kLabel = "#343a40";       // dark grey: box labels

}  // namespace rcsim::colours
