#pragma once
// The report's sections for real drives (docs/metrics.md): per annotated object (a table,
// detection rate against range, each object's targets in its own frame) and the stationary
// background the annotation leaves out (counts, range and azimuth distributions, W1 and KS).

#include <string>

#include "replay/store/report_reader.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::report {

// At most `max_pictures` objects are drawn in their own frame: those with the most recorded targets.
std::string object_section(ReportDatabase& db, const RunData& run, int max_pictures);
std::string background_section(ReportDatabase& db, const RunData& run);

}  // namespace rcsim::replay::report
