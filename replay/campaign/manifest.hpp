#pragma once
// A campaign manifest (`rcsim-campaign` v1, schemas/campaign.md): the recordings of a measurement
// campaign (directories or globs, relative to the manifest), how each is replayed, the pass/fail
// criteria and, optionally, what the Slurm batch script asks for.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "replay/verdict/criteria.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay::campaign {

// How every recording of the campaign is replayed: rcsim replay's options.
struct CampaignReplay {
  ReplayOptions options;             // seed, metric and import parameters, calibration, sensor override
  std::optional<Fidelity> fidelity;  // unset: from what each recording's sensors report
  StoreLevel store = StoreLevel::summary;

  // The options of one recording's run (its default fidelity filled in).
  ReplayOptions options_for(const Recording& header) const;
};

// What the batch script's #SBATCH lines ask for (all optional).
struct SlurmRequest {
  std::string partition, account, time_limit, memory;  // --partition, --account, --time, --mem
  std::vector<std::string> extra;                      // more sbatch options, verbatim ("--qos=long")
};

struct CampaignManifest {
  std::filesystem::path file;
  std::string name;
  std::vector<std::filesystem::path> recordings;  // absolute, normalised, sorted, each once
  CampaignReplay replay;
  std::vector<verdict::Criterion> criteria;
  SlurmRequest slurm;
  nlohmann::json document;  // as read
};

// Reads and checks a manifest: unknown fields, a pattern that matches no recording, a directory
// without recording.json, an unknown figure are refused with the file and field.
CampaignManifest read_manifest(const std::filesystem::path& path);

// The manifest's `replay` member alone (also what a plan stores); paths are resolved against
// `base_dir`.
CampaignReplay parse_campaign_replay(const JsonField& replay, const std::filesystem::path& base_dir);

}  // namespace rcsim::replay::campaign
