#include "replay/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::svg {

namespace {

struct Frame {
  double left, top, right, bottom;  // plot area in pixels
};


void open_svg(std::string& out, int width_px, int height_px, const std::string& css_class, const std::string& title) {
  out += fmt::format(R"(<svg class="{}" xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" role="img" aria-label="{}">)",
                     css_class, width_px, height_px, width_px, height_px, escape(title));
  out += fmt::format(R"(<rect class="bg" x="0" y="0" width="{}" height="{}" fill="#fff"/>)", width_px, height_px);
  out += fmt::format(R"(<text x="8" y="16" class="title">{}</text>)", escape(title));
}

// Grid, frame, ticks and axis labels.
void draw_axes(std::string& out, const Frame& f, const LinearScale& sx, const LinearScale& sy, const Ticks& tx,
               const Ticks& ty, const std::string& x_label, const std::string& y_label) {
  out += R"(<g class="grid" stroke="#e3e3e3" stroke-width="1">)";
  for (const double v : tx.values) {
    out += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}"/>)", coord(sx(v)), coord(f.top), coord(f.bottom));
  }
  for (const double v : ty.values) {
    out += fmt::format(R"(<line x1="{1}" y1="{0}" x2="{2}" y2="{0}"/>)", coord(sy(v)), coord(f.left), coord(f.right));
  }
  out += "</g>";
  out += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555"/>)", coord(f.left),
                     coord(f.top), coord(f.right - f.left), coord(f.bottom - f.top));
  out += R"(<g class="ticks" font-size="11" fill="#333">)";
  for (const double v : tx.values) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">{}</text>)", coord(sx(v)), coord(f.bottom + 14),
                       fixed(v, tx.decimals));
  }
  for (const double v : ty.values) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", coord(f.left - 5), coord(sy(v) + 4),
                       fixed(v, ty.decimals));
  }
  out += "</g>";
  out += fmt::format(R"(<text class="axis-label" x="{}" y="{}" text-anchor="middle">{}</text>)",
                     coord(0.5 * (f.left + f.right)), coord(f.bottom + 34), escape(x_label));
  const double cy = 0.5 * (f.top + f.bottom);
  out += fmt::format(R"~(<text class="axis-label" x="14" y="{0}" text-anchor="middle" transform="rotate(-90 14 {0})">{1}</text>)~",
                     coord(cy), escape(y_label));
}


// The data ranges of a time-series plot, its plot area, scales and ticks.
struct PlotAxes {
  std::size_t n_points = 0;  // finite points over all series
  Frame frame{};
  LinearScale sx, sy;
  Ticks tx, ty;
};

PlotAxes plot_axes(const PlotSpec& spec) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  PlotAxes a;
  for (const auto& s : spec.series) {
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
      ++a.n_points;
    }
  }
  if (a.n_points == 0) {
    x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;
  }
  widen(x_lo, x_hi, 1e-3, 0.0);
  if (spec.y_from_zero) {
    y_lo = 0.0;
    y_hi = a.n_points == 0 ? 1.0 : std::max(y_hi * 1.08, 1e-3);
  } else {
    widen(y_lo, y_hi, 1.0, 0.06);
  }
  a.frame = Frame{kMarginLeft, kMarginTop, spec.width_px - kMarginRight, spec.height_px - kMarginBottom};
  a.tx = nice_ticks(x_lo, x_hi, 8), a.ty = nice_ticks(y_lo, y_hi, 5);
  a.sx = LinearScale{x_lo, x_hi, a.frame.left, a.frame.right}, a.sy = LinearScale{y_lo, y_hi, a.frame.bottom, a.frame.top};
  return a;
}

// Legend, right-aligned in the title line: the last series rightmost.
void draw_plot_legend(const PlotSpec& spec, std::string& out) {
  double legend_x = spec.width_px - kMarginRight;
  for (auto it = spec.series.rbegin(); it != spec.series.rend(); ++it) {
    const double text_w = 6.5 * static_cast<double>(it->label.size());
    legend_x -= text_w;
    out += fmt::format(R"(<text x="{}" y="16" class="legend">{}</text>)", coord(legend_x), escape(it->label));
    legend_x -= 18.0;
    if (it->dots) {
      out += fmt::format(R"(<circle cx="{}" cy="12" r="3" fill="{}"/>)", coord(legend_x + 8), it->colour);
    } else {
      out += fmt::format(R"(<line x1="{}" y1="12" x2="{}" y2="12" stroke="{}" stroke-width="2"{}/>)", coord(legend_x + 1),
                         coord(legend_x + 15), it->colour, it->dashed ? R"( stroke-dasharray="4 2")" : "");
    }
    legend_x -= 14.0;
  }
}

// One path per series: dots as zero-length round-capped segments; a line lifts its pen at a
// non-finite point, so that a gap in the data stays a gap.
void draw_series(const PlotSeries& s, const LinearScale& sx, const LinearScale& sy, std::string& out) {
  std::string d;
  bool pen_down = false;
  for (const auto& [x, y] : s.points) {
    if (!std::isfinite(x) || !std::isfinite(y)) {
      pen_down = false;
      continue;
    }
    if (s.dots) {
      d += fmt::format("M{} {}h0", coord(sx(x)), coord(sy(y)));
    } else {
      d += fmt::format("{}{} {}", pen_down ? "L" : "M", coord(sx(x)), coord(sy(y)));
      pen_down = true;
    }
  }
  if (d.empty()) return;
  if (s.dots) {
    out += fmt::format(R"(<path class="series dots" d="{}" stroke="{}" stroke-width="4" stroke-linecap="round" fill="none"/>)",
                       d, s.colour);
  } else {
    out += fmt::format(R"(<path class="series line" d="{}" stroke="{}" stroke-width="{}" stroke-linejoin="round" fill="none"{}/>)",
                       d, s.colour, s.dashed ? "1.6" : "2.2", s.dashed ? R"( stroke-dasharray="6 3")" : "");
  }
}

}  // namespace

std::string plot_svg(const PlotSpec& spec) {
  const PlotAxes a = plot_axes(spec);
  std::string out;
  open_svg(out, spec.width_px, spec.height_px, "plot", spec.title);
  if (!spec.note.empty()) {
    out += fmt::format(R"(<text x="8" y="30" class="note">{}</text>)", escape(spec.note));
  }
  draw_axes(out, a.frame, a.sx, a.sy, a.tx, a.ty, spec.x_label, spec.y_label);
  draw_plot_legend(spec, out);
  if (a.n_points == 0) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle" class="note">no data</text>)",
                       coord(0.5 * (a.frame.left + a.frame.right)), coord(0.5 * (a.frame.top + a.frame.bottom)));
  }
  for (const auto& s : spec.series) draw_series(s, a.sx, a.sy, out);
  out += "</svg>";
  return out;
}

std::string histogram_svg(const HistogramSpec& spec) {
  const double bins = static_cast<double>(std::max<std::size_t>(1, spec.counts.size()));
  double x_lo = spec.lo, x_hi = spec.lo + bins * spec.bin_width;
  widen(x_lo, x_hi, 1e-12, 0.0);
  long long max_count = 0, total = 0;
  for (const long long c : spec.counts) {
    max_count = std::max(max_count, c);
    total += c;
  }
  double y_hi = std::max<double>(1.0, static_cast<double>(max_count) * 1.08);
  const Frame f{kMarginLeft, kMarginTop, spec.width_px - kMarginRight, spec.height_px - kMarginBottom};
  const Ticks tx = nice_ticks(x_lo, x_hi, 6), ty = nice_ticks(0.0, y_hi, 4);
  const LinearScale sx{x_lo, x_hi, f.left, f.right}, sy{0.0, y_hi, f.bottom, f.top};

  std::string out;
  open_svg(out, spec.width_px, spec.height_px, "histogram", spec.title);
  std::string note = spec.note;
  if (spec.below + spec.above > 0) {
    note += fmt::format("{}{} below / {} above the range, counted in the end bins", note.empty() ? "" : "; ", spec.below,
                        spec.above);
  }
  if (!note.empty()) out += fmt::format(R"(<text x="8" y="30" class="note">{}</text>)", escape(note));
  draw_axes(out, f, sx, sy, tx, ty, spec.x_label, spec.y_label);
  if (total == 0) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle" class="note">no {}</text>)",
                       coord(0.5 * (f.left + f.right)), coord(0.5 * (f.top + f.bottom)), escape(spec.y_label));
  }
  out += R"(<g class="bars" fill="#6a51a3" stroke="#fff" stroke-width="0.5">)";
  for (std::size_t i = 0; i < spec.counts.size(); ++i) {
    if (spec.counts[i] == 0) continue;
    const double a = sx(spec.lo + static_cast<double>(i) * spec.bin_width);
    const double b = sx(spec.lo + static_cast<double>(i + 1) * spec.bin_width);
    const double top = sy(static_cast<double>(spec.counts[i]));
    out += fmt::format(R"(<rect class="bar" x="{}" y="{}" width="{}" height="{}"/>)", coord(a), coord(top),
                       coord(std::max(0.5, b - a)), coord(f.bottom - top));
  }
  out += "</g>";
  // Zero residual, the ideal.
  if (spec.zero_line && x_lo < 0.0 && x_hi > 0.0) {
    out += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#222" stroke-dasharray="3 3"/>)",
                       coord(sx(0.0)), coord(f.top), coord(f.bottom));
  }
  // Markers, their labels staggered in two rows so that neighbours stay legible.
  int row = 0;
  for (const HistogramMarker& m : spec.markers) {
    if (!std::isfinite(m.x) || m.x < x_lo || m.x > x_hi) continue;
    const double x = sx(m.x);
    out += fmt::format(R"(<line class="marker" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="{3}" stroke-width="1.5"{4}/>)",
                       coord(x), coord(f.top), coord(f.bottom), m.colour, m.dashed ? R"( stroke-dasharray="5 3")" : "");
    const bool right_half = x > 0.5 * (f.left + f.right);
    out += fmt::format(R"(<text class="note" x="{}" y="{}" text-anchor="{}" style="fill:{}">{}</text>)",
                       coord(right_half ? x - 3 : x + 3), coord(f.top + 11 + 11 * (row++ % 2)),
                       right_half ? "end" : "start", m.colour, escape(m.label));
  }
  out += "</svg>";
  return out;
}

}  // namespace rcsim::replay::svg
