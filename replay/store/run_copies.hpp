#pragma once
// Copies of a stored run with its figures varied, as if many recordings had been replayed: what
// the campaign report's benchmark judges, ranks and plots (bench/make_campaign_db.cpp,
// docs/report.md "Campaign report"). Every table that refers to a run is copied, whatever its
// columns, so the copies are runs as the report reads them.
#include <cstdint>
#include <memory>
#include <string>

#include "replay/store/report_database.hpp"

namespace rcsim::replay {

// The source run's figures the generated criteria are set from.
struct SourceRunFigures {
  double gospa_mean_m = 0.0;
  double object_detection_rate_simulated = 0.0;
  double wasserstein1_range_m = 0.0;
};
SourceRunFigures source_run_figures(ReportDatabase& db, std::int64_t run_id);

// How one copy differs from its source: `quality` scales GOSPA, OSPA (by its square root) and the
// residuals, and (below) the matched targets; the rest as named.
struct RunVariation {
  double quality = 1.0;
  double amplitude_shift_db = 0.0;
  double simulated_targets_factor = 1.0;
  bool no_latency_pair = false;
  double latency_difference_s = 0.0;
  double time_factor = 1.0;  // simulate CPU and wall time
  double detection_factor = 1.0;  // the objects' simulated detections
  double distance_factor = 1.0;   // W1 (KS by its square root, at most 1)
};

// Writes the copies in one transaction, committed by commit().
class RunCopier {
 public:
  RunCopier(ReportDatabase& db, std::int64_t source_run);
  ~RunCopier();
  // The source run's rows of every table, under run id `id`.
  void copy(std::int64_t id);
  void rename(std::int64_t id, const std::string& recording_name, const std::string& recording_dir, std::int64_t seed,
              const std::string& checksum);
  void vary(std::int64_t id, const RunVariation& v);
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rcsim::replay
