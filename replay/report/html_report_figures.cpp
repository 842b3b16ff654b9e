#include "replay/report/html_report_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

#include "common/angles.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

namespace {

const SensorInfo* find_sensor(const RunData& run, int sensor) {
  for (const auto& s : run.sensors) {
    if (s.sensor == sensor) return &s;
  }
  return nullptr;
}

}  // namespace

std::vector<ChosenCycle> choose_cycles(const CycleHighlights& found, const RunData& run, std::size_t max_count) {
  std::vector<ChosenCycle> chosen;
  const auto add = [&](int cycle, const std::string& reason) {
    for (auto& c : chosen) {
      if (c.cycle == cycle) {
        c.reason += "; " + reason;
        return;
      }
    }
    if (chosen.size() < max_count) chosen.push_back({cycle, reason});
  };
  if (found.largest_gospa && found.largest_gospa->value > 0.0) {
    add(found.largest_gospa->cycle, fmt::format("largest GOSPA ({:.2f} m, sensor {})", found.largest_gospa->value,
                                                run.sensor_label(found.largest_gospa->sensor)));
  }
  if (found.most_merge_artefacts) {
    add(found.most_merge_artefacts->cycle,
        fmt::format("most merge artefacts ({:.0f}, recorded + simulated)", found.most_merge_artefacts->value));
  }
  if (found.first_recorded) add(found.first_recorded->cycle, "first recorded target");
  if (run.info.cycles > 0) add(run.info.cycles / 2, "middle of the run");
  if (found.first_simulated) add(found.first_simulated->cycle, "first simulated target");
  if (found.largest_count_difference) {
    add(found.largest_count_difference->cycle,
        fmt::format("largest count difference ({:.0f})", found.largest_count_difference->value));
  }
  // Fill up with the last cycle and the quarters, so that quiet runs still show their course.
  if (run.info.cycles > 0) {
    add(run.info.cycles - 1, "last cycle");
    add(run.info.cycles / 4, "first quarter");
    add(3 * run.info.cycles / 4, "third quarter");
  }
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.cycle < b.cycle; });
  return chosen;
}

namespace {

// The cycle's title and notes: time, why it is pictured, counts and GOSPA per sensor.
void describe_cycle(const RunData& run, const ChosenCycle& chosen, const CycleWindow& window, svg::BirdsEyeSpec& spec) {
  double t_s = 0.0;
  long long n_recorded = 0, n_simulated = 0;
  std::string gospa_text;
  for (const CycleRow& c : window.cycles) {
    if (c.cycle != window.cycle) continue;
    t_s = c.t_s;
    n_recorded += c.n_recorded;
    n_simulated += c.n_simulated;
    gospa_text += fmt::format("{}{:.2f} m ({})", gospa_text.empty() ? "" : ", ", c.gospa_m, run.sensor_label(c.sensor));
  }
  spec.title = fmt::format("Cycle {} at t = {:.2f} s", window.cycle, t_s);
  spec.notes.push_back(chosen.reason);
  spec.notes.push_back(fmt::format("{} recorded / {} simulated targets; GOSPA {}", n_recorded, n_simulated,
                                   gospa_text.empty() ? "-" : gospa_text));
  if (spec.trace_cycles > 0) spec.notes.push_back(fmt::format("faded: the {} cycles before", spec.trace_cycles));
}

void add_boxes(const RunData& run, const CycleWindow& window, const Pose2& X_VW, svg::BirdsEyeSpec& spec) {
  for (const ObjectStateRow& state : window.objects) {
    svg::BirdsEyeBox box;
    box.label = svg::shorten(run.object_label(state.object), 14);
    box.X_VO = compose(X_VW, state.X_WO);
    for (const auto& o : run.objects) {
      if (o.object == state.object) box.length_m = o.length_m, box.width_m = o.width_m;
    }
    for (const auto& [a, b] : window.merge_pairs) box.in_merge_pair = box.in_merge_pair || a == state.object || b == state.object;
    spec.boxes.push_back(std::move(box));
  }
}

// Targets of the cycle and its traces, into the pictured cycle's vehicle frame, and the links
// of the pictured cycle's assigned pairs.
void add_targets(const CycleWindow& window, const std::map<std::pair<int, int>, Pose2>& X_WS, const Pose2& X_VW,
                 svg::BirdsEyeSpec& spec) {
  std::map<std::pair<int, int>, Vec2> simulated_now;              // (sensor, idx) -> p_V
  std::vector<std::pair<std::pair<int, int>, Vec2>> recorded_now;  // ((sensor, match), p_V)
  for (const TargetRow& row : window.targets) {
    const auto pose = X_WS.find({row.cycle, row.sensor});
    if (pose == X_WS.end()) continue;
    svg::BirdsEyeTarget t;
    t.simulated = row.simulated;
    t.age = window.cycle - row.cycle;
    t.merge_artefact = row.merge_artefact;
    t.target_class = row.target_class;
    spec.class_legend = spec.class_legend || !row.target_class.empty();
    t.p_V = transform_point(X_VW, transform_point(pose->second, row.p_ST_S));
    spec.targets.push_back(t);
    if (row.cycle != window.cycle) continue;
    if (t.simulated) {
      simulated_now[{row.sensor, row.idx}] = t.p_V;
    } else if (row.match_idx) {
      recorded_now.push_back({{row.sensor, *row.match_idx}, t.p_V});
    }
  }
  for (const auto& [key, p_V] : recorded_now) {
    const auto it = simulated_now.find(key);
    if (it != simulated_now.end()) spec.links.push_back({p_V, it->second});
  }
}

}  // namespace

svg::BirdsEyeSpec birdseye_of_cycle(const RunData& run, const ChosenCycle& chosen, const CycleWindow& window) {
  svg::BirdsEyeSpec spec;
  spec.trace_cycles = window.cycle - window.first_cycle;
  std::map<std::pair<int, int>, Pose2> X_WS;  // (cycle, sensor): sensor poses in the world
  for (const CycleRow& c : window.cycles) X_WS[{c.cycle, c.sensor}] = c.X_WS;
  // The vehicle pose from the first sensor: X_WV = X_WS * X_VS^-1.
  Pose2 X_VW;
  for (const auto& s : run.sensors) {
    const auto it = X_WS.find({window.cycle, s.sensor});
    if (it == X_WS.end()) continue;
    X_VW = inverse(compose(it->second, inverse(s.X_VS)));
    break;
  }
  describe_cycle(run, chosen, window, spec);
  for (const auto& s : run.sensors) spec.sensors.push_back({s.id, s.X_VS, s.azimuth_half_rad, s.max_range_m});
  add_boxes(run, window, X_VW, spec);
  add_targets(window, X_WS, X_VW, spec);
  return spec;
}

int series_stride(const RunData& run, int max_points) {
  const int cycles = std::max(1, run.info.cycles);
  return std::max(1, (cycles + max_points - 1) / std::max(1, max_points));
}

std::string every_nth_cycle(int stride) {
  if (stride == 1) return "every cycle";
  // 11th, 12th, 13th (and 111th ...) take "th" whatever their last digit.
  const int last = stride % 10, last_two = stride % 100;
  const char* suffix = (last_two >= 11 && last_two <= 13) ? "th" : last == 1 ? "st" : last == 2 ? "nd" : last == 3 ? "rd" : "th";
  return fmt::format("every {}{} cycle", stride, suffix);
}

std::vector<svg::PlotSpec> time_series(const RunData& run, int stride, const std::vector<NearestTargetRow>& nearest,
                                       const std::vector<CycleBucketRow>& buckets) {
  struct PerSensor {
    svg::PlotSeries range[2], lateral[2], count[2], gospa_mean, gospa_max;
  };
  std::map<int, PerSensor> series;
  for (const auto& s : run.sensors) series[s.sensor];
  for (const NearestTargetRow& row : nearest) {
    const SensorInfo* info = find_sensor(run, row.sensor);
    if (info == nullptr) continue;
    const int origin = row.simulated ? 1 : 0;
    const Vec2 p_V = transform_point(info->X_VS, row.p_ST_S);
    PerSensor& p = series[row.sensor];
    p.range[origin].points.emplace_back(row.t_s, row.range_m);
    p.lateral[origin].points.emplace_back(row.t_s, p_V.y());
  }
  // Counts and GOSPA: means (and the GOSPA maximum) over buckets of `stride` cycles.
  for (const CycleBucketRow& row : buckets) {
    PerSensor& p = series[row.sensor];
    p.count[0].points.emplace_back(row.t_s, row.recorded_mean);
    p.count[1].points.emplace_back(row.t_s, row.simulated_mean);
    p.gospa_mean.points.emplace_back(row.t_s, row.gospa_mean_m);
    p.gospa_max.points.emplace_back(row.t_s, row.gospa_max_m);
  }

  const std::string dots_note = stride > 1 ? every_nth_cycle(stride) + " shown" : "";
  const std::string mean_note = stride > 1 ? fmt::format("mean over {} cycles per point", stride) : "";
  std::vector<svg::PlotSpec> plots;
  for (auto& [sensor, p] : series) {
    const std::string name = run.sensor_label(sensor);
    const auto pair = [&](svg::PlotSeries (&s)[2], bool dots) {
      s[0].label = "recorded", s[0].colour = svg::kRecordedColour, s[0].dots = dots;
      s[1].label = "simulated", s[1].colour = svg::kSimulatedColour, s[1].dots = dots, s[1].dashed = !dots;
      return std::vector<svg::PlotSeries>{std::move(s[0]), std::move(s[1])};
    };
    if (run.info.has_targets()) {  // a summary run has no targets (html_report.cpp says so)
      plots.push_back({"Nearest object target range, sensor " + name, "t / s", "range / m", dots_note, 600, 250, false,
                       pair(p.range, true)});
      plots.push_back({"Nearest object target lateral position, sensor " + name, "t / s", "y / m (vehicle frame)",
                       dots_note, 600, 250, false, pair(p.lateral, true)});
    }
    plots.push_back({"Targets per cycle, sensor " + name, "t / s", "targets", mean_note, 600, 250, true,
                     pair(p.count, false)});
    std::vector<svg::PlotSeries> gospa;
    if (stride > 1) {
      p.gospa_max.label = "maximum", p.gospa_max.colour = "#adb5bd";
      gospa.push_back(std::move(p.gospa_max));
    }
    p.gospa_mean.label = stride > 1 ? "mean" : "GOSPA", p.gospa_mean.colour = "#212529";
    gospa.push_back(std::move(p.gospa_mean));
    plots.push_back({"GOSPA, sensor " + name, "t / s", "GOSPA / m", mean_note, 600, 250, true, std::move(gospa)});
  }
  return plots;
}

namespace {

struct ResidualQuantity {
  const char* title;
  const char* label;
  double scale;     // stored unit -> shown unit
  double min_span;  // in the shown unit
};
const ResidualQuantity kResidualQuantities[4] = {
    {"Range residual", "range, simulated - recorded / m", 1.0, 0.02},
    {"Azimuth residual", "azimuth, simulated - recorded / deg", 180.0 / kPi, 0.02},
    {"Range-rate residual", "range rate, simulated - recorded / (m/s)", 1.0, 0.02},
    {"Amplitude residual", "amplitude, simulated - recorded / dB", 1.0, 0.02}};

}  // namespace

int residual_sample_stride(const RunData& run) { return std::max(1, run.info.cycles / 5000); }

ResidualHistograms::ResidualHistograms(const ResidualSampleStats& sample, int bins) : histograms_(4) {
  for (std::size_t i = 0; i < 4; ++i) {
    const ResidualQuantity& quantity = kResidualQuantities[i];
    svg::HistogramSpec& h = histograms_[i];
    h.title = quantity.title;
    h.x_label = quantity.label;
    h.counts.assign(static_cast<std::size_t>(std::max(1, bins)), 0);
    double a = 0.0, b = 0.0;
    if (sample.count > 0) {
      // The view: the quartiles and three interquartile ranges beyond each (Tukey's far fences),
      // within the data. Quantiles, not the standard deviation: on a real drive a few pairs
      // 30 m/s apart made sigma so wide that the bulk fell into one bar. The rest is counted in
      // the end bins and noted.
      const double q1 = sample.q1[i] * quantity.scale, q3 = sample.q3[i] * quantity.scale;
      a = std::max(sample.min[i] * quantity.scale, q1 - 3.0 * (q3 - q1));
      b = std::min(sample.max[i] * quantity.scale, q3 + 3.0 * (q3 - q1));
    }
    svg::widen(a, b, quantity.min_span, 0.02);
    h.lo = a;
    h.bin_width = (b - a) / static_cast<double>(h.counts.size());
  }
}

void ResidualHistograms::add(const Residuals& residuals) {
  ++count_;
  for (std::size_t i = 0; i < 4; ++i) {
    svg::HistogramSpec& h = histograms_[i];
    const double v = residuals[i] * kResidualQuantities[i].scale;
    sum_[i] += v;
    sum_sq_[i] += v * v;
    const double bin = std::floor((v - h.lo) / h.bin_width);
    const double last = static_cast<double>(h.counts.size() - 1);
    if (bin < 0.0) ++h.below;
    if (bin > last) ++h.above;
    ++h.counts[static_cast<std::size_t>(std::clamp(bin, 0.0, last))];
  }
}

std::vector<svg::HistogramSpec> ResidualHistograms::specs() const {
  std::vector<svg::HistogramSpec> out = histograms_;
  for (std::size_t i = 0; i < 4 && count_ > 0; ++i) {
    const double n = static_cast<double>(count_);
    out[i].note = fmt::format("{} pairs, mean {:.3g}, RMS {:.3g}", count_, sum_[i] / n, std::sqrt(sum_sq_[i] / n));
  }
  return out;
}

}  // namespace rcsim::replay::report
