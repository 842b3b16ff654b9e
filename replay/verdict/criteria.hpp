#pragma once
// Pass/fail criteria on the stored figures, and the verdicts they give (schemas/campaign.md,
// "Criteria"). A criterion bounds one figure (run_figures.hpp) from above or below, either per
// recording (every run must pass) or over the campaign (a statistic of the runs' values). A figure
// a run lacks fails its criterion unless the criterion says `"if_missing": "pass"`. Criteria live
// in a campaign manifest or an `rcsim-criteria` document, and in the report database (table
// `criteria`), from which every verdict is computed when it is needed.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/json_reader.hpp"
#include "replay/verdict/run_figures.hpp"
#include "replay/store/campaign_store.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::verdict {

enum class Scope { recording, campaign };
enum class Statistic { value, mean, median, p95, min, max };  // value: per recording
enum class Bound { max, min };  // max: passes if the figure <= threshold; min: if >= threshold

struct Criterion {
  std::string figure;
  Scope scope = Scope::recording;
  Statistic statistic = Statistic::value;
  Bound bound = Bound::max;
  double threshold = 0.0;
  bool pass_if_missing = false;
  // The kind of run it judges (the default tolerances, default_criteria.hpp); nullopt: every run.
  // Files cannot set it: one --criteria file judges the runs it is given.
  std::optional<ListLevel> kind = std::nullopt;

  // "gospa_mean_m <= 1.5" or "mean gospa_mean_m over the campaign <= 1.2".
  std::string text() const;
  friend bool operator==(const Criterion&, const Criterion&) = default;
};

// The `criteria` array of a manifest or criteria document (`document`). An entry may give both
// "min" and "max" (two criteria). Errors name the file and the field (criteria[2].figure).
std::vector<Criterion> parse_criteria(const JsonField& document);

// An `rcsim-criteria` v1 document, or the criteria of an `rcsim-campaign` manifest.
std::vector<Criterion> read_criteria_file(const std::filesystem::path& path);

// The criteria stored in a report database (in order), and replacing them.
std::vector<Criterion> stored_criteria(ReportDatabase& db);
void store_criteria(ReportDatabase& db, const std::vector<Criterion>& criteria);

// The criteria as the table criteria holds them (replay/store/campaign_store.hpp), and back.
std::vector<CriterionRow> criterion_rows(const std::vector<Criterion>& criteria);
std::vector<Criterion> criteria_from_rows(const std::vector<CriterionRow>& rows);

struct CriterionResult {
  std::size_t criterion = 0;  // index into Verdicts::criteria
  std::optional<double> value;
  bool passed = false;
};

struct RunVerdict {
  std::int64_t run_id = 0;
  std::string recording_name, recording_dir;
  ListLevel kind = ListLevel::tracks;
  std::int64_t seed = 0;
  double duration_s = 0.0;
  double wall_s = 0.0;
  bool passed = true;
  std::vector<CriterionResult> results;  // the per-recording criteria, in order
};

// Where the criteria of a verdict come from: the default tolerances of each kind of run
// (docs/verdicts.md), a --criteria file, or the report's own (a campaign's manifest, or the file
// of an earlier --criteria).
enum class CriteriaSource { defaults, file, report };

struct Verdicts {
  CriteriaSource source = CriteriaSource::report;
  bool gate = true;  // a failure sets the exit status (3); the default tolerances only where asked for
  std::vector<Criterion> criteria;
  std::vector<RunVerdict> runs;             // by run id
  std::vector<CriterionResult> campaign;    // the campaign criteria, in order
  int runs_failed = 0;
  bool passed() const;
};

// Judges the runs of the database by the criteria: all of them, with the campaign criteria over
// all; or the one run given (rcsim replay), by the per-recording criteria alone. A criterion of
// a kind judges the runs of that kind only.
Verdicts judge(ReportDatabase& db, const std::vector<Criterion>& criteria,
               std::optional<std::int64_t> only_run = std::nullopt);

// The results of one run grouped by figure, in the criteria's order: a figure bounded from
// below and above (two criteria) is one row, "0.8 .. 1.25". What the verdict blocks print.
struct FigureVerdict {
  std::string figure;
  std::optional<double> value;
  std::optional<double> min, max;
  bool passed = true;
  std::string tolerance() const;  // "<= 1", ">= 0.5", "0.8 .. 1.25"
};
std::vector<FigureVerdict> figure_verdicts(const Verdicts& verdicts, const RunVerdict& run);

// "gospa_mean_m = 1.73 > 1.5" or "latency_difference_mean_s missing".
std::string describe_failure(const Criterion& criterion, const CriterionResult& result);

}  // namespace rcsim::replay::verdict
