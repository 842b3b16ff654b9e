#include "replay/verdict/run_figures.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "replay/run/run_accumulators.hpp"
#include "replay/store/campaign_store.hpp"

namespace rcsim::replay::verdict {

namespace {

// What a run's figures are computed from (replay/store/campaign_store.hpp); missing values are NaN.
using RunRecord = RunFigureSources;

using Compute = std::function<double(const RunRecord&)>;

// a / b, NaN (missing) where b is 0 or either is missing.
double ratio(double a, double b) { return b > 0.0 ? a / b : std::nan(""); }

struct CatalogueEntry {
  FigureInfo info;
  Compute compute;
};

const std::vector<CatalogueEntry>& catalogue() {
  static const std::vector<CatalogueEntry> entries = {
      {{"gospa_mean_m", "m", "GOSPA against the recording, mean over sensor cycles", Worse::higher},
       [](const RunRecord& r) { return r.gospa_mean; }},
      {{"ospa_mean_m", "m", "OSPA, mean over sensor cycles", Worse::higher}, [](const RunRecord& r) { return r.ospa_mean; }},
      {{"gospa_object_mean_m", "m", "GOSPA on the targets of annotated objects only", Worse::higher},
       [](const RunRecord& r) { return r.gospa_object_mean; }},
      {{"ospa_object_mean_m", "m", "OSPA on the targets of annotated objects only", Worse::higher},
       [](const RunRecord& r) { return r.ospa_object_mean; }},
      {{"target_count_ratio", "1", "simulated / recorded targets (1: as many)", Worse::away_from_one},
       [](const RunRecord& r) { return ratio(r.targets_simulated, r.targets_recorded); }},
      {{"object_target_count_ratio", "1", "simulated / recorded targets of annotated objects (1: as many)",
        Worse::away_from_one},
       [](const RunRecord& r) { return ratio(r.object_simulated, r.object_recorded); }},
      {{"background_target_count_ratio", "1", "simulated / recorded stationary-background targets (1: as many)",
        Worse::away_from_one},
       [](const RunRecord& r) { return ratio(r.background_simulated, r.background_recorded); }},
      {{"matched_fraction", "1", "recorded targets assigned a simulated one within the GOSPA cut-off", Worse::lower},
       [](const RunRecord& r) { return ratio(r.targets_matched, r.targets_recorded); }},
      {{"object_detection_rate_recorded", "1", "object-sensor cycles in view with a recorded object target", Worse::lower},
       [](const RunRecord& r) { return ratio(r.detected_recorded, r.in_view); }},
      {{"object_detection_rate_simulated", "1", "object-sensor cycles in view with a simulated object target",
        Worse::lower},
       [](const RunRecord& r) { return ratio(r.detected_simulated, r.in_view); }},
      {{"object_detection_rate_difference", "1", "simulated - recorded object detection rate", Worse::away_from_zero},
       [](const RunRecord& r) { return ratio(r.detected_simulated - r.detected_recorded, r.in_view); }},
      {{"latency_difference_mean_s", "s", "simulated - recorded confirmation latency, mean over paired episodes",
        Worse::away_from_zero},
       [](const RunRecord& r) { return r.latency_pairs > 0 ? r.latency_difference_mean_s : std::nan(""); }},
      {{"latency_recorded_s", "s", "recorded confirmation latency, mean", Worse::higher},
       [](const RunRecord& r) { return r.latency_recorded_s; }},
      {{"latency_simulated_s", "s", "simulated confirmation latency, mean", Worse::higher},
       [](const RunRecord& r) { return r.latency_simulated_s; }},
      {{"latency_unconfirmed_simulated_fraction", "1", "episodes the simulation never confirmed", Worse::higher},
       [](const RunRecord& r) { return ratio(r.latency_unconfirmed_simulated, r.latency_episodes); }},
      {{"merge_artefacts_recorded", "1", "recorded merge artefacts (paper Fig. 10)", Worse::higher},
       [](const RunRecord& r) { return r.merge_recorded; }},
      {{"merge_artefacts_simulated", "1", "simulated merge artefacts", Worse::higher},
       [](const RunRecord& r) { return r.merge_simulated; }},
      {{"merge_artefact_match_fraction", "1", "recorded merge artefacts the simulation matched", Worse::lower},
       [](const RunRecord& r) { return ratio(r.merge_matched, r.merge_recorded); }},
      {{"residual_range_rms_m", "m", "range residual of assigned pairs, RMS", Worse::higher},
       [](const RunRecord& r) { return r.residual_range_rms_m; }},
      {{"residual_azimuth_rms_rad", "rad", "azimuth residual of assigned pairs, RMS", Worse::higher},
       [](const RunRecord& r) { return r.residual_azimuth_rms_rad; }},
      {{"residual_range_rate_rms_mps", "m/s", "range-rate residual of assigned pairs, RMS", Worse::higher},
       [](const RunRecord& r) { return r.residual_range_rate_rms_mps; }},
      {{"residual_amplitude_mean_db", "dB", "amplitude residual of assigned pairs, mean", Worse::away_from_zero},
       [](const RunRecord& r) { return r.residual_amplitude_mean_db; }},
      {{"replay_wall_s", "s", "wall time of the replay", Worse::higher}, [](const RunRecord& r) { return r.wall_s; }},
      {{"simulate_cpu_s", "s", "CPU time of the simulation", Worse::higher},
       [](const RunRecord& r) { return r.simulate_cpu_s; }},
  };
  return entries;
}

constexpr std::string_view kW1Prefix = "wasserstein1.";
constexpr std::string_view kKsPrefix = "kolmogorov_smirnov.";

}  // namespace

const std::vector<FigureInfo>& figure_catalogue() {
  static const std::vector<FigureInfo> infos = [] {
    std::vector<FigureInfo> out;
    for (const auto& e : catalogue()) out.push_back(e.info);
    return out;
  }();
  return infos;
}

std::optional<FigureInfo> find_figure(std::string_view name) {
  for (const auto& e : catalogue()) {
    if (e.info.name == name) return e.info;
  }
  for (const auto prefix : {kW1Prefix, kKsPrefix}) {
    const std::string_view quantity = name.substr(std::min(name.size(), prefix.size()));
    const bool known = std::any_of(kComparedQuantities.begin(), kComparedQuantities.end(),
                                   [quantity](const ComparedQuantity& q) { return q.name == quantity; });
    if (name.starts_with(prefix) && known) {
      const bool w1 = prefix == kW1Prefix;
      return FigureInfo{std::string(name), w1 ? "of the quantity" : "1",
                        std::string(w1 ? "Wasserstein-1 (area metric) between recorded and simulated "
                                       : "Kolmogorov-Smirnov statistic between recorded and simulated ") +
                            std::string(name.substr(prefix.size())),
                        Worse::higher};
    }
  }
  return std::nullopt;
}

std::string figure_names() {
  std::string out;
  for (const auto& e : catalogue()) out += (out.empty() ? "" : ", ") + e.info.name;
  std::string quantities;
  for (const ComparedQuantity& q : kComparedQuantities) quantities += (quantities.empty() ? "" : ", ") + std::string(q.name);
  return out + ", wasserstein1.QUANTITY, kolmogorov_smirnov.QUANTITY (QUANTITY: " + quantities + ")";
}

std::vector<RunFigureRow> read_run_figures(ReportDatabase& db, const std::vector<std::string>& figures) {
  // What each figure asked for is computed from: a catalogue entry, or a distance of a quantity.
  std::vector<const CatalogueEntry*> entries(figures.size(), nullptr);
  std::map<std::string, std::vector<std::size_t>> distances;  // quantity -> figure indices
  for (std::size_t i = 0; i < figures.size(); ++i) {
    for (const auto& e : catalogue()) {
      if (e.info.name == figures[i]) entries[i] = &e;
    }
    if (entries[i] != nullptr) continue;
    if (!find_figure(figures[i])) throw std::invalid_argument("unknown figure '" + figures[i] + "'");
    const auto dot = figures[i].find('.');
    distances[figures[i].substr(dot + 1)].push_back(i);
  }

  std::vector<RunFigureRow> rows;
  std::map<std::int64_t, std::size_t> row_of;
  for (const RunRecord& record : read_run_figure_sources(db)) {
    RunFigureRow row;
    row.run_id = record.run_id;
    row.recording_name = record.recording_name;
    row.recording_dir = record.recording_dir;
    row.seed = record.seed;
    row.duration_s = record.duration_s;
    row.kind = record.kind;
    row.values.resize(figures.size());
    for (std::size_t i = 0; i < figures.size(); ++i) {
      if (entries[i] == nullptr) continue;
      const double v = entries[i]->compute(record);
      if (std::isfinite(v)) row.values[i] = v;
    }
    row_of[row.run_id] = rows.size();
    rows.push_back(std::move(row));
  }
  if (!distances.empty()) {
    for (const RunDistance& d : read_run_distances(db)) {
      const auto run = row_of.find(d.run_id);
      const auto wanted = distances.find(d.quantity);
      if (run == row_of.end() || wanted == distances.end()) continue;
      for (const std::size_t i : wanted->second) {
        const std::optional<double>& value = figures[i].starts_with(kW1Prefix) ? d.wasserstein1 : d.kolmogorov_smirnov;
        if (value) rows[run->second].values[i] = *value;
      }
    }
  }
  return rows;
}

}  // namespace rcsim::replay::verdict
