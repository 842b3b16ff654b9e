#include "replay/report/real_drive_sections.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <set>

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

// One row per object and sensor, of at most kMaxObjectRows objects (objects_with_most_targets).
std::string object_detection_table(const RunData& run) {
  const std::set<int> shown = objects_with_most_targets(run);
  std::set<int> all;
  std::int64_t targets_all = 0, targets_shown = 0;
  for (const ObjectFigures& f : run.object_figures) {
    all.insert(f.object);
    targets_all += f.targets_recorded;
    if (shown.count(f.object) != 0) targets_shown += f.targets_recorded;
  }
  const auto rows = static_cast<std::size_t>(
      std::count_if(all.begin(), all.end(), [&shown](int o) { return shown.count(o) != 0; }));
  std::string out;
  if (rows < all.size()) {
    out += fmt::format(R"(<p class="hint objects-capped">The {} of {} objects in view with the most recorded targets )"
                       R"(({} of their {} recorded targets), in the order of the recording; every object counts in the )"
                       R"(table by class and range above.</p>)",
                       rows, all.size(), targets_shown, targets_all);
  }
  out += R"(<table class="objects-detection">)";
  out += header_row({"object", "class", "sensor", "cycles in view", "detection rate\nrecorded", "detection rate\nsimulated",
                     "targets per cycle\nrecorded", "targets per cycle\nsimulated"});
  for (const ObjectFigures& f : run.object_figures) {
    if (shown.count(f.object) == 0) continue;
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

// Per object class (run_objects.class) and bin of the nearest point's range, over all objects of
// the class and all sensors: object-cycles in view, object targets per object-cycle and the share
// detected, each side; then the class over all ranges. Targets per bin are not known in runs
// stored before schema v6.
std::string class_range_table(const RunData& run) {
  struct Sums {
    double to_m = 0.0;
    std::int64_t in_view = 0, detected[2] = {0, 0}, targets[2] = {0, 0};
    bool targets_known = true;
    void add(const ObjectRangeBin& b) {
      to_m = b.range_to_m;
      in_view += b.cycles_in_view;
      detected[0] += b.detected_recorded;
      detected[1] += b.detected_simulated;
      targets_known = targets_known && b.targets_recorded && b.targets_simulated;
      if (targets_known) targets[0] += *b.targets_recorded, targets[1] += *b.targets_simulated;
    }
  };
  std::map<std::string, std::pair<std::map<double, Sums>, Sums>> classes;  // class -> (bins by range_from_m, all)
  for (const ObjectRangeBin& b : run.object_ranges) {
    const ObjectInfo* info = object_info(run, b.object);
    auto& [bins, all] = classes[info ? info->object_class : "(unknown)"];
    bins[b.range_from_m].add(b);
    all.add(b);
  }
  bool unknown = false;
  const auto row = [&unknown](const std::string& object_class, const std::string& range, const Sums& s,
                              const char* css) {
    std::string per_cycle[2] = {"not known", "not known"}, ratio = "not known";
    if (s.targets_known) {
      for (int side = 0; side < 2; ++side) per_cycle[side] = num(rate(s.targets[side], s.in_view), 2);
      ratio = s.targets[0] > 0 ? num(rate(s.targets[1], s.targets[0]), 2) : "-";
    } else {
      unknown = true;
    }
    return fmt::format(R"(<tr class="{}">)", css) + cell(object_class) + cell_num(range) +
           cell_num(std::to_string(s.in_view)) + cell_num(per_cycle[0]) + cell_num(per_cycle[1]) + cell_num(ratio) +
           cell_num(percent(s.detected[0], s.in_view)) + cell_num(percent(s.detected[1], s.in_view)) + "</tr>";
  };
  std::string out = R"(<table class="objects-class-range">)";
  out += header_row({"class", "range / m", "object-cycles\nin view", "targets per\nobject-cycle\nrecorded",
                     "targets per\nobject-cycle\nsimulated", "simulated /\nrecorded", "detected\nrecorded",
                     "detected\nsimulated"});
  for (const auto& [object_class, sums] : classes) {
    for (const auto& [from_m, bin] : sums.first) {
      out += row(object_class, fmt::format("{}\u2013{}", num(from_m, 0), num(bin.to_m, 0)), bin, "bin");
    }
    out += row(object_class, "all", sums.second, "total");
  }
  out += "</table>";
  if (unknown) {
    out += R"(<p class="hint">Targets per range bin are not known for this run: it was stored before report schema )"
           R"(v6. Replay it again to see them.</p>)";
  } else if (run.summary && run.summary->classes) {
    std::int64_t binned[2] = {0, 0};
    for (const ObjectRangeBin& b : run.object_ranges) binned[0] += *b.targets_recorded, binned[1] += *b.targets_simulated;
    const auto& all = run.summary->classes->object;
    out += fmt::format(R"(<p class="hint">Targets: an object's targets of class object in the cycles it was in view, )"
                       R"({} of the run's {} recorded and {} of its {} simulated object targets; the others belong to )"
                       R"(boxes whose nearest point lay outside the field of view.</p>)",
                       binned[0], all[0], binned[1], all[1]);
  }
  return out;
}

// The W1 and KS of the object targets' offsets from their box's centre (x forward, y left), in a line.
std::string object_offset_line(const RunData& run) {
  std::string parts;
  std::int64_t n[2] = {0, 0};
  for (const char* axis : {"x", "y"}) {
    const auto d = std::find_if(run.distances.begin(), run.distances.end(), [axis](const DistanceRow& r) {
      return r.quantity == std::string("object_offset_") + axis;
    });
    if (d == run.distances.end()) {
      return R"(<p class="object-offsets">The offsets' distribution distances were not computed for this run (stored )"
             R"(by an earlier rcsim). Replay it again to see them.</p>)";
    }
    parts += fmt::format("{}{}: W1 {} {}, KS {}", parts.empty() ? "" : "; ", axis, opt(d->wasserstein1, 3, "-"),
                         svg::escape(d->unit), opt(d->kolmogorov_smirnov, 3, "-"));
    n[0] = d->n_recorded, n[1] = d->n_simulated;
  }
  return fmt::format(R"(<p class="object-offsets">Offsets of the object targets from their box's centre in the )"
                     R"(object's frame (x forward, y left), recorded against simulated, all objects and sensors: {} )"
                     R"(({} recorded, {} simulated targets; <code>wasserstein1.object_offset_x</code> and so on in )"
                     R"(criteria).</p>)",
                     parts, n[0], n[1]);
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
std::string object_frame_pictures(ReportDatabase& db, const RunData& run, int max_pictures) {
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
  std::vector<int> objects;
  for (const auto& [object, counts] : order) objects.push_back(object);
  auto targets = read_objects_frame_targets(db, run.info.run_id, objects, kPointsPerOrigin);
  std::string out = R"(<div class="figs">)";
  for (const auto& [object, counts] : order) {
    const ObjectInfo* info = object_info(run, object);
    svg::ObjectFrameSpec spec;
    spec.title = svg::shorten(run.object_label(object), 28);
    spec.notes.push_back(fmt::format("{} recorded, {} simulated targets", counts.first, counts.second));
    if (info) spec.length_m = info->length_m, spec.width_m = info->width_m;
    for (const ObjectFrameTarget& t : targets[object]) {
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

std::string object_section(ReportDatabase& db, const RunData& run, int max_pictures) {
  if (!run.summary || !run.summary->classes) {
    return "<p>This run was stored before report schema v3: it has no per-object figures. Replay it again.</p>";
  }
  if (run.object_figures.empty()) return "<p>No annotated object was in any sensor's field of view.</p>";
  std::string out = R"(<p class="hint">Per annotated object and sensor, over the cycles in which the box's nearest )"
                    R"(point lay in the sensor's field of view and range (occlusion not considered). Detected: at least )"
                    R"(one target within the association gate of the box.</p>)";
  out += "<h4>Objects by class and range</h4>";
  out += R"(<p class="hint">Per class and bin of the range of the box's nearest point, over all objects of the class )"
         R"(and all sensors: an object-cycle is one object in view of one sensor in one cycle.</p>)";
  out += R"(<div class="scroll">)" + class_range_table(run) + "</div>" + object_offset_line(run);
  out += "<h4>Per object</h4>";
  out += R"(<div class="cols"><div class="scroll">)" + object_detection_table(run) + "</div><div>" + detection_rate_plot(run) +
         "</div></div>";
  out += "<h4>Targets in each object's own frame, all cycles and sensors (paper Fig. 3)</h4>";
  out += run.info.has_targets() ? object_frame_pictures(db, run, max_pictures)
                                : needs_full_store("The pictures of the targets in each object's frame");
  return out;
}

std::string background_section(ReportDatabase& db, const RunData& run) {
  if (!run.summary || !run.summary->classes) {
    return "<p>This run was stored before report schema v3: it has no background figures. Replay it again.</p>";
  }
  const RunSummary::Classes& k = *run.summary->classes;
  const double sensor_cycles = std::max<double>(1.0, static_cast<double>(run.sensor_cycles()));
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
  const auto [range, azimuth] = read_background_histograms(db, run.info.run_id, {0.0, max_range_m / kBins, kBins},
                                                           {-half_rad, 2.0 * half_rad / kBins, kBins});
  out += background_plot(range, "Background: range", "range / m", 1.0);
  out += background_plot(azimuth, "Background: azimuth", "azimuth / deg", rad_to_deg(1.0));
  return out + "</div>";
}

}  // namespace rcsim::replay::report
