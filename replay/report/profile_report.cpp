#include "replay/report/profile_report.hpp"

#include <fmt/format.h>

#include "common/xml_escape.hpp"
#include "replay/report/html_report.hpp"
#include "replay/report/svg_plot.hpp"

namespace rcsim::replay {
namespace {

std::string figure_svg(const profile::DerivationFigure& f) {
  if (f.bin_width > 0.0) {
    svg::HistogramSpec h;
    h.title = f.title, h.x_label = f.x_label, h.y_label = f.y_label, h.note = f.note;
    h.lo = f.lo, h.bin_width = f.bin_width, h.counts = f.counts, h.zero_line = false;
    h.markers.push_back({f.marker, f.marker_label});
    return svg::histogram_svg(h);
  }
  svg::PlotSpec p;
  p.title = f.title, p.x_label = f.x_label, p.y_label = f.y_label, p.note = f.note;
  p.y_from_zero = f.y_from_zero;
  const char* colours[] = {svg::kRecordedColour, svg::kSimulatedColour, "#2b8a3e"};
  for (std::size_t i = 0; i < f.series.size(); ++i) {
    p.series.push_back({f.series[i].label, colours[i % 3], f.series[i].dots, false, f.series[i].points});
  }
  return svg::plot_svg(p);
}

}  // namespace

void write_profile_report(std::ostream& out, const profile::ProfileDerivation& d, const std::string& profile_file) {
  const std::string name = d.profile.value("name", "");
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>rcsim profile derive: " << xml_escape(name)
      << "</title><style>" << report_stylesheet() << "</style></head><body>\n";
  out << "<h1>Sensor profile " << xml_escape(name) << ", derived from recordings</h1>\n";
  out << fmt::format("<p class=\"meta\">{} detections in {} sensor cycles; base {}; written to {}. Every value below is "
                     "<b>derived</b> (read off the recordings), from the <b>recording</b>'s header, or the <b>base</b>'s "
                     "(the data cannot show it; rcsim calibrate --real-drive fits some of those).</p>\n",
                     d.detections, d.sensor_cycles, xml_escape(d.base), xml_escape(profile_file));
  out << "<h2>Values</h2>\n<div class=\"scroll\"><table><tr><th>field</th><th>value</th><th>source</th><th>interval</th>"
         "<th>evidence</th><th>support</th></tr>\n";
  for (const auto& v : d.values) {
    out << fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td><td "
                       "class=\"num\">{}</td></tr>\n",
                       xml_escape(v.field), xml_escape(profile::value_text(v.value)), xml_escape(profile::source_text(v)),
                       xml_escape(profile::interval_text(v)), xml_escape(v.evidence), v.support > 0 ? std::to_string(v.support) : "");
  }
  out << "</table></div>\n<h2>The fits</h2>\n<div class=\"figs\">\n";
  for (const auto& f : d.figures) out << figure_svg(f) << '\n';
  out << "</div>\n</body></html>\n";
}

}  // namespace rcsim::replay
