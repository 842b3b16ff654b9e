#pragma once
// One shard of a planned campaign (`rcsim campaign run-shard`, what each Slurm array task runs):
// its recordings replayed one after the other into the shard's own report. Restartable: a run
// is stored in one transaction, and a run whose identity (replay/store/run_identity.hpp) the
// shard's report holds already is skipped, so a task killed or preempted and run again redoes
// only the runs it had not finished.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "replay/campaign/plan.hpp"
#include "replay/store/report_database.hpp"

namespace rcsim::replay::campaign {

struct ShardOutcome {
  int stored = 0;   // replayed and stored now
  int skipped = 0;  // stored by an earlier attempt
  std::vector<std::string> failures;  // "DIR: what went wrong", one per recording that failed
};

// Runs the shard into `plan.shard_report(shard)`, one line per recording on `log`. A recording
// that fails (bad input) is reported and the others still run.
ShardOutcome run_shard(const CampaignPlan& plan, int shard, std::ostream& log);

// Writes the campaign's name, manifest and criteria into a report that has none; refuses one of
// another campaign (the shards of two campaigns never mix), naming the file.
void claim_report_for_campaign(ReportDatabase& db, const std::string& db_path, const CampaignManifest& manifest);

}  // namespace rcsim::replay::campaign
