#include "replay/report/campaign_data.hpp"

#include <algorithm>
#include <cmath>

#include "replay/store/campaign_store.hpp"

namespace rcsim::replay::report {

std::vector<double> CampaignData::sorted_values(std::size_t figure) const {
  std::vector<double> values;
  values.reserve(runs.size());
  for (const auto& run : runs) {
    if (run.values[figure]) values.push_back(*run.values[figure]);
  }
  std::sort(values.begin(), values.end());
  return values;
}

std::optional<std::size_t> CampaignData::figure_index(const std::string& figure) const {
  for (std::size_t i = 0; i < figures.size(); ++i) {
    if (figures[i].name == figure) return i;
  }
  return std::nullopt;
}

bool is_campaign_database(ReportDatabase& db) {
  return !read_campaign_name(db).value_or("").empty() || count_criterion_rows(db) > 0;
}

CampaignData read_campaign_data(ReportDatabase& db) {
  CampaignData data;
  data.name = read_campaign_name(db).value_or("");
  const std::vector<verdict::Criterion> criteria = verdict::stored_criteria(db);

  // Every candidate figure, then those some run has or a criterion names.
  std::vector<verdict::FigureInfo> candidates = verdict::figure_catalogue();
  for (const auto& [quantity, unit] : read_distance_quantities(db)) {
    for (const char* prefix : {"wasserstein1.", "kolmogorov_smirnov."}) {
      auto info = verdict::find_figure(prefix + quantity);
      if (!info) continue;
      if (info->name.starts_with("wasserstein1.")) info->unit = unit;
      candidates.push_back(*info);
    }
  }
  for (const auto& c : criteria) {
    const bool listed = std::any_of(candidates.begin(), candidates.end(), [&](const auto& f) { return f.name == c.figure; });
    if (!listed) {
      if (auto info = verdict::find_figure(c.figure)) candidates.push_back(*info);
    }
  }
  std::vector<std::string> names;
  for (const auto& f : candidates) names.push_back(f.name);
  std::vector<verdict::RunFigureRow> rows = verdict::read_run_figures(db, names);

  // The judged figures first, in the order of the criteria; then the others some run has.
  std::vector<std::size_t> kept;
  for (const auto& c : criteria) {
    const auto i = static_cast<std::size_t>(std::find(names.begin(), names.end(), c.figure) - names.begin());
    if (i < names.size() && std::find(kept.begin(), kept.end(), i) == kept.end()) kept.push_back(i);
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const bool present = std::any_of(rows.begin(), rows.end(), [&](const auto& r) { return r.values[i].has_value(); });
    if (present && std::find(kept.begin(), kept.end(), i) == kept.end()) kept.push_back(i);
  }
  for (const std::size_t i : kept) data.figures.push_back(candidates[i]);
  for (auto& row : rows) {
    std::vector<std::optional<double>> values;
    values.reserve(kept.size());
    for (const std::size_t i : kept) values.push_back(row.values[i]);
    row.values = std::move(values);
  }
  data.runs = std::move(rows);
  data.verdicts = verdict::judge(db, criteria);
  return data;
}

}  // namespace rcsim::replay::report
