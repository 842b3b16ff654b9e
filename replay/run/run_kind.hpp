#pragma once
// What a run compares, by what its recording reports (schemas/report-database.md, runs.level):
// confirmed tracks, or raw detections. It chooses a run's default tolerances
// (replay/verdict/default_criteria.hpp, docs/verdicts.md) and what the report calls its targets.
#include <string>
#include <string_view>

#include "io/recording.hpp"

namespace rcsim::replay {

enum class RunKind { tracks, detections };

// runs.level of a recording: "detections" where every sensor reports detections, "tracks" where
// every sensor reports tracks, "mixed" otherwise.
std::string run_level_of(const Recording& recording);

// A stored run's kind: detections for the levels "detections" and "mixed" (a recording with any
// sensor of raw detections has a background drawn from a density). Runs stored before the level
// was written (always "tracks" then) are detections where they were simulated without a tracker.
RunKind run_kind(std::string_view level, std::string_view fidelity_level);

// "tracks" or "detections".
std::string_view run_kind_name(RunKind kind);

}  // namespace rcsim::replay
