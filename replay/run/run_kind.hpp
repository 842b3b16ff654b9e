#pragma once
// What a run compares, by what its recording reports (schemas/report-database.md, runs.level):
// confirmed tracks, or raw detections. It chooses a run's default tolerances
// (replay/verdict/default_criteria.hpp, docs/verdicts.md) and what the report calls its targets.
#include <string>
#include <string_view>

#include "io/recording.hpp"

namespace rcsim::replay {

// runs.level of a recording: "detections" where every sensor reports detections, "tracks" where
// every sensor reports tracks, "mixed" otherwise.
std::string run_level_of(const Recording& recording);

// What a stored run compares (tracks or detections, never ideal): detections for the levels
// "detections" and "mixed" (a recording with any sensor of raw detections has a background drawn
// from a density). Runs stored before the level was written (always "tracks" then) are
// detections where they were simulated without a tracker.
ListLevel compared_level(std::string_view level, std::string_view fidelity_level);

}  // namespace rcsim::replay
