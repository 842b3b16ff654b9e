// Writes a generated campaign report database for the campaign report's benchmark
// (scripts/bench-report.sh, docs/report.md "Campaign report"): one real replay of a bundled
// recording stored with --store summary, copied RUNS - 1 times with varied figures, plus a
// campaign row and a few criteria (replay/campaign/criteria.hpp), so that `rcsim report` has
// thousands of runs to judge, rank and plot. Not committed: regenerate it.
//
// Each copy is drive_NNNNN with its own seed. Its quality q is log-normal (sigma 0.35) with 3 %
// outliers 3 to 6 times worse; GOSPA, OSPA and the residuals scale with q, the distribution
// distances with q (KS with its square root, at most 1), the simulated object detection with
// 1 / q^0.2 and noise, the amplitude residual shifts by noise, the latency difference is drawn
// about +0.05 s (sigma 0.15 s), and one run in ten has no latency pair (its latency difference is
// missing). Every table that refers to a run is
// copied, whatever its columns, so the copies are runs as the report reads them.
//   usage: rcsim_make_campaign_db OUTPUT.sqlite [RUNS=10000] [RECORDING_DIR=recordings_synthetic/front_approach] [SEED=1]
#include <SQLiteCpp/SQLiteCpp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "replay/campaign/criteria.hpp"
#include "tool_arguments.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"

namespace {

using namespace rcsim;
using namespace rcsim::replay;

// "INSERT INTO t (a, b, ...) SELECT ?1, b, ... FROM t WHERE run_id = ?2" for a table with a run_id.
std::string copy_statement(SQLite::Database& db, const std::string& table) {
  std::vector<std::string> columns;
  SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?)");
  info.bind(1, table);
  while (info.executeStep()) columns.push_back(info.getColumn(0).getString());
  std::string names, values;
  for (const std::string& c : columns) {
    names += (names.empty() ? "" : ", ") + c;
    values += (values.empty() ? "" : ", ") + (c == "run_id" ? std::string("?1") : c);
  }
  return fmt::format("INSERT INTO {0} ({1}) SELECT {2} FROM {0} WHERE run_id = ?2", table, names, values);
}

std::vector<campaign::Criterion> campaign_criteria() {
  using campaign::Bound;
  using campaign::Criterion;
  using campaign::Scope;
  using campaign::Statistic;
  std::vector<Criterion> c;
  c.push_back({"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 0.0, false});  // threshold set below
  c.push_back({"object_detection_rate_simulated", Scope::recording, Statistic::value, Bound::min, 0.0, false});
  c.push_back({"latency_difference_mean_s", Scope::recording, Statistic::value, Bound::max, 0.3, true});
  c.push_back({"latency_difference_mean_s", Scope::recording, Statistic::value, Bound::min, -0.3, true});
  c.push_back({"gospa_mean_m", Scope::campaign, Statistic::p95, Bound::max, 0.0, false});
  c.push_back({"wasserstein1.range", Scope::campaign, Statistic::mean, Bound::max, 0.0, false});
  return c;
}

const bench_tools::ToolUsage kCampaignDbUsage{
    "rcsim_make_campaign_db", "OUTPUT.sqlite [RUNS=10000] [RECORDING_DIR=recordings_synthetic/front_approach] [SEED=1]",
    "Writes a generated campaign report database for the campaign report's benchmark\n"
    "(scripts/bench-report.sh): one replay of RECORDING_DIR, copied RUNS - 1 times with varied figures,\n"
    "a campaign row and criteria. OUTPUT.sqlite must not exist.",
    1, 4};

}  // namespace

int main(int argc, char** argv) {
  int exit_status = 0;
  const auto arguments = bench_tools::tool_arguments(argc, argv, kCampaignDbUsage, exit_status);
  if (!arguments) return exit_status;
  const std::string out = arguments->front();
  const std::optional<long> runs =
      arguments->size() > 1 ? bench_tools::number_argument<long>((*arguments)[1]) : std::optional<long>(10000);
  const std::filesystem::path recording = arguments->size() > 2 ? (*arguments)[2] : "recordings_synthetic/front_approach";
  const std::optional<unsigned> seed =
      arguments->size() > 3 ? bench_tools::number_argument<unsigned>((*arguments)[3]) : std::optional<unsigned>(1u);
  if (!runs || *runs < 1) return bench_tools::refuse_command_line(kCampaignDbUsage, "RUNS must be a whole number >= 1");
  if (!seed) return bench_tools::refuse_command_line(kCampaignDbUsage, "SEED must be a whole number >= 0");
  if (std::filesystem::exists(out)) {
    std::cerr << "rcsim_make_campaign_db: " << out << " exists; remove it first\n";
    return 2;
  }
  try {
    const auto db = open_report_database(out, true);
    {
      ReportWriter writer(*db, StoreLevel::summary);
      replay_recording_dir(recording, ReplayOptions{}, writer);
    }
    const std::int64_t source = 1;
    double gospa = 0.0, rate = 0.0, w1_range = 0.0;
    {
      SQLite::Statement q(*db, "SELECT gospa_mean FROM summaries WHERE run_id = 1");
      q.executeStep();
      gospa = q.getColumn(0).getDouble();
      SQLite::Statement r(*db,
                          "SELECT CAST(sum(cycles_detected_simulated) AS REAL) / max(1, sum(cycles_in_view)) "
                          "FROM object_figures WHERE run_id = 1");
      r.executeStep();
      rate = r.getColumn(0).getDouble();
      SQLite::Statement w(*db, "SELECT coalesce(wasserstein1, 0) FROM distribution_distances "
                               "WHERE run_id = 1 AND quantity = 'range'");
      if (w.executeStep()) w1_range = w.getColumn(0).getDouble();
    }

    std::vector<std::string> tables;
    {
      SQLite::Statement q(*db, "SELECT m.name FROM sqlite_master m WHERE m.type = 'table' AND m.name <> 'runs' AND "
                               "EXISTS (SELECT 1 FROM pragma_table_info(m.name) WHERE name = 'run_id') ORDER BY m.name");
      while (q.executeStep()) tables.push_back(q.getColumn(0).getString());
    }
    SQLite::Transaction transaction(*db);
    SQLite::Statement copy_run(*db, copy_statement(*db, "runs"));
    SQLite::Statement rename(*db, "UPDATE runs SET recording_name = ?, recording_dir = ?, seed = ?, "
                                  "recording_checksum = ? WHERE run_id = ?");
    std::vector<std::unique_ptr<SQLite::Statement>> copies;
    for (const std::string& t : tables) copies.push_back(std::make_unique<SQLite::Statement>(*db, copy_statement(*db, t)));
    SQLite::Statement vary_summary(*db, R"SQL(
UPDATE summaries SET gospa_mean = gospa_mean * ?1, ospa_mean = ospa_mean * sqrt(?1),
  gospa_object_mean = gospa_object_mean * ?1, ospa_object_mean = ospa_object_mean * sqrt(?1),
  residual_range_rms_m = residual_range_rms_m * ?1, residual_azimuth_rms_rad = residual_azimuth_rms_rad * ?1,
  residual_range_rate_rms_mps = residual_range_rate_rms_mps * ?1,
  residual_amplitude_mean_db = residual_amplitude_mean_db + ?2,
  targets_simulated = CAST(round(targets_simulated * ?3) AS INTEGER),
  targets_matched = min(targets_recorded, CAST(round(targets_matched / sqrt(?1)) AS INTEGER)),
  latency_difference_mean_s = CASE WHEN ?4 THEN NULL ELSE ?5 END,
  latency_pairs = CASE WHEN ?4 THEN 0 ELSE max(latency_pairs, 1) END,
  simulate_cpu_s = simulate_cpu_s * ?6, total_wall_s = total_wall_s * ?6
WHERE run_id = ?7)SQL");
    SQLite::Statement vary_objects(*db, "UPDATE object_figures SET cycles_detected_simulated = "
                                        "max(0, min(cycles_in_view, CAST(round(cycles_detected_simulated * ?1) AS INTEGER))) "
                                        "WHERE run_id = ?2");
    SQLite::Statement vary_distances(*db, "UPDATE distribution_distances SET wasserstein1 = wasserstein1 * ?1, "
                                          "kolmogorov_smirnov = min(1.0, kolmogorov_smirnov * sqrt(?1)) WHERE run_id = ?2");

    std::mt19937_64 rng(*seed);
    std::lognormal_distribution<double> quality(0.0, 0.35);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    // The source run last, so that every copy is of its figures as replayed.
    for (std::int64_t k = 1; k <= *runs; ++k) {
      const std::int64_t id = k == *runs ? source : k + 1;
      if (id != source) {
        copy_run.bind(1, id);
        copy_run.bind(2, source);
        copy_run.exec();
        copy_run.reset();
        for (auto& c : copies) {
          c->bind(1, id);
          c->bind(2, source);
          c->exec();
          c->reset();
        }
      }
      rename.bind(1, fmt::format("drive_{:05d}", id));
      rename.bind(2, fmt::format("/campaign/drives/drive_{:05d}", id));
      rename.bind(3, id);
      rename.bind(4, fmt::format("{:016x}", static_cast<std::uint64_t>(rng())));
      rename.bind(5, id);
      rename.exec();
      rename.reset();

      double q = quality(rng);
      if (uniform(rng) < 0.03) q *= 3.0 + 3.0 * uniform(rng);
      vary_summary.bind(1, q);
      vary_summary.bind(2, 0.8 * noise(rng));
      vary_summary.bind(3, std::max(0.2, 1.0 + 0.1 * noise(rng)));
      vary_summary.bind(4, uniform(rng) < 0.1 ? 1 : 0);
      vary_summary.bind(5, 0.05 + 0.15 * noise(rng));
      vary_summary.bind(6, 0.8 + 0.5 * uniform(rng));
      vary_summary.bind(7, id);
      vary_summary.exec();
      vary_summary.reset();
      vary_objects.bind(1, std::max(0.0, (1.0 + 0.08 * noise(rng)) / std::pow(q, 0.2)));
      vary_objects.bind(2, id);
      vary_objects.exec();
      vary_objects.reset();
      vary_distances.bind(1, q * (0.8 + 0.4 * uniform(rng)));
      vary_distances.bind(2, id);
      vary_distances.exec();
      vary_distances.reset();
    }

    // Thresholds from the source run, so that about a third of the runs fail a criterion.
    std::vector<campaign::Criterion> criteria = campaign_criteria();
    criteria[0].threshold = std::round(gospa * 1.3 * 1000.0) / 1000.0;
    criteria[1].threshold = std::round(rate * 0.85 * 1000.0) / 1000.0;
    criteria[4].threshold = std::round(gospa * 2.5 * 1000.0) / 1000.0;
    criteria[5].threshold = std::round(w1_range * 1.0 * 1000.0) / 1000.0;
    campaign::store_criteria(*db, criteria);
    SQLite::Statement name(*db, "INSERT INTO campaign (name, manifest) VALUES (?, ?)");
    name.bind(1, "generated-campaign");
    name.bind(2, fmt::format(R"({{"format": "rcsim-campaign", "version": 1, "name": "generated-campaign", )"
                             R"("recordings": ["drives/*"], "generated_from": "{}"}})",
                             recording.string()));
    name.exec();
    transaction.commit();
    std::cout << "wrote " << out << ": " << *runs << " runs copied from " << recording.string() << ", "
              << criteria.size() << " criteria\n";
  } catch (const std::exception& e) {
    std::cerr << "rcsim_make_campaign_db: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
