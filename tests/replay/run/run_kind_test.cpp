// What a run compares (replay/run/run_kind.hpp): runs.level from a recording's sensors, and the
// compared level read back from a stored level and fidelity, case by case.
#include "replay/run/run_kind.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rcsim::replay::run_kind_test {

// A recording header whose sensors report `levels`, one sensor each.
Recording recording_reporting(const std::vector<ListLevel>& levels) {
  Recording r;
  r.name = "levels";
  for (std::size_t i = 0; i < levels.size(); ++i) {
    RecordingSensor s;
    s.id = std::string("s").append(std::to_string(i));
    s.type = "srr24";
    s.reports = levels[i];
    r.sensors.push_back(s);
  }
  return r;
}

TEST(RunKind, TheLevelIsTracksOrDetectionsOnlyWhereEverySensorAgrees) {
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::tracks})), "tracks");
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::tracks, ListLevel::tracks})), "tracks");
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::detections, ListLevel::detections})), "detections");
  // One sensor of each, in either order: mixed.
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::tracks, ListLevel::detections})), "mixed");
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::detections, ListLevel::tracks})), "mixed");
  // Ideal targets are neither level a run stores: mixed as well.
  EXPECT_EQ(run_level_of(recording_reporting({ListLevel::ideal})), "mixed");
}

TEST(RunKind, ARecordingWithoutSensorsCountsAsTracks) {
  // "every sensor reports tracks" holds vacuously, and tracks are asked first.
  EXPECT_EQ(run_level_of(recording_reporting({})), "tracks");
}

TEST(RunKind, TheComparedLevelOfEveryStoredLevelAndFidelity) {
  // detections and mixed compare detections whatever the fidelity (also an unset one, "").
  for (const char* fidelity : {"", "full", "no_tracking", "geometry"}) {
    EXPECT_EQ(compared_level("detections", fidelity), ListLevel::detections) << fidelity;
    EXPECT_EQ(compared_level("mixed", fidelity), ListLevel::detections) << fidelity;
  }
  // tracks (or a level this build does not know) compares tracks unless simulated without a tracker.
  EXPECT_EQ(compared_level("tracks", ""), ListLevel::tracks);
  EXPECT_EQ(compared_level("", "full"), ListLevel::tracks);
  EXPECT_EQ(compared_level("", "no_tracking"), ListLevel::detections);
  EXPECT_EQ(compared_level("Detections", "full"), ListLevel::tracks);  // the words are case-sensitive
}

}  // namespace rcsim::replay::run_kind_test
