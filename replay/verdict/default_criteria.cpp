#include "replay/verdict/default_criteria.hpp"

#include "common/json_reader.hpp"

namespace rcsim::replay::verdict {

namespace {

// Track-level recordings (confirmed tracks; the bundled recordings). All-target GOSPA first: with
// no statistical background it measures the model. 1 m is half the default cut-off c = 2 m.
constexpr std::string_view kTrackTolerances = R"({
  "format": "rcsim-criteria",
  "version": 1,
  "criteria": [
    {"figure": "gospa_mean_m", "max": 1.0},
    {"figure": "target_count_ratio", "min": 0.8, "max": 1.25},
    {"figure": "object_detection_rate_difference", "min": -0.15, "max": 0.15},
    {"figure": "latency_difference_mean_s", "min": -0.5, "max": 0.5, "if_missing": "pass"},
    {"figure": "merge_artefact_match_fraction", "min": 0.5, "if_missing": "pass"}
  ]
}
)";

// Detection-level recordings (raw detections; real drives). Object-target GOSPA first, then the
// goals aimotive_lrr was derived to (docs/sensor-profiles.md): object counts within 0.8-1.25,
// detection rates within 15 points, the background's density within 25 % and its range and
// azimuth distributions within a KS distance of 0.2.
constexpr std::string_view kDetectionTolerances = R"({
  "format": "rcsim-criteria",
  "version": 1,
  "criteria": [
    {"figure": "gospa_object_mean_m", "max": 2.0},
    {"figure": "object_target_count_ratio", "min": 0.8, "max": 1.25},
    {"figure": "object_detection_rate_difference", "min": -0.15, "max": 0.15},
    {"figure": "background_target_count_ratio", "min": 0.75, "max": 1.25, "if_missing": "pass"},
    {"figure": "kolmogorov_smirnov.background_range", "max": 0.2, "if_missing": "pass"},
    {"figure": "kolmogorov_smirnov.background_azimuth", "max": 0.2, "if_missing": "pass"}
  ]
}
)";

std::vector<Criterion> parse_defaults(ListLevel kind) {
  const std::string name = "default tolerances (" + std::string(list_level_name(kind)) + ")";
  const nlohmann::json doc = parse_json_text(std::string(default_criteria_document(kind)), name);
  std::vector<Criterion> out = parse_criteria(JsonField(doc, name, ""));
  for (Criterion& c : out) c.kind = kind;
  return out;
}

}  // namespace

std::string_view default_criteria_document(ListLevel kind) {
  return kind == ListLevel::detections ? kDetectionTolerances : kTrackTolerances;
}

const std::vector<Criterion>& default_criteria() {
  static const std::vector<Criterion> criteria = [] {
    std::vector<Criterion> out = parse_defaults(ListLevel::tracks);
    for (Criterion& c : parse_defaults(ListLevel::detections)) out.push_back(std::move(c));
    return out;
  }();
  return criteria;
}

Verdicts judge_report(ReportDatabase& db, std::optional<std::int64_t> only_run) {
  std::vector<Criterion> criteria = stored_criteria(db);
  const bool own = !criteria.empty();
  Verdicts verdicts = judge(db, own ? criteria : default_criteria(), only_run);
  verdicts.source = own ? CriteriaSource::report : CriteriaSource::defaults;
  verdicts.gate = own;
  return verdicts;
}

}  // namespace rcsim::replay::verdict
