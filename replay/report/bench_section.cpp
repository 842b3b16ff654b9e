#include "replay/report/bench_section.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "replay/evaluate/bench.hpp"
#include "replay/report/html_cells.hpp"
#include "replay/report/svg_pareto.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

namespace {

using replay::kNoiseFloorLevel;
using svg::escape;

constexpr const char* kNull = "\u2014";  // em dash: a NULL in the database

std::optional<double> mean(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

std::optional<double> ratio(double numerator, double denominator) {
  if (!(denominator > 0.0)) return std::nullopt;
  return numerator / denominator;
}

// The noise-floor row of a recording, if the bench has one.
const BenchRow* noise_floor_row(const BenchData& bench, int recording) {
  for (const BenchRow& r : bench.rows) {
    if (r.recording == recording && r.level == kNoiseFloorLevel) return &r;
  }
  return nullptr;
}

std::string opt_text(const std::optional<double>& value, int decimals) {
  return value ? svg::fixed(*value, decimals) : std::string(kNull);
}

std::string opt_speed(const std::optional<double>& value) {
  return value ? svg::speed_text(*value) : std::string(kNull);
}

std::string cell_int(std::int64_t value) { return cell_num(std::to_string(value)); }


std::string row_open(const std::string& level) {
  return fmt::format(R"(<tr data-level="{}"{}>)", escape(level), level == kDefaultLevel ? R"( class="default")" : "");
}

// The levels with a speed, as plot points; the noise floor is the plot's line, not a point.
std::vector<svg::ParetoPoint> pareto_points(const BenchSummary& summary) {
  std::vector<svg::ParetoPoint> points;
  for (const LevelSummary& l : summary.levels) {
    if (l.level == kNoiseFloorLevel || !l.cycles_per_cpu_s) continue;
    points.push_back({l.level, *l.cycles_per_cpu_s, l.gospa_mean_m, l.level == kDefaultLevel});
  }
  return points;
}

std::string level_table(const BenchSummary& summary) {
  const std::vector<svg::ParetoPoint> points = pareto_points(summary);
  const std::vector<bool> front = svg::pareto_front(points);
  std::string out = R"(<div class="scroll"><table class="bench-levels">)";
  out += header_row({"level", "record-\nings", "sensor\ncycles", "CPU\ntime / s", "sensor\ncycles per\nCPU s",
                     "GOSPA\nmean / m", "GOSPA /\nnoise\nfloor", "targets per\ncycle, sim. /\nrec. (mean)",
                     "merge\nartefacts\nrecorded", "found", "missed", "spurious",
                     "latency diff.\nsim. \u2212 rec.\n/ s (mean)", "latency\npairs", "Pareto\nfront"});
  for (const LevelSummary& l : summary.levels) {
    std::string on_front = kNull;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i].label == l.level) on_front = front[i] ? "yes" : "no";
    }
    out += row_open(l.level) + cell(l.level) + cell_int(l.recordings) + cell_int(l.sensor_cycles) +
           cell_num(opt_text(l.cpu_s, 3)) + cell_num(opt_speed(l.cycles_per_cpu_s)) +
           cell_num(svg::fixed(l.gospa_mean_m, 3)) + cell_num(opt_text(l.gospa_over_noise_floor, 2)) +
           cell_num(opt_text(l.targets_per_cycle_ratio, 3)) + cell_int(l.merge_recorded) + cell_int(l.merge_found) +
           cell_int(l.merge_missed) + cell_int(l.merge_spurious) + cell_num(opt_text(l.latency_difference_s, 3)) +
           cell_int(l.latency_pairs) + cell(on_front) + "</tr>";
  }
  return out + "</table></div>";
}

std::string row_table(const BenchData& bench) {
  std::string out = R"(<div class="scroll"><table class="bench-rows">)";
  out += header_row({"#", "recording", "level", "sensor\ncycles", "CPU\ntime / s", "sensor\ncycles per\nCPU s",
                     "GOSPA\nmean / m", "GOSPA /\nnoise\nfloor", "targets per\ncycle, sim.\n/ rec.",
                     "merge\nartefacts\nrecorded", "found", "missed", "spurious",
                     "latency diff.\nsim. \u2212 rec.\n/ s", "latency\npairs"});
  for (const BenchRow& r : bench.rows) {
    const BenchRow* floor = noise_floor_row(bench, r.recording);
    const std::optional<double> over_floor = floor ? ratio(r.gospa_mean_m, floor->gospa_mean_m) : std::nullopt;
    out += row_open(r.level) + cell_int(r.recording) + cell(r.recording_name) + cell(r.level) +
           cell_int(r.sensor_cycles) + cell_num(opt_text(r.cpu_s, 3)) + cell_num(opt_speed(r.sensor_cycles_per_cpu_s)) +
           cell_num(svg::fixed(r.gospa_mean_m, 3)) + cell_num(opt_text(over_floor, 2)) +
           cell_num(opt_text(r.targets_per_cycle_ratio, 3)) + cell_int(r.merge_recorded) + cell_int(r.merge_found) +
           cell_int(r.merge_missed) + cell_int(r.merge_spurious) + cell_num(opt_text(r.latency_difference_s, 3)) +
           cell_int(r.latency_pairs) + "</tr>";
  }
  return out + "</table></div>";
}

// The axes every per-recording plot shares: all their speeds and errors.
svg::ParetoExtent shared_extent(const std::vector<BenchSummary>& per_recording) {
  svg::ParetoExtent e{std::numeric_limits<double>::infinity(), 0.0, 0.0};
  for (const BenchSummary& s : per_recording) {
    for (const svg::ParetoPoint& p : pareto_points(s)) {
      e.cycles_per_cpu_s_lo = std::min(e.cycles_per_cpu_s_lo, p.cycles_per_cpu_s);
      e.cycles_per_cpu_s_hi = std::max(e.cycles_per_cpu_s_hi, p.cycles_per_cpu_s);
      e.error_hi_m = std::max(e.error_hi_m, p.error_m);
    }
    if (s.noise_floor_m) e.error_hi_m = std::max(e.error_hi_m, *s.noise_floor_m);
  }
  return e;
}

std::string parameters_block(const BenchInfo& info) {
  std::string text = info.parameters;
  const nlohmann::ordered_json parsed = parse_stored_json(text);
  if (!parsed.is_discarded()) text = parsed.dump(2);
  return "<details><summary>Bench parameters (<code>bench_runs.parameters</code>)</summary><pre>" + escape(text) +
         "</pre></details>";
}

}  // namespace

BenchSummary summarise_bench(const BenchData& bench, std::optional<int> recording) {
  // The bench's own summary (replay/evaluate/bench.hpp), so that report and rcsim bench agree.
  std::vector<replay::BenchRow> rows;
  std::vector<double> floors;
  for (const BenchRow& r : bench.rows) {
    if (recording && r.recording != *recording) continue;
    if (r.level == kNoiseFloorLevel) floors.push_back(r.gospa_mean_m);
    replay::BenchRow c;
    c.recording = r.recording;
    c.level = r.level;
    c.sensor_cycles = r.sensor_cycles;
    c.cpu_s = r.cpu_s.value_or(-1.0);
    c.gospa_mean_m = r.gospa_mean_m;
    c.targets_per_cycle_ratio = r.targets_per_cycle_ratio.value_or(-1.0);
    c.merge_recorded = r.merge_recorded;
    c.merge_found = r.merge_found;
    c.merge_missed = r.merge_missed;
    c.merge_spurious = r.merge_spurious;
    c.has_latency = r.latency_difference_s.has_value();
    c.latency_difference_s = r.latency_difference_s.value_or(0.0);
    c.latency_pairs = static_cast<int>(r.latency_pairs);
    rows.push_back(std::move(c));
  }
  const auto present = [](double v) { return v >= 0.0 ? std::optional<double>(v) : std::nullopt; };
  BenchSummary summary;
  summary.noise_floor_m = mean(floors);
  for (const replay::BenchLevelSummary& s : replay::summarise_levels(rows)) {
    LevelSummary l;
    l.level = s.level;
    l.recordings = s.recordings;
    l.sensor_cycles = s.sensor_cycles;
    l.cpu_s = present(s.cpu_s);
    l.cycles_per_cpu_s = present(s.sensor_cycles_per_cpu_s);
    l.gospa_mean_m = s.gospa_mean_m;
    l.gospa_over_noise_floor = present(s.gospa_over_noise_floor);
    l.targets_per_cycle_ratio = present(s.targets_per_cycle_ratio);
    l.merge_recorded = s.merge_recorded;
    l.merge_found = s.merge_found;
    l.merge_missed = s.merge_missed;
    l.merge_spurious = s.merge_spurious;
    if (s.has_latency) l.latency_difference_s = s.latency_difference_s;
    l.latency_pairs = s.latency_pairs;
    summary.levels.push_back(std::move(l));
  }
  std::stable_sort(summary.levels.begin(), summary.levels.end(),
                   [](const LevelSummary& a, const LevelSummary& b) { return level_before(a.level, b.level); });
  return summary;
}

std::string bench_section(const BenchData& bench) {
  const BenchInfo& i = bench.info;
  const std::vector<int> recordings = bench.recordings();
  const BenchSummary all = summarise_bench(bench);
  std::string out =
      fmt::format(R"(<section class="bench" id="bench-{0}"><h2>Speed against error (bench {0})</h2>)", i.bench_id);
  out += fmt::format(
      R"(<p class="meta bench-info">Measured on <b>{}</b>, stored {} UTC, seed {}, rcsim {}; {} recording{}.</p>)",
      escape(i.machine), escape(i.created_utc), i.seed, escape(i.rcsim_version), recordings.size(),
      recordings.size() == 1 ? "" : "s");
  out +=
      R"(<p class="hint">Each fidelity level of the model and the signal-level reference, run on every recording of )"
      "the bench. Speed is sensor cycles per CPU second (all recordings: their sensor cycles summed over their CPU "
      "time summed; log scale); error is the GOSPA mean against the recording (all recordings: the mean of each "
      "one's GOSPA mean). A level is on the Pareto front (filled, joined) when no other level is at least as fast "
      "and at least as accurate and better in one of the two; hollow points are dominated. The dashed line is the "
      "noise floor: the reference "
      "against itself with another seed, the error no model can go below. The default level <code>full</code> is "
      "ringed.</p>";

  svg::ParetoSpec main;
  main.title = fmt::format("Speed against error, {} recording{}", recordings.size(), recordings.size() == 1 ? "" : "s");
  main.note = fmt::format("one point per level; error = mean over the recordings of each one's GOSPA mean{}",
                          all.noise_floor_m ? "" : "; no noise floor in this bench");
  main.x_label = "sensor cycles per CPU second (log scale; summed cycles / summed CPU time)";
  main.y_label = "GOSPA mean / m (mean over the recordings)";
  main.width_px = 900;
  main.height_px = 460;
  main.points = pareto_points(all);
  main.noise_floor_m = all.noise_floor_m;
  out += R"(<div class="figs">)" + svg::pareto_svg(main) + "</div>";

  if (recordings.size() > 1) {
    std::vector<BenchSummary> per_recording;
    for (const int r : recordings) per_recording.push_back(summarise_bench(bench, r));
    const svg::ParetoExtent extent = shared_extent(per_recording);
    out +=
        "<h3>Per recording</h3><p class=\"hint\">The same plot for each recording alone, on shared axes, with that "
        "recording's noise floor.</p><div class=\"figs\">";
    for (std::size_t k = 0; k < recordings.size(); ++k) {
      const BenchRow* first = nullptr;
      for (const BenchRow& row : bench.rows) {
        if (row.recording == recordings[k] && first == nullptr) first = &row;
      }
      svg::ParetoSpec small;
      small.title = fmt::format("#{} {}", recordings[k], svg::shorten(first->recording_name, 44));
      small.note = fmt::format("checksum {}, {} sensor cycles", first->recording_checksum, first->sensor_cycles);
      small.x_label = "sensor cycles per CPU s (log scale)";
      small.y_label = "GOSPA mean / m";
      small.width_px = 620;
      small.height_px = 330;
      small.legend = false;  // the main plot has it
      small.points = pareto_points(per_recording[k]);
      small.noise_floor_m = per_recording[k].noise_floor_m;
      small.extent = extent;
      out += svg::pareto_svg(small);
    }
    out += "</div>";
  }

  out += "<h3>Per level, over all recordings</h3>" + level_table(all);
  out +=
      "<p class=\"hint\">Sums over the recordings: sensor cycles, CPU time, merge artefacts, latency pairs. Means over "
      "the recordings: GOSPA, the targets-per-cycle ratio and the latency difference (of the recordings that have "
      "one). GOSPA / noise floor divides the mean GOSPA by the mean noise floor of the same recordings. "
      "\u2014: not measured (no CPU time for the noise floor, nothing recorded, no paired episode).</p>";
  out += "<h3>Per recording and level</h3>" + row_table(bench);
  out += parameters_block(i);
  out += "</section>\n";
  return out;
}

}  // namespace rcsim::replay::report
