#pragma once
// One stored run as an MCAP file that Foxglove opens with no set-up (schemas/mcap-replay.md):
// recorded and simulated targets per sensor coloured by class, the annotated boxes, the ego and
// the sensors' mountings as transforms, the view fields, and each cycle's figures to plot. JSON
// messages under Foxglove's own schema names (foxglove.SceneUpdate, foxglove.FrameTransform),
// the figures under rcsim.CycleFigures, every schema written as JSON Schema.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "replay/store/report_database.hpp"

namespace rcsim::replay {

struct McapReplayCounts {
  std::uint64_t messages = 0, bytes = 0;
  int cycles = 0, sensors = 0;
};

// The export's clock: the run's (seconds since the recording's start, from 1970), or the log's
// (the recording's source.first_timestamp_ns added: the export overlays the original log).
enum class McapClock { run, log };

// Writes run `run_id` of `db` to `out`. A run stored with --store summary has no targets, boxes
// or sensor poses: its file holds the view fields, the mountings and the figures. On sensors' own
// clocks each sensor's targets are written at its own cycles only, kept until its next. With
// McapClock::log, a run whose recording names no first_timestamp_ns (not imported from a log) is
// refused (std::invalid_argument).
McapReplayCounts write_run_mcap(ReportDatabase& db, std::int64_t run_id, std::ostream& out, McapClock clock = McapClock::run);

// "/rcsim/FRAME/WHAT" (recorded, simulated, view_field, figures), "/rcsim/WHAT" without a frame.
std::string mcap_replay_topic(const std::string& frame, const std::string& what);

}  // namespace rcsim::replay
