#pragma once
// The HTML tables of the report, rendered from what html_report_data.hpp read. Every text
// from the database is escaped here; numbers carry their units in the header or the row.
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "replay/store/report_reader.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay::report {

std::string run_information_table(const RunData& run);
std::string summary_table(const RunData& run);
std::string sensor_table(const RunData& run);
// The objects' tables show at most this many objects (an imaging radar's recording annotates
// ~1,000): those with the most recorded targets, saying so.
inline constexpr std::size_t kMaxObjectRows = 50;
// The kMaxObjectRows objects (of run_objects and object_figures) with the most recorded targets
// over the sensors (ties: the first in the recording); all when there are no more.
std::set<int> objects_with_most_targets(const RunData& run);
// The annotated objects (at most kMaxObjectRows, with a note and the count per class).
std::string object_table(const RunData& run);
// The distribution distances of all targets, or (background) those of the stationary background;
// the object targets' offsets (object_offset_*) are in the objects' section (real_drive_sections).
std::string distance_table(const RunData& run, bool background = false);
std::string merge_artefact_table(const RunData& run);
std::string latency_table(const RunData& run);
// The metric and import parameters (runs.parameters, JSON) with their cited sources.
std::string parameter_table(const RunData& run);
// The recording's provenance and the sensor configurations, verbatim (escaped), folded.
std::string provenance_blocks(const RunData& run);
// Several runs side by side: one column per run, first what tells them apart (their labels).
std::string comparison_table(const std::vector<RunData>& runs, const std::map<std::int64_t, RunLabel>& labels);

}  // namespace rcsim::replay::report
