// Writes a generated campaign report database for the campaign report's benchmark
// (scripts/bench-report.sh, docs/report.md "Campaign report"): one real replay of a bundled
// recording stored with --store summary, copied RUNS - 1 times with varied figures, plus a
// campaign row and a few criteria (replay/verdict/criteria.hpp), so that `rcsim report` has
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
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "replay/verdict/criteria.hpp"
#include "tool_arguments.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/campaign_store.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_copies.hpp"

namespace {

using namespace rcsim;
using namespace rcsim::replay;

std::vector<verdict::Criterion> campaign_criteria() {
  using verdict::Bound;
  using verdict::Criterion;
  using verdict::Scope;
  using verdict::Statistic;
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
    const SourceRunFigures figures = source_run_figures(*db, source);
    RunCopier copier(*db, source);
    std::mt19937_64 rng(*seed);
    std::lognormal_distribution<double> quality(0.0, 0.35);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    // The source run last, so that every copy is of its figures as replayed.
    for (std::int64_t k = 1; k <= *runs; ++k) {
      const std::int64_t id = k == *runs ? source : k + 1;
      if (id != source) copier.copy(id);
      copier.rename(id, fmt::format("drive_{:05d}", id), fmt::format("/campaign/drives/drive_{:05d}", id), id,
                    fmt::format("{:016x}", static_cast<std::uint64_t>(rng())));
      RunVariation v;
      v.quality = quality(rng);
      if (uniform(rng) < 0.03) v.quality *= 3.0 + 3.0 * uniform(rng);
      v.amplitude_shift_db = 0.8 * noise(rng);
      v.simulated_targets_factor = std::max(0.2, 1.0 + 0.1 * noise(rng));
      v.no_latency_pair = uniform(rng) < 0.1;
      v.latency_difference_s = 0.05 + 0.15 * noise(rng);
      v.time_factor = 0.8 + 0.5 * uniform(rng);
      v.detection_factor = std::max(0.0, (1.0 + 0.08 * noise(rng)) / std::pow(v.quality, 0.2));
      v.distance_factor = v.quality * (0.8 + 0.4 * uniform(rng));
      copier.vary(id, v);
    }
    copier.commit();

    // Thresholds from the source run, so that about a third of the runs fail a criterion.
    std::vector<verdict::Criterion> criteria = campaign_criteria();
    criteria[0].threshold = std::round(figures.gospa_mean_m * 1.3 * 1000.0) / 1000.0;
    criteria[1].threshold = std::round(figures.object_detection_rate_simulated * 0.85 * 1000.0) / 1000.0;
    criteria[4].threshold = std::round(figures.gospa_mean_m * 2.5 * 1000.0) / 1000.0;
    criteria[5].threshold = std::round(figures.wasserstein1_range_m * 1.0 * 1000.0) / 1000.0;
    claim_campaign(*db, "generated-campaign",
                   fmt::format(R"({{"format": "rcsim-campaign", "version": 1, "name": "generated-campaign", )"
                               R"("recordings": ["drives/*"], "generated_from": "{}"}})",
                               recording.string()),
                   verdict::criterion_rows(criteria));
    std::cout << "wrote " << out << ": " << *runs << " runs copied from " << recording.string() << ", "
              << criteria.size() << " criteria\n";
  } catch (const std::exception& e) {
    std::cerr << "rcsim_make_campaign_db: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
