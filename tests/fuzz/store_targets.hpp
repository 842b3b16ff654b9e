#pragma once
// Fuzz entry points of what `rcsim report`, `rcsim merge` and `rcsim campaign plan` read
// (docs/fuzzing.md): a report database, and a campaign manifest. A report database is binary: the
// input is the whole file, the seeds are databases the harness writes itself by replaying the
// recording base (tests/fuzz/base/recording.txt); SQLite's page checks, quick_check and the
// store's own bounds must refuse what the mutations damage.
#include <SQLiteCpp/SQLiteCpp.h>

#include <sstream>

#include "fuzz/fuzz_support.hpp"
#include "replay/campaign/manifest.hpp"
#include "replay/campaign/plan.hpp"
#include "replay/report/html_report.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_merge.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::fuzz {

// A recording directory holding the recording base (12 cycles of two_in_one_cell), written once.
inline std::filesystem::path base_recording_dir() {
  static const std::filesystem::path dir = [] {
    static const std::string base_text = read_source_file("tests/fuzz/base/recording.txt");
    const std::vector<std::string_view> base = split_sections(base_text);
    const std::filesystem::path d = fresh_dir("base_recording");
    write_recording_sections(d, base);
    return d;
  }();
  return dir;
}

// The seeds: the recording base replayed into a report at each store level, as one file (the
// journal folded in), read back as bytes.
inline std::vector<std::pair<std::string, std::vector<std::uint8_t>>> report_database_seeds() {
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> seeds;
  for (const char* store : {"full", "summary"}) {
    const std::filesystem::path path = fresh_dir(std::string("seed_") + store) / "report.sqlite";
    {
      const auto db = replay::open_report_database(path.string(), true);
      {
        replay::ReportWriter writer(*db, replay::store_level_from_name(store));
        replay::ReplayOptions options;
        options.seed = 1;
        (void)replay::replay_recording_dir(base_recording_dir(), options, writer);
      }
      db->exec("PRAGMA journal_mode = DELETE");
    }
    const std::string bytes = read_source_file(path);
    seeds.emplace_back(std::string("report_") + store, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  }
  return seeds;
}

// The input is a report database: rendered as `rcsim report` renders it, and merged into a new
// report as `rcsim merge` merges it. Each either works or refuses, naming the file.
inline void fuzz_report_database(Input data) {
  const std::filesystem::path dir = fresh_dir("report_database");
  const std::filesystem::path db = dir / "report.sqlite";
  write_file(db, as_text(data));
  refusals_are_fine([&] {
    replay::HtmlReportOptions options;
    options.max_points = 200;
    options.pictures = 1;
    (void)replay::write_html_report_file(db.string(), (dir / "report.html").string(), options);
  });
  refusals_are_fine([&] { (void)replay::merge_reports({db.string()}, (dir / "merged.sqlite").string()); });
}

// A manifest's text planned as `rcsim campaign plan` plans it, beside three recordings
// (drives/2026-07-01, drives/2026-07-02, extra/drive_0042: the schema's example finds them), read
// back, and its batch script made; refusals are exceptions, as from the command.
inline std::string plan_campaign_manifest(std::string_view text) {
  static const std::filesystem::path recordings = [] {
    const std::filesystem::path d = fresh_dir("campaign_recordings");
    for (const char* place : {"drives/2026-07-01", "drives/2026-07-02", "extra/drive_0042"}) {
      std::filesystem::create_directories((d / place).parent_path());
      std::filesystem::create_directory_symlink(base_recording_dir(), d / place);
    }
    return d;
  }();
  const std::filesystem::path manifest = recordings / "campaign.json";
  write_file(manifest, text);
  const std::filesystem::path plan_dir = fresh_dir("campaign_plan");
  std::filesystem::remove(plan_dir);
  const auto m = replay::campaign::read_manifest(manifest);
  (void)replay::campaign::write_plan(m, 2, plan_dir, "/usr/bin/rcsim");
  return replay::campaign::batch_script(replay::campaign::read_plan(plan_dir));
}

// The input is a campaign manifest (schemas/campaign.md). Nothing in it may reach the batch
// script but as a line of the script's own shape: a newline in a name would start a command.
inline void fuzz_campaign_manifest(Input data) {
  refusals_are_fine([&] {
    std::istringstream lines(plan_campaign_manifest(as_text(data)));
    for (std::string line; std::getline(lines, line);) {
      const bool ours = line == "#!/bin/bash" || line.starts_with("# ") || line.starts_with("#SBATCH --") ||
                        line == "set -euo pipefail" || line.starts_with("exec '/usr/bin/rcsim' campaign run-shard '");
      if (!ours) throw Finding("a line of the batch script that rcsim did not write: " + line);
    }
  });
}

}  // namespace rcsim::fuzz
