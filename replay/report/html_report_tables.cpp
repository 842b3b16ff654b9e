#include "replay/report/html_report_tables.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <nlohmann/json.hpp>

#include "common/angles.hpp"
#include "common/json_reader.hpp"
#include "replay/report/html_cells.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

using svg::escape;

std::string run_information_table(const RunData& run) {
  const RunInfo& i = run.info;
  std::string out = R"(<table class="kv run-info">)";
  out += kv("recording", "recording", i.recording_name, "", true);
  out += kv("recording_dir", "recording directory", i.recording_dir, "", true);
  out += kv("checksum", "recording checksum (FNV-1a 64)", i.recording_checksum, "", true);
  out += kv("seed", "seed", std::to_string(i.seed), "");
  if (run.on_own_clocks()) {
    // Each cycle is one sensor's (recording v4): the duration from the cycles' own times.
    double first_s = INFINITY, last_s = -INFINITY;
    for (const SensorTotals& t : run.sensor_totals) first_s = std::min(first_s, t.first_t_s), last_s = std::max(last_s, t.last_t_s);
    out += kv("cycles", "cycles", std::to_string(i.cycles),
              fmt::format("of {} sensor{}, each on its own clock", run.sensors.size(), run.sensors.size() == 1 ? "" : "s"));
    out += kv("cycle_time", "annotation step", num(i.cycle_time_s, 4), "s");
    out += kv("duration", "duration", num(last_s - first_s, 1), "s");
  } else {
    out += kv("cycles", "cycles", std::to_string(i.cycles),
              fmt::format("x {} sensor{}", run.sensors.size(), run.sensors.size() == 1 ? "" : "s"));
    out += kv("cycle_time", "cycle time", num(i.cycle_time_s, 4), "s");
    out += kv("duration", "duration", num(i.cycle_time_s * i.cycles, 1), "s");
  }
  out += kv("level", "compared level", i.level, "", true);
  out += kv("rcsim_version", "rcsim version", i.rcsim_version, "", true);
  out += kv("created", "stored", i.created_utc, "UTC", true);
  out += kv("store", "store level", i.store, "rcsim replay --store", true);
  return out + "</table>";
}

std::string summary_table(const RunData& run) {
  if (!run.summary) return R"(<p class="warn">This run has no summary row (damaged database).</p>)";
  const RunSummary& s = *run.summary;
  std::string out = R"(<table class="kv summary">)";
  out += kv("targets_recorded", "targets recorded", std::to_string(s.targets_recorded), "");
  out += kv("targets_simulated", "targets simulated", std::to_string(s.targets_simulated),
            s.targets_recorded > 0 ? fmt::format("{:.3f} x recorded", static_cast<double>(s.targets_simulated) /
                                                                          static_cast<double>(s.targets_recorded))
                                   : "");
  out += kv("targets_matched", "targets matched (assigned pairs)", std::to_string(s.targets_matched),
            percent(s.targets_matched, s.targets_recorded) + " of recorded");
  out += kv("gospa_mean", "GOSPA, mean over cycles and sensors", num(s.gospa_mean_m, 3), "m");
  out += kv("gospa_localisation", "  localisation part (mean)", num(s.gospa_localisation_mean_mp, 3), "mᵖ");
  out += kv("gospa_missed", "  missed part (mean)", num(s.gospa_missed_mean_mp, 3), "mᵖ");
  out += kv("gospa_false", "  false part (mean)", num(s.gospa_false_mean_mp, 3), "mᵖ");
  out += kv("ospa_mean", "OSPA, mean", num(s.ospa_mean_m, 3), "m");
  if (s.classes) {
    const RunSummary::Classes& k = *s.classes;
    out += kv("gospa_object_mean", "GOSPA on the object targets, mean", num(k.gospa_object_mean_m, 3), "m");
    out += kv("ospa_object_mean", "OSPA on the object targets, mean", num(k.ospa_object_mean_m, 3), "m");
    out += kv("targets_object", "object targets, recorded / simulated",
              fmt::format("{} / {}", k.object[0], k.object[1]), percent(k.object[0], s.targets_recorded) + " of recorded");
    out += kv("targets_background", "stationary background, recorded / simulated",
              fmt::format("{} / {}", k.background[0], k.background[1]),
              percent(k.background[0], s.targets_recorded) + " of recorded");
    out += kv("targets_other", "other targets, recorded / simulated", fmt::format("{} / {}", k.other[0], k.other[1]),
              percent(k.other[0], s.targets_recorded) + " of recorded");
  }
  out += kv("residual_range_rms", "residual RMS, range", num(s.residual_range_rms_m, 3), "m");
  out += kv("residual_azimuth_rms", "residual RMS, azimuth", deg(s.residual_azimuth_rms_rad, 3), "deg");
  out += kv("residual_range_rate_rms", "residual RMS, range rate", num(s.residual_range_rate_rms_mps, 3), "m/s");
  out += kv("residual_amplitude_mean", "residual mean, amplitude", num(s.residual_amplitude_mean_db, 2), "dB");
  out += kv("merge_recorded", "merge artefacts recorded", std::to_string(s.merge_recorded), "targets");
  out += kv("merge_simulated", "merge artefacts simulated", std::to_string(s.merge_simulated), "targets");
  out += kv("merge_matched", "merge artefacts matched", std::to_string(s.merge_matched),
            s.classes ? "recorded ones with a simulated one of the same pair and cycle within the match distance"
                      : "in both, per pair and cycle (counted, before schema v3)");
  if (s.classes) {  // schema v3: each side over the episodes it confirmed; the paired difference
    const RunSummary::Classes& k = *s.classes;
    out += kv("latency_recorded", "confirmation latency recorded, mean", opt(s.latency_recorded_s, 3, "-"),
              fmt::format("s, over {} of {} episodes confirmed", k.latency_episodes - k.latency_unconfirmed[0],
                          k.latency_episodes));
    out += kv("latency_simulated", "confirmation latency simulated, mean", opt(s.latency_simulated_s, 3, "-"),
              fmt::format("s, over {} of {} episodes confirmed", k.latency_episodes - k.latency_unconfirmed[1],
                          k.latency_episodes));
    out += kv("latency_difference", "latency simulated - recorded, mean", opt(k.latency_difference_mean_s, 3, "-"),
              fmt::format("s, over {} episodes confirmed by both", s.latency_pairs));
  } else {
    out += kv("latency_recorded", "confirmation latency recorded, mean", opt(s.latency_recorded_s, 3, "-"),
              fmt::format("s, over {} object-sensor pairs reported in both", s.latency_pairs));
    out += kv("latency_simulated", "confirmation latency simulated, mean", opt(s.latency_simulated_s, 3, "-"), "s");
  }
  out += kv("simulate_cpu", "simulation CPU time", num(s.simulate_cpu_s, 3), "s");
  out += kv("total_wall", "replay wall time (import, simulation, metrics, storage)", num(s.total_wall_s, 3), "s");
  return out + "</table>";
}

std::string sensor_table(const RunData& run) {
  std::string out = R"(<table class="sensors">)";
  out += header_row({"sensor", "type", "x / m", "y / m", "yaw / deg", "FOV / deg", "max range / m", "cycles",
                     "recorded", "simulated", "assigned", "GOSPA mean / m", "GOSPA max / m", "OSPA mean / m",
                     "merge rec.", "merge sim.", "merge matched"});
  for (const SensorInfo& s : run.sensors) {
    SensorTotals t;
    for (const auto& row : run.sensor_totals) {
      if (row.sensor == s.sensor) t = row;
    }
    out += "<tr>" + cell(s.id) + cell(s.type) + cell_num(num(s.X_VS.x_m, 2)) + cell_num(num(s.X_VS.y_m, 2)) +
           cell_num(deg(s.X_VS.yaw_rad, 1)) + cell_num("\u00b1" + deg(s.azimuth_half_rad, 1)) +
           cell_num(num(s.max_range_m, 1)) + cell_num(std::to_string(t.cycles)) + cell_num(std::to_string(t.recorded)) +
           cell_num(std::to_string(t.simulated)) + cell_num(std::to_string(t.assigned)) +
           cell_num(num(t.gospa_mean_m, 3)) + cell_num(num(t.gospa_max_m, 3)) + cell_num(num(t.ospa_mean_m, 3)) +
           cell_num(std::to_string(t.merge_recorded)) + cell_num(std::to_string(t.merge_simulated)) +
           cell_num(std::to_string(t.merge_matched)) + "</tr>";
  }
  return out + "</table>";
}

std::set<int> objects_with_most_targets(const RunData& run) {
  std::map<int, std::int64_t> recorded;  // object -> recorded targets
  for (const ObjectInfo& o : run.objects) recorded[o.object] += 0;
  for (const ObjectFigures& f : run.object_figures) recorded[f.object] += f.targets_recorded;
  std::vector<std::pair<int, std::int64_t>> order(recorded.begin(), recorded.end());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  if (order.size() > kMaxObjectRows) order.resize(kMaxObjectRows);
  std::set<int> shown;
  for (const auto& entry : order) shown.insert(entry.first);
  return shown;
}

std::string object_table(const RunData& run) {
  if (run.objects.empty()) return "<p>The recording has no annotated objects.</p>";
  std::string out;
  const std::set<int> shown = objects_with_most_targets(run);
  if (shown.size() < run.objects.size()) {
    std::map<std::string, int> classes;
    for (const ObjectInfo& o : run.objects) ++classes[o.object_class];
    std::string counts;
    for (const auto& [name, n] : classes) counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", n, name);
    out += R"(<p class="hint objects-capped">)" +
           escape(fmt::format("The {} of {} annotated objects with the most recorded targets, in the order of the "
                              "recording; by class: {}.",
                              shown.size(), run.objects.size(), counts)) +
           "</p>";
  }
  out += R"(<table class="objects">)";
  out += header_row({"#", "object", "class (model)", "length / m", "width / m", "reflectors"});
  for (const ObjectInfo& o : run.objects) {
    if (shown.count(o.object) == 0) continue;
    out += "<tr>" + cell_num(std::to_string(o.object)) + cell(o.id) + cell(o.object_class) +
           cell_num(num(o.length_m, 2)) + cell_num(num(o.width_m, 2)) + cell_num(std::to_string(o.reflectors)) + "</tr>";
  }
  return out + "</table>";
}

std::string distance_table(const RunData& run, bool background) {
  std::string out = R"(<table class="distances">)";
  out += header_row({"quantity", "unit", "W1 (area metric)", "KS statistic", "n recorded", "n simulated"});
  for (const DistanceRow& d : run.distances) {
    if (d.quantity.starts_with("background_") != background || d.quantity.starts_with("object_offset_")) continue;
    out += "<tr>" + cell(d.quantity) + cell(d.unit) + cell_num(opt(d.wasserstein1, 4, "-")) +
           cell_num(opt(d.kolmogorov_smirnov, 4, "-")) + cell_num(std::to_string(d.n_recorded)) +
           cell_num(std::to_string(d.n_simulated)) + "</tr>";
  }
  return out + "</table>";
}

std::string merge_artefact_table(const RunData& run) {
  if (run.merge_pairs.empty()) {
    return "<p>No two objects shared a range-speed resolution cell in any cycle: no merge artefacts expected.</p>";
  }
  std::string out = R"(<table class="merge">)";
  out += header_row({"object A", "object B", "sensor", "cycles sharing a cell", "first / s", "last / s",
                     "artefacts recorded", "artefacts simulated", "matched"});
  for (const MergePairRow& m : run.merge_pairs) {
    out += "<tr>" + cell(run.object_label(m.object_a)) + cell(run.object_label(m.object_b)) +
           cell(run.sensor_label(m.sensor)) + cell_num(std::to_string(m.cycles)) + cell_num(num(m.first_t_s, 2)) +
           cell_num(num(m.last_t_s, 2)) + cell_num(std::to_string(m.recorded)) + cell_num(std::to_string(m.simulated)) +
           cell_num(std::to_string(m.matched)) + "</tr>";
  }
  out += "</table>";
  out += "<p class=\"hint\">Artefact counts are those of the cycles in which the pair shares a cell (a cycle with "
         "several pairs counts its artefacts for each).</p>";
  return out;
}

std::string latency_table(const RunData& run) {
  if (run.latencies.empty()) return "<p>No object became detectable for any sensor.</p>";
  std::string out = R"(<table class="latency">)";
  out += header_row({"object", "class", "sensor", "detectable from / s", "confirmed recorded / s",
                     "confirmed simulated / s", "latency recorded / s", "latency simulated / s",
                     "simulated - recorded / s"});
  for (const LatencyRow& l : run.latencies) {
    std::string object_class;
    for (const auto& o : run.objects) {
      if (o.object == l.object) object_class = o.object_class;
    }
    const std::optional<double> diff = l.latency_recorded_s && l.latency_simulated_s
                                           ? std::optional<double>(*l.latency_simulated_s - *l.latency_recorded_s)
                                           : std::nullopt;
    out += "<tr>" + cell(run.object_label(l.object)) + cell(object_class) + cell(run.sensor_label(l.sensor)) +
           cell_num(num(l.detectable_from_s, 3)) + cell_num(opt(l.first_recorded_s, 3, "never (censored)")) +
           cell_num(opt(l.first_simulated_s, 3, "never (censored)")) + cell_num(opt(l.latency_recorded_s, 3, "-")) +
           cell_num(opt(l.latency_simulated_s, 3, "-")) + cell_num(opt(diff, 3, "-")) + "</tr>";
  }
  return out + "</table>";
}

std::string parameter_table(const RunData& run) {
  const nlohmann::ordered_json parameters = parse_stored_json(run.info.parameters);
  if (parameters.is_discarded() || !parameters.is_object()) {
    return "<pre>" + escape(run.info.parameters) + "</pre>";
  }
  const auto value_text = [](const nlohmann::ordered_json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); };
  std::string out = R"(<table class="parameters">)";
  out += header_row({"metric / step", "parameters", "source"});
  for (const auto& [name, value] : parameters.items()) {
    std::string params, source;
    if (value.is_object()) {
      for (const auto& [key, v] : value.items()) {
        if (key == "source") {
          source = value_text(v);
        } else if (v.is_object()) {
          for (const auto& [sub_key, sub] : v.items()) {
            params += "<div>" + escape(key + "." + sub_key) + " = " + escape(value_text(sub)) + "</div>";
          }
        } else {
          params += "<div>" + escape(key) + " = " + escape(value_text(v)) + "</div>";
        }
      }
    } else {
      params = escape(value_text(value));
    }
    out += "<tr>" + cell(name) + "<td>" + params + "</td>" + cell(source) + "</tr>";
  }
  return out + "</table>";
}

std::string provenance_blocks(const RunData& run) {
  std::string source = run.info.recording_source;
  const nlohmann::ordered_json parsed = parse_stored_json(source);
  if (!parsed.is_discarded()) source = parsed.dump(2);
  std::string out = "<details><summary>Recording provenance (recording.json <code>source</code>)</summary><pre>" +
                    escape(source) + "</pre></details>";
  for (const SensorInfo& s : run.sensors) {
    out += "<details><summary>Sensor configuration of " + escape(s.id) + " (" + escape(s.type) + ")</summary><pre>" +
           escape(s.configuration) + "</pre></details>";
  }
  return out;
}

std::string comparison_table(const std::vector<RunData>& runs, const std::map<std::int64_t, RunLabel>& labels) {
  std::string out = R"(<div class="scroll"><table class="comparison"><tr><th>quantity</th>)";
  for (const RunData& r : runs) {
    out += fmt::format(R"(<th><a href="#run-{0}">run {0}</a></th>)", r.info.run_id);
  }
  out += "</tr>";
  const auto row = [&](const std::string& label, const std::function<std::string(const RunData&)>& value) {
    out += "<tr><th>" + escape(label) + "</th>";
    const bool text = label.rfind("recording", 0) == 0 || label == "sensor profiles" || label == "fidelity" ||
                      label == "effects" || label == "calibration" || label == "compared";
    for (const RunData& r : runs) out += text ? cell(value(r)) : cell_num(value(r));
    out += "</tr>";
  };
  const auto summary = [](const std::function<std::string(const RunSummary&)>& f) {
    return [f](const RunData& r) { return r.summary ? f(*r.summary) : std::string("-"); };
  };
  row("recording", [](const RunData& r) { return r.info.recording_name; });
  // What tells the runs apart (run_identity.hpp's RunLabel).
  const auto labelled = [&labels](std::string RunLabel::*field) {
    return [&labels, field](const RunData& r) {
      const auto it = labels.find(r.info.run_id);
      return it == labels.end() ? std::string("-") : it->second.*field;
    };
  };
  row("compared", labelled(&RunLabel::level));
  row("sensor profiles", labelled(&RunLabel::sensors));
  row("fidelity", labelled(&RunLabel::fidelity));
  row("effects", labelled(&RunLabel::effects));
  row("calibration", [&labels](const RunData& r) {
    const auto it = labels.find(r.info.run_id);
    if (it == labels.end() || it->second.calibration.empty()) return std::string("none");
    const RunLabel& l = it->second;
    return l.calibration + (l.calibration_checksum.empty() ? "" : " #" + l.calibration_checksum.substr(0, 8));
  });
  row("seed", [](const RunData& r) { return std::to_string(r.info.seed); });
  row("cycles x sensors", [](const RunData& r) {
    return r.on_own_clocks() ? fmt::format("{} on their own clocks", r.sensor_cycles())
                             : fmt::format("{} x {}", r.info.cycles, r.sensors.size());
  });
  row("targets recorded", summary([](const RunSummary& s) { return std::to_string(s.targets_recorded); }));
  row("targets simulated", summary([](const RunSummary& s) { return std::to_string(s.targets_simulated); }));
  row("targets matched", summary([](const RunSummary& s) { return std::to_string(s.targets_matched); }));
  row("GOSPA mean / m", summary([](const RunSummary& s) { return num(s.gospa_mean_m, 3); }));
  row("  localisation / mᵖ", summary([](const RunSummary& s) { return num(s.gospa_localisation_mean_mp, 3); }));
  row("  missed / mᵖ", summary([](const RunSummary& s) { return num(s.gospa_missed_mean_mp, 3); }));
  row("  false / mᵖ", summary([](const RunSummary& s) { return num(s.gospa_false_mean_mp, 3); }));
  row("OSPA mean / m", summary([](const RunSummary& s) { return num(s.ospa_mean_m, 3); }));
  row("residual RMS range / m", summary([](const RunSummary& s) { return num(s.residual_range_rms_m, 3); }));
  row("residual RMS azimuth / deg", summary([](const RunSummary& s) { return deg(s.residual_azimuth_rms_rad, 3); }));
  row("residual RMS range rate / (m/s)", summary([](const RunSummary& s) { return num(s.residual_range_rate_rms_mps, 3); }));
  row("residual mean amplitude / dB", summary([](const RunSummary& s) { return num(s.residual_amplitude_mean_db, 2); }));
  row("merge artefacts rec. / sim. / matched", summary([](const RunSummary& s) {
        return fmt::format("{} / {} / {}", s.merge_recorded, s.merge_simulated, s.merge_matched);
      }));
  row("latency recorded / s", summary([](const RunSummary& s) { return opt(s.latency_recorded_s, 3, "-"); }));
  row("latency simulated / s", summary([](const RunSummary& s) { return opt(s.latency_simulated_s, 3, "-"); }));
  // Distribution distances, per quantity of the first run that has them.
  std::vector<std::pair<std::string, std::string>> quantities;
  for (const RunData& r : runs) {
    for (const auto& d : r.distances) {
      bool known = false;
      for (const auto& q : quantities) known = known || q.first == d.quantity;
      if (!known) quantities.emplace_back(d.quantity, d.unit);
    }
  }
  for (const auto& [quantity, unit] : quantities) {
    row("W1 / KS " + quantity + " (" + unit + ")", [&, q = quantity](const RunData& r) {
      for (const auto& d : r.distances) {
        if (d.quantity == q) return opt(d.wasserstein1, 3, "-") + " / " + opt(d.kolmogorov_smirnov, 3, "-");
      }
      return std::string("-");
    });
  }
  return out + "</table></div>";
}

}  // namespace rcsim::replay::report
