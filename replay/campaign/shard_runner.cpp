#include "replay/campaign/shard_runner.hpp"

#include <fmt/format.h>
#include <filesystem>
#include <ostream>
#include <map>

#include "common/input_error.hpp"
#include "io/recording_stream.hpp"
#include "model/model_library.hpp"
#include "replay/run/run_sink_wrapper.hpp"
#include "replay/store/campaign_store.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::replay::campaign {

void claim_report_for_campaign(ReportDatabase& db, const std::string& db_path, const CampaignManifest& manifest) {
  const auto stored = claim_campaign(db, manifest.name, manifest.document.dump(), verdict::criterion_rows(manifest.criteria));
  if (!stored) return;  // claimed now
  if (stored->name != manifest.name) {
    throw InputError(db_path, "campaign", fmt::format("holds the runs of campaign '{}', not '{}'", stored->name,
                                                      manifest.name));
  }
  if (verdict::criteria_from_rows(stored->criteria) != manifest.criteria) {
    throw InputError(db_path, "criteria", "holds other criteria than the campaign's manifest; plan into a new directory");
  }
}

ShardOutcome run_shard(const CampaignPlan& plan, int shard, std::ostream& log) {
  if (shard < 0 || shard >= static_cast<int>(plan.shards.size())) {
    throw InputError("--shard", std::to_string(shard),
                     fmt::format("the plan in {} has shards 0 to {}", plan.dir.string(), plan.shards.size() - 1));
  }
  const std::string db_path = plan.shard_report(shard).string();
  const auto db = open_report_database(db_path, true);
  claim_report_for_campaign(*db, db_path, plan.manifest);
  // A planned recording is stored when a run of the same identity was made of the same directory:
  // campaign status counts runs by directory, so a byte-identical copy elsewhere is a run of its own.
  const auto place_key = [](const RunIdentity& identity, const std::string& dir) {
    return identity.key() + "\n" + std::filesystem::absolute(dir).lexically_normal().string();
  };
  std::map<std::string, std::int64_t> stored_keys;  // identity and directory -> run id
  const std::map<std::int64_t, RunIdentity> identities = stored_run_identities(*db);
  const std::vector<std::string> dirs = stored_recording_dirs(*db);  // by run id, as the identities
  std::size_t i = 0;
  for (const auto& [run_id, identity] : identities) {
    if (i < dirs.size()) stored_keys.emplace(place_key(identity, dirs[i++]), run_id);
  }

  const ModelLibrary library = ModelLibrary::builtin();
  const CampaignReplay& replay = plan.manifest.replay;
  ShardOutcome outcome;
  for (const PlannedRecording& r : plan.shards[static_cast<std::size_t>(shard)].recordings) {
    try {
      const Recording header = read_recording_header(r.dir);
      const ReplayOptions options = replay.options_for(header);
      const RunIdentity identity = planned_run_identity(recording_checksum(r.dir),
                                                        import_header(header, 0.0, library, options.import), options,
                                                        replay.store);
      const std::string key = place_key(identity, r.dir.string());
      if (const auto stored = stored_keys.find(key); stored != stored_keys.end()) {
        ++outcome.skipped;
        log << fmt::format("shard {}: {}: stored already (run {}), skipped\n", shard, r.dir.string(), stored->second);
        continue;
      }
      ReportWriter writer(*db, replay.store);
      std::unique_ptr<ReplaySink> wrapper;
      const ReplaySummary summary = replay_recording_dir(r.dir, options, wrapped_run_sink(writer, wrapper));
      stored_keys.emplace(key, writer.run_id());
      ++outcome.stored;
      log << fmt::format("shard {}: {}: run {} stored ({} cycles, GOSPA mean {:.3f} m, {:.2f} s)\n", shard,
                         r.dir.string(), writer.run_id(), summary.cycles, summary.gospa_mean_m, summary.total_wall_s);
    } catch (const std::exception& e) {
      outcome.failures.push_back(fmt::format("{}: {}", r.dir.string(), e.what()));
      log << fmt::format("shard {}: {}: FAILED: {}\n", shard, r.dir.string(), e.what());
    }
    log.flush();
  }
  return outcome;
}

}  // namespace rcsim::replay::campaign
