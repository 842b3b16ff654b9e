#pragma once
// The default tolerances (docs/verdicts.md): what every run is judged by when neither a
// --criteria file nor the report (a campaign) gives criteria. One rcsim-criteria document per kind
// of run: a track-level recording is judged on all its targets, a detection-level one on its
// annotated objects and, as a distribution, its stationary background, which a model draws from a
// density and which can never match the recorded points one by one.
#include <string_view>
#include <vector>

#include "replay/verdict/criteria.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::verdict {

// The rcsim-criteria document of the default tolerances of one kind, as docs/verdicts.md shows it.
std::string_view default_criteria_document(ListLevel kind);

// The default tolerances of both kinds, each criterion tagged with its kind: tracks first.
const std::vector<Criterion>& default_criteria();

// The runs judged as rcsim report shows them (all, or the one given): by the report's own criteria
// (a campaign's, or a stored --criteria file's), else by the default tolerances of each run's kind.
Verdicts judge_report(ReportDatabase& db, std::optional<std::int64_t> only_run = std::nullopt);

}  // namespace rcsim::replay::verdict
