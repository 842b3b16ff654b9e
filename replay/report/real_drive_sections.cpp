#include "replay/report/real_drive_sections.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>

#include "replay/report/html_cells.hpp"
#include "replay/report/html_report_tables.hpp"
#include "replay/report/svg_object_frame.hpp"
#include "replay/report/svg_plot.hpp"
#include "replay/store/figure_reader.hpp"

namespace rcsim::replay::report {

namespace {

constexpr int kPointsPerOrigin = 2000;  // per object picture

double rate(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

const ObjectInfo* object_info(const RunData& run, int object) {
  for (const auto& o : run.objects) {
    if (o.object == object) return &o;
  }
  return nullptr;
}

std::string object_detection_table(const RunData& run) {
  std::string out = R"(<table class="objects-detection">)";
  out += header_row({"object", "class", "sensor", "cycles in view", "detection rate\nrecorded", "detection rate\nsimulated",
                     "targets per cycle\nrecorded", "targets per cycle\nsimulated"});
  for (const ObjectFigures& f : run.object_figures) {
    const ObjectInfo* info = object_info(run, f.object);
    out += "<tr>" + cell(run.object_label(f.object)) + cell(info ? info->object_class : "") +
           cell(run.sensor_label(f.sensor)) + cell_num(std::to_string(f.cycles_in_view)) +
           cell_num(percent(f.detected_recorded, f.cycles_in_view)) +
           cell_num(percent(f.detected_simulated, f.cycles_in_view)) +
           cell_num(num(rate(f.targets_recorded, f.cycles_in_view), 2)) +
           cell_num(num(rate(f.targets_simulated, f.cycles_in_view), 2)) + "</tr>";
  }
  return out + "</table>";
}

// Detection rate against the range of the box's nearest point, over all objects and sensors.
std::string detection_rate_plot(const RunData& run) {
  struct Bin {
    double to_m = 0.0;
    std::int64_t in_view = 0, recorded = 0, simulated = 0;
  };
  std::map<double, Bin> bins;  // by range_from_m
  for (const ObjectRangeBin& b : run.object_ranges) {
    Bin& bin = bins[b.range_from_m];
    bin.to_m = b.range_to_m;
    bin.in_view += b.cycles_in_view;
    bin.recorded += b.detected_recorded;
    bin.simulated += b.detected_simulated;
  }
  svg::PlotSpec plot;
  plot.title = "Detection rate against range, all annotated objects";
  plot.x_label = "range of the box's nearest point / m";
  plot.y_label = "cycles detected / in view";
  plot.y_from_zero = true;
  svg::PlotSeries recorded{"recorded", svg::kRecordedColour, false, false, {}};
  svg::PlotSeries simulated{"simulated", svg::kSimulatedColour, false, true, {}};
  std::int64_t cycles = 0;
  for (const auto& [from_m, bin] : bins) {
    const double centre_m = 0.5 * (from_m + bin.to_m);
    recorded.points.emplace_back(centre_m, rate(bin.recorded, bin.in_view));
    simulated.points.emplace_back(centre_m, rate(bin.simulated, bin.in_view));
    cycles += bin.in_view;
  }
  plot.note = fmt::format("{} object-sensor cycles in view, in bins of {} m", cycles,
                          bins.empty() ? std::string("-") : num(bins.begin()->second.to_m - bins.begin()->first, 0));
  plot.series = {recorded, simulated};
  return svg::plot_svg(plot);
}

// The objects with the most recorded targets, each in its own frame.
std::string object_frame_pictures(SQLite::Database& db, const RunData& run, int max_pictures) {
  std::map<int, std::pair<std::int64_t, std::int64_t>> totals;  // object -> (recorded, simulated)
  for (const ObjectFigures& f : run.object_figures) {
    totals[f.object].first += f.targets_recorded;
    totals[f.object].second += f.targets_simulated;
  }
  std::vector<std::pair<int, std::pair<std::int64_t, std::int64_t>>> order(totals.begin(), totals.end());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return a.second.first + a.second.second > b.second.first + b.second.second;
  });
  if (order.size() > static_cast<std::size_t>(std::max(0, max_pictures))) order.resize(static_cast<std::size_t>(std::max(0, max_pictures)));
  std::string out = R"(<div class="figs">)";
  for (const auto& [object, counts] : order) {
    const ObjectInfo* info = object_info(run, object);
    svg::ObjectFrameSpec spec;
    spec.title = svg::shorten(run.object_label(object), 28);
    spec.notes.push_back(fmt::format("{} recorded, {} simulated targets", counts.first, counts.second));
    if (info) spec.length_m = info->length_m, spec.width_m = info->width_m;
    for (const ObjectFrameTarget& t : read_object_frame_targets(db, run.info.run_id, object, kPointsPerOrigin)) {
      spec.targets.push_back({t.p_OT_O, t.simulated});
    }
    if (counts.first > kPointsPerOrigin || counts.second > kPointsPerOrigin) {
      spec.notes.push_back(fmt::format("at most {} of each drawn, evenly thinned", kPointsPerOrigin));
    }
    out += svg::object_frame_svg(spec);
  }
  return out + "</div>";
}

// The background's share of recorded bins, recorded against simulated, as two lines.
std::string background_plot(const BackgroundHistogram& h, const std::string& title, const std::string& x_label,
                            double x_scale) {
  svg::PlotSpec plot;
  plot.title = title;
  plot.x_label = x_label;
  plot.y_label = "fraction";
  plot.y_from_zero = true;
  std::int64_t n[2] = {0, 0};
  for (int origin = 0; origin < 2; ++origin) {
    for (const std::int64_t c : h.counts[static_cast<std::size_t>(origin)]) n[origin] += c;
  }
  plot.note = fmt::format("{} recorded, {} simulated background targets", n[0], n[1]);
  for (int origin = 0; origin < 2; ++origin) {
    svg::PlotSeries series{origin == 0 ? "recorded" : "simulated",
                           origin == 0 ? svg::kRecordedColour : svg::kSimulatedColour, false, origin == 1, {}};
    const auto& counts = h.counts[static_cast<std::size_t>(origin)];
    for (std::size_t b = 0; b < counts.size() && n[origin] > 0; ++b) {
      const double centre = h.lo + (static_cast<double>(b) + 0.5) * h.bin_width;
      series.points.emplace_back(centre * x_scale, rate(counts[b], n[origin]));
    }
    plot.series.push_back(std::move(series));
  }
  return svg::plot_svg(plot);
}

}  // namespace

std::string object_section(SQLite::Database& db, const RunData& run, int max_pictures) {
  if (!run.summary || !run.summary->classes) {
    return "<p>This run was stored before report schema v3: it has no per-object figures. Replay it again.</p>";
  }
  if (run.object_figures.empty()) return "<p>No annotated object was in any sensor's field of view.</p>";
  std::string out = R"(<p class="hint">Per annotated object and sensor, over the cycles in which the box's nearest )"
                    R"(point lay in the sensor's field of view and range (occlusion not considered). Detected: at least )"
                    R"(one target within the association gate of the box.</p>)";
  out += R"(<div class="cols"><div class="scroll">)" + object_detection_table(run) + "</div><div>" + detection_rate_plot(run) +
         "</div></div>";
  out += "<h4>Targets in each object's own frame, all cycles and sensors (paper Fig. 3)</h4>";
  out += run.info.has_targets() ? object_frame_pictures(db, run, max_pictures)
                                : needs_full_store("The pictures of the targets in each object's frame");
  return out;
}

std::string background_section(SQLite::Database& db, const RunData& run) {
  if (!run.summary || !run.summary->classes) {
    return "<p>This run was stored before report schema v3: it has no background figures. Replay it again.</p>";
  }
  const RunSummary::Classes& k = *run.summary->classes;
  const double sensor_cycles = std::max<double>(1.0, static_cast<double>(run.summary->cycles * run.sensors.size()));
  std::string out = R"(<p class="hint">Targets on no annotated box whose radial speed, compensated for the ego )"
                    R"(motion, is near zero: guard rails, signs, the road. The model holds only what the scene holds, )"
                    R"(so a recording's background is what it leaves out.</p>)";
  out += R"(<div class="cols"><div><table class="kv background">)";
  out += kv("background_recorded", "background targets recorded", std::to_string(k.background[0]),
            num(static_cast<double>(k.background[0]) / sensor_cycles, 2) + " per sensor cycle");
  out += kv("background_simulated", "background targets simulated", std::to_string(k.background[1]),
            num(static_cast<double>(k.background[1]) / sensor_cycles, 2) + " per sensor cycle");
  out += "</table></div><div>" + distance_table(run, true) + "</div></div>";
  double max_range_m = 1.0, half_rad = 0.1;
  for (const SensorInfo& s : run.sensors) {
    max_range_m = std::max(max_range_m, s.max_range_m);
    half_rad = std::max(half_rad, s.azimuth_half_rad);
  }
  if (!run.info.has_targets()) return out + needs_full_store("The background's range and azimuth histograms");
  constexpr int kBins = 30;
  out += R"(<div class="figs">)";
  out += background_plot(read_background_histogram(db, run.info.run_id, BackgroundQuantity::range, 0.0,
                                                   max_range_m / kBins, kBins),
                         "Background: range", "range / m", 1.0);
  out += background_plot(read_background_histogram(db, run.info.run_id, BackgroundQuantity::azimuth, -half_rad,
                                                   2.0 * half_rad / kBins, kBins),
                         "Background: azimuth", "azimuth / deg", rad_to_deg(1.0));
  return out + "</div>";
}

}  // namespace rcsim::replay::report
