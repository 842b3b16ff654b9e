#pragma once
// The figures of every run of a report by recording directory, for comparing a campaign's merged
// report with a serial replay figure for figure (the times left out: they differ run to run).
#include <SQLiteCpp/SQLiteCpp.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "replay/verdict/run_figures.hpp"

namespace rcsim::testing {

inline std::map<std::string, std::vector<std::optional<double>>> figures_by_recording(const std::filesystem::path& db_path) {
  std::vector<std::string> names;
  for (const auto& f : replay::verdict::figure_catalogue()) {
    if (f.name != "replay_wall_s" && f.name != "simulate_cpu_s") names.push_back(f.name);
  }
  names.push_back("wasserstein1.background_range");
  names.push_back("kolmogorov_smirnov.background_azimuth");
  replay::ReportDatabase db(db_path.string());
  std::map<std::string, std::vector<std::optional<double>>> out;
  for (auto& row : replay::verdict::read_run_figures(db, names)) out[row.recording_dir] = row.values;
  return out;
}

}  // namespace rcsim::testing
