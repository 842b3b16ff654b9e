#include "replay/report/svg_pareto.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <tuple>
#include <numeric>

#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::svg {

namespace {

// The margins and colours of svg_plot.cpp, so that the plot sits among the others.
constexpr const char* kFrontColour = "#2b8a3e";      // green: the Pareto front
constexpr const char* kDominatedColour = "#868e96";  // grey: dominated levels
constexpr const char* kDefaultColour = "#d9480f";    // orange: the default level
constexpr const char* kFloorColour = "#495057";
constexpr double kMarkerRadiusPx = 5.0, kDefaultRingPx = 9.0;
// Estimated advance of an 11 px (legend: 12 px) glyph of the fallback sans fonts (DejaVu Sans is the
// widest); labels are placed with it, so it errs wide.
constexpr double kCharWidthPx = 6.6, kBoldCharWidthPx = 7.2, kLegendCharWidthPx = 7.0;

bool drawable(const ParetoPoint& p) {
  return std::isfinite(p.cycles_per_cpu_s) && p.cycles_per_cpu_s > 0.0 && std::isfinite(p.error_m);
}

// b dominates a: at least as fast and at least as accurate, strictly better in one.
bool dominates(const ParetoPoint& b, const ParetoPoint& a) {
  return b.cycles_per_cpu_s >= a.cycles_per_cpu_s && b.error_m <= a.error_m &&
         (b.cycles_per_cpu_s > a.cycles_per_cpu_s || b.error_m < a.error_m);
}

struct Box {
  double x0, y0, x1, y1;
};

double overlap_area(const Box& a, const Box& b) {
  return std::max(0.0, std::min(a.x1, b.x1) - std::max(a.x0, b.x0)) *
         std::max(0.0, std::min(a.y1, b.y1) - std::max(a.y0, b.y0));
}

// Area of `box` outside `bounds`.
double outside_area(const Box& box, const Box& bounds) {
  return (box.x1 - box.x0) * (box.y1 - box.y0) - overlap_area(box, bounds);
}

struct Segment {
  double x0, y0, x1, y1;
};

// Whether two segments cross (touching ends do not count).
bool crosses(const Segment& a, const Segment& b) {
  const auto side = [](double ax, double ay, double bx, double by, double cx, double cy) {
    const double z = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    return z > 1e-9 ? 1 : z < -1e-9 ? -1 : 0;
  };
  return side(a.x0, a.y0, a.x1, a.y1, b.x0, b.y0) * side(a.x0, a.y0, a.x1, a.y1, b.x1, b.y1) < 0 &&
         side(b.x0, b.y0, b.x1, b.y1, a.x0, a.y0) * side(b.x0, b.y0, b.x1, b.y1, a.x1, a.y1) < 0;
}

// Small boxes along a segment, so that labels keep off lines.
void add_samples(std::vector<Box>& boxes, const Segment& s) {
  const double length = std::hypot(s.x1 - s.x0, s.y1 - s.y0);
  const int steps = std::max(1, static_cast<int>(length / 4.0));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps, x = s.x0 + t * (s.x1 - s.x0), y = s.y0 + t * (s.y1 - s.y0);
    boxes.push_back({x - 1.5, y - 1.5, x + 1.5, y + 1.5});
  }
}

// The point of `box` nearest to (x, y).
std::pair<double, double> nearest_on(const Box& box, double x, double y) {
  return {std::clamp(x, box.x0, box.x1), std::clamp(y, box.y0, box.y1)};
}

// What the point labels must keep off, built up as they are placed.
struct LabelLayout {
  Box bounds{};                         // the plot frame
  std::vector<Box> occupied;            // markers, labels, samples along lines and leaders
  std::vector<Box> markers;             // per drawable point
  std::vector<Segment> lines, leaders;  // the front and the noise floor; leaders placed so far

  void add_line(const Segment& s) {
    lines.push_back(s);
    add_samples(occupied, s);
  }
};

struct Label {
  double x = 0.0, y = 0.0;  // text anchor point (baseline)
  const char* anchor = "start";
  Box box{};
  std::optional<Segment> leader;  // from the marker's edge to the label, when placed away from it
};

// Where to put a label of `width_px` for the marker `own` of radius `marker_px` at (px, py): left,
// right, above or below it, next to it or further out, wherever it costs least: overlap with
// what is placed, leaving the frame, distance, and for a label away from its point a leader that
// would cross markers, lines or other leaders. The model levels lie within a factor of a few in
// speed on an axis of four decades, so their labels often need to move out, joined by a leader.
Label place_label(const LabelLayout& layout, std::size_t own, double px, double py, double width_px, double marker_px) {
  constexpr double kHeightPx = 12.0;
  Label best;
  double best_cost = std::numeric_limits<double>::infinity();
  const auto consider = [&](double x0, double y0, const char* anchor) {
    Label l;
    l.box = {x0, y0, x0 + width_px, y0 + kHeightPx};
    l.anchor = anchor;
    l.x = anchor[0] == 's' ? x0 : anchor[0] == 'e' ? x0 + width_px : x0 + 0.5 * width_px;
    l.y = y0 + kHeightPx - 3.0;
    const auto [nx, ny] = nearest_on(l.box, px, py);
    const double gap = std::hypot(nx - px, ny - py);
    double cost = 10.0 * outside_area(l.box, layout.bounds) + 0.05 * gap;
    for (const Box& o : layout.occupied) cost += overlap_area(l.box, o);
    if (gap > marker_px + 8.0) {
      const double ux = (nx - px) / gap, uy = (ny - py) / gap;
      const Segment leader{px + ux * (marker_px + 1.0), py + uy * (marker_px + 1.0), nx - ux * 2.0, ny - uy * 2.0};
      std::vector<Box> samples;
      add_samples(samples, leader);
      for (std::size_t m = 0; m < layout.markers.size(); ++m) {
        if (m == own) continue;
        for (const Box& b : samples) cost += 10.0 * overlap_area(b, layout.markers[m]);
      }
      for (const Segment& s : layout.leaders) cost += crosses(leader, s) ? 400.0 : 0.0;
      for (const Segment& s : layout.lines) cost += crosses(leader, s) ? 40.0 : 0.0;
      l.leader = leader;
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = l;
    }
  };
  for (const double gap : {3.0, 14.0, 28.0, 46.0, 68.0}) {
    for (const double rise : {0.0, -14.0, 14.0, -28.0, 28.0, -42.0, 42.0, -56.0, 56.0}) {
      const double y0 = py + rise - 0.5 * kHeightPx;
      consider(px + marker_px + gap, y0, "start");
      consider(px - marker_px - gap - width_px, y0, "end");
    }
  }
  for (const double rise : {3.0, 14.0, 28.0, 42.0}) {
    consider(px - 0.5 * width_px, py - marker_px - rise - kHeightPx, "middle");
    consider(px - 0.5 * width_px, py + marker_px + rise, "middle");
  }
  return best;
}

constexpr std::array<const char*, 10> kSuperscriptDigits{"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                                         "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};

}  // namespace

std::string speed_text(double cycles_per_cpu_s) {
  return cycles_per_cpu_s >= 100.0 ? fmt::format("{:.0f}", cycles_per_cpu_s) : fmt::format("{:.3g}", cycles_per_cpu_s);
}

std::string power_of_ten_label(int exponent) {
  std::string out = "10";
  if (exponent < 0) out += "\u207b";  // superscript minus
  for (const char digit : std::to_string(std::abs(exponent)))
    out += kSuperscriptDigits[static_cast<std::size_t>(digit - '0')];
  return out;
}

std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<bool> front(points.size(), false);
  for (std::size_t a = 0; a < points.size(); ++a) {
    if (!drawable(points[a])) continue;
    front[a] = std::none_of(points.begin(), points.end(),
                            [&](const ParetoPoint& b) { return drawable(b) && dominates(b, points[a]); });
  }
  return front;
}

namespace {

// The plot's axes: x = log10(sensor cycles per CPU second), y = error from zero.
struct ParetoView {
  double x_lo = 0.0, x_hi = 0.0, y_hi = 0.0;
  std::size_t drawn = 0;  // points with a CPU time
  Box frame;
  LinearScale sx, sy;
  double px(const ParetoPoint& p) const { return sx(std::log10(p.cycles_per_cpu_s)); }
  double py(const ParetoPoint& p) const { return sy(p.error_m); }
};

ParetoView make_pareto_view(const ParetoSpec& spec) {
  // x in log10 units.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_hi = 0.0;
  std::size_t drawn = 0;
  for (const ParetoPoint& p : spec.points) {
    if (!drawable(p)) continue;
    x_lo = std::min(x_lo, std::log10(p.cycles_per_cpu_s));
    x_hi = std::max(x_hi, std::log10(p.cycles_per_cpu_s));
    y_hi = std::max(y_hi, p.error_m);
    ++drawn;
  }
  if (spec.extent) {
    for (const double v : {spec.extent->cycles_per_cpu_s_lo, spec.extent->cycles_per_cpu_s_hi}) {
      if (!std::isfinite(v) || v <= 0.0) continue;
      x_lo = std::min(x_lo, std::log10(v));
      x_hi = std::max(x_hi, std::log10(v));
    }
    if (std::isfinite(spec.extent->error_hi_m)) y_hi = std::max(y_hi, spec.extent->error_hi_m);
  }
  if (!(x_lo <= x_hi)) {
    x_lo = 2.0;
    x_hi = 6.0;
  }
  if (spec.noise_floor_m && std::isfinite(*spec.noise_floor_m)) y_hi = std::max(y_hi, *spec.noise_floor_m);
  // At least one decade wide, with room for the labels of the slowest and fastest points.
  widen(x_lo, x_hi, 1.0, 0.0);
  const double x_pad = std::max(0.25, 0.06 * (x_hi - x_lo));
  x_lo -= x_pad;
  x_hi += x_pad;
  // An axis end close to a power of ten is moved onto it, so that it carries a tick label.
  if (x_lo - std::floor(x_lo) < 0.3) x_lo = std::floor(x_lo);
  if (std::ceil(x_hi) - x_hi < 0.3) x_hi = std::ceil(x_hi);
  y_hi = y_hi > 0.0 ? y_hi * 1.12 : 1.0;

  ParetoView v;
  v.x_lo = x_lo, v.x_hi = x_hi, v.y_hi = y_hi, v.drawn = drawn;
  v.frame = Box{kMarginLeft, kMarginTop, spec.width_px - kMarginRight, spec.height_px - kMarginBottom};
  v.sx = LinearScale{x_lo, x_hi, v.frame.x0, v.frame.x1};
  v.sy = LinearScale{0.0, y_hi, v.frame.y1, v.frame.y0};
  return v;
}

void draw_pareto_header(const ParetoSpec& spec, std::string& out) {
  out += fmt::format(
      R"(<svg class="pareto" xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" role="img" aria-label="{}">)",
      spec.width_px, spec.height_px, spec.width_px, spec.height_px, escape(spec.title));
  out += fmt::format(R"(<rect class="bg" x="0" y="0" width="{}" height="{}" fill="#fff"/>)", spec.width_px,
                     spec.height_px);
  out += fmt::format(R"(<text x="8" y="16" class="title">{}</text>)", escape(spec.title));
  if (!spec.note.empty()) out += fmt::format(R"(<text x="8" y="30" class="note">{}</text>)", escape(spec.note));
}

void draw_pareto_axes(const ParetoSpec& spec, const ParetoView& view, std::string& out) {
  const double x_lo = view.x_lo, x_hi = view.x_hi;
  const Box& frame = view.frame;
  const auto& [sx, sy] = std::tie(view.sx, view.sy);
  const Ticks ty = nice_ticks(0.0, view.y_hi, 5);
  // Grid: every power of ten, lighter lines at its multiples 2..9; labels at the powers of ten,
  // and at 2 and 5 times them when fewer than three powers of ten lie on the axis.
  const int first_decade = static_cast<int>(std::floor(x_lo)), last_decade = static_cast<int>(std::ceil(x_hi));
  int majors = 0;
  for (int k = first_decade; k <= last_decade; ++k) majors += (k >= x_lo && k <= x_hi);
  const int label_every = std::max(1, (majors + 7) / 8);
  std::string grid = R"(<g class="grid" stroke-width="1">)",
              tick_labels = R"(<g class="ticks" font-size="11" fill="#333">)";
  for (int k = first_decade; k <= last_decade; ++k) {
    for (int m = 1; m <= 9; ++m) {
      const double v = static_cast<double>(k) + std::log10(static_cast<double>(m));
      if (v < x_lo || v > x_hi) continue;
      const double x = sx(v);
      grid += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="{3}"/>)", coord(x), coord(frame.y0),
                          coord(frame.y1), m == 1 ? "#e3e3e3" : "#f3f3f3");
      std::string text;
      if (m == 1 && (k % label_every) == 0) text = power_of_ten_label(k);
      if ((m == 2 || m == 5) && majors < 3) text = fmt::format("{}\u00b7{}", m, power_of_ten_label(k));
      if (!text.empty()) {
        tick_labels +=
            fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">{}</text>)", coord(x), coord(frame.y1 + 14), text);
      }
    }
  }
  for (const double v : ty.values) {
    grid += fmt::format(R"(<line x1="{1}" y1="{0}" x2="{2}" y2="{0}" stroke="#e3e3e3"/>)", coord(sy(v)),
                        coord(frame.x0), coord(frame.x1));
    tick_labels += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", coord(frame.x0 - 5),
                               coord(sy(v) + 4), fixed(v, ty.decimals));
  }
  out += grid + "</g>";
  out += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555"/>)", coord(frame.x0),
                     coord(frame.y0), coord(frame.x1 - frame.x0), coord(frame.y1 - frame.y0));
  out += tick_labels + "</g>";
  out += fmt::format(R"(<text class="axis-label" x="{}" y="{}" text-anchor="middle">{}</text>)",
                     coord(0.5 * (frame.x0 + frame.x1)), coord(frame.y1 + 34), escape(spec.x_label));
  const double cy = 0.5 * (frame.y0 + frame.y1);
  out += fmt::format(
      R"~(<text class="axis-label" x="14" y="{0}" text-anchor="middle" transform="rotate(-90 14 {0})">{1}</text>)~",
      coord(cy), escape(spec.y_label));

}

// Legend, right-aligned in the title line.
void draw_pareto_legend(const Box& frame, std::string& out) {
    double x = frame.x1;
    const auto legend_text = [&](const char* text) {
      x -= kLegendCharWidthPx * static_cast<double>(std::string_view(text).size());
      out += fmt::format(R"(<text x="{}" y="16" class="legend">{}</text>)", coord(x), text);
    };
    legend_text("noise floor");
    out +=
        fmt::format(R"(<line x1="{}" y1="12" x2="{}" y2="12" stroke="{}" stroke-width="1.5" stroke-dasharray="6 3"/>)",
                    coord(x - 24), coord(x - 4), kFloorColour);
    x -= 36;
    legend_text("dominated");
    out += fmt::format(R"(<circle cx="{}" cy="12" r="4" fill="#fff" stroke="{}" stroke-width="1.5"/>)", coord(x - 9),
                       kDominatedColour);
    x -= 26;
    legend_text("Pareto front");
    out += fmt::format(R"(<circle cx="{}" cy="12" r="4" fill="{}"/>)", coord(x - 9), kFrontColour);
    x -= 26;
    legend_text("default level");
    out += fmt::format(R"(<circle cx="{}" cy="12" r="6" fill="none" stroke="{}" stroke-width="2"/>)", coord(x - 10),
                       kDefaultColour);
}

// The noise floor's dashed line and its label, placed where it overlaps the least.
void draw_noise_floor(double floor_m, const ParetoView& view, LabelLayout& layout, std::string& out) {
  const Box& frame = view.frame;
    const double y = view.sy(floor_m);
    out += fmt::format(
        R"(<line class="noise-floor" x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="1.5" stroke-dasharray="6 3"/>)",
        coord(frame.x0), coord(y), coord(frame.x1), coord(y), kFloorColour);
    // Under the line at the fast end first: the levels lie above the floor, the slow reference
    // often close to it.
    const std::string text = fmt::format("noise floor {} m", fixed(floor_m, 3));
    const double w = kCharWidthPx * static_cast<double>(text.size());
    const double right = frame.x1 - 6.0, left = frame.x0 + 6.0;
    const std::array<Box, 4> candidates{{{right - w, y + 3, right, y + 15},
                                         {left, y + 3, left + w, y + 15},
                                         {right - w, y - 15, right, y - 3},
                                         {left, y - 15, left + w, y - 3}}};
    const Box* at = &candidates.front();
    double at_cost = std::numeric_limits<double>::infinity();
    for (const Box& c : candidates) {
      double cost = 10.0 * outside_area(c, frame);
      for (const Box& o : layout.occupied) cost += overlap_area(c, o);
      if (cost < at_cost) {
        at_cost = cost;
        at = &c;
      }
    }
    out += fmt::format(R"(<text class="noise-floor-label note" x="{}" y="{}">{}</text>)", coord(at->x0),
                       coord(at->y1 - 3), text);
    layout.occupied.push_back(*at);
    layout.add_line({frame.x0, y, frame.x1, y});
}

// The front, from the slowest to the fastest level; its segments keep labels off.
void draw_front(const ParetoSpec& spec, const std::vector<bool>& front, const ParetoView& view, LabelLayout& layout,
                std::string& out) {
  std::vector<std::size_t> on_front;
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    if (front[i]) on_front.push_back(i);
  }
  std::sort(on_front.begin(), on_front.end(), [&](std::size_t a, std::size_t b) {
    return spec.points[a].cycles_per_cpu_s < spec.points[b].cycles_per_cpu_s;
  });
  if (on_front.size() > 1) {
    std::string d;
    for (std::size_t k = 0; k < on_front.size(); ++k) {
      const ParetoPoint& p = spec.points[on_front[k]];
      d += fmt::format("{}{} {}", k == 0 ? "M" : "L", coord(view.px(p)), coord(view.py(p)));
      if (k > 0) {
        const ParetoPoint& q = spec.points[on_front[k - 1]];
        layout.add_line({view.px(q), view.py(q), view.px(p), view.py(p)});
      }
    }
    out += fmt::format(
        R"(<path class="front" d="{}" stroke="{}" stroke-width="1.8" stroke-linejoin="round" fill="none"/>)", d,
        kFrontColour);
  }

}

// Labels: the default level placed first, then the front, then the rest; leaders where a label
// had to move away from its point. Returns the labels (drawn last, above the markers).
std::string draw_point_labels(const ParetoSpec& spec, const std::vector<bool>& front, const ParetoView& view,
                              LabelLayout& layout, std::string& out) {
  std::vector<std::size_t> order(spec.points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto rank = [&](std::size_t i) { return spec.points[i].highlighted ? 0 : front[i] ? 1 : 2; };
    return rank(a) < rank(b);
  });
  std::string leaders = R"(<g class="leaders" stroke="#495057" stroke-width="1">)", labels;
  for (const std::size_t i : order) {
    const ParetoPoint& p = spec.points[i];
    if (!drawable(p)) continue;
    const double marker_px = p.highlighted ? kDefaultRingPx : kMarkerRadiusPx;
    const double width = (p.highlighted ? kBoldCharWidthPx : kCharWidthPx) * static_cast<double>(p.label.size());
    const Label l = place_label(layout, i, view.px(p), view.py(p), width, marker_px);
    layout.occupied.push_back(l.box);
    if (l.leader) {
      const Segment& s = *l.leader;
      leaders +=
          fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}"/>)", coord(s.x0), coord(s.y0), coord(s.x1), coord(s.y1));
      layout.leaders.push_back(s);
      add_samples(layout.occupied, s);
    }
    labels += fmt::format(
        R"(<text class="point-label{}" x="{}" y="{}" text-anchor="{}" font-size="11" fill="{}"{}>{}</text>)",
        p.highlighted ? " default" : "", coord(l.x), coord(l.y), l.anchor, p.highlighted ? kDefaultColour : "#212529",
        p.highlighted ? R"( font-weight="700")" : "", escape(p.label));
  }
  out += leaders + "</g>";

  return labels;
}

void draw_markers(const ParetoSpec& spec, const std::vector<bool>& front, const ParetoView& view, std::string& out) {
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    const ParetoPoint& p = spec.points[i];
    if (!drawable(p)) continue;
    const std::string x = coord(view.px(p)), y = coord(view.py(p));
    out += fmt::format(
        R"(<g class="point {}{}" data-level="{}"><title>{}: {} sensor cycles per CPU s, error {} m{}</title>)",
        front[i] ? "front" : "dominated", p.highlighted ? " default" : "", escape(p.label), escape(p.label),
        speed_text(p.cycles_per_cpu_s), fixed(p.error_m, 3), front[i] ? " (Pareto front)" : "");
    if (p.highlighted) {
      out += fmt::format(R"(<circle cx="{}" cy="{}" r="{}" fill="none" stroke="{}" stroke-width="2.5"/>)", x, y,
                         kDefaultRingPx, kDefaultColour);
    }
    out += front[i] ? fmt::format(R"(<circle cx="{}" cy="{}" r="{}" fill="{}" stroke="#fff" stroke-width="1"/>)", x, y,
                                  kMarkerRadiusPx, kFrontColour)
                    : fmt::format(R"(<circle cx="{}" cy="{}" r="{}" fill="#fff" stroke="{}" stroke-width="1.8"/>)", x,
                                  y, kMarkerRadiusPx - 0.5, kDominatedColour);
    out += "</g>";
  }
}

}  // namespace

std::string pareto_svg(const ParetoSpec& spec) {
  const std::vector<bool> front = pareto_front(spec.points);
  const ParetoView view = make_pareto_view(spec);
  const Box& frame = view.frame;
  std::string out;
  draw_pareto_header(spec, out);
  draw_pareto_axes(spec, view, out);
  if (spec.legend) draw_pareto_legend(frame, out);
  if (view.drawn == 0) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle" class="note">no level with a CPU time</text>)",
                       coord(0.5 * (frame.x0 + frame.x1)), coord(0.5 * (frame.y0 + frame.y1)));
  }
  // Everything a label must keep off: markers, the noise-floor line and its label, the front,
  // and the labels and leaders placed before it.
  LabelLayout layout;
  layout.bounds = frame;
  for (const ParetoPoint& p : spec.points) {
    const double r = (p.highlighted ? kDefaultRingPx : kMarkerRadiusPx) + 1.5;
    layout.markers.push_back(drawable(p) ? Box{view.px(p) - r, view.py(p) - r, view.px(p) + r, view.py(p) + r} : Box{0, 0, 0, 0});
  }
  layout.occupied = layout.markers;
  if (spec.noise_floor_m && std::isfinite(*spec.noise_floor_m)) draw_noise_floor(*spec.noise_floor_m, view, layout, out);
  draw_front(spec, front, view, layout, out);
  const std::string labels = draw_point_labels(spec, front, view, layout, out);
  draw_markers(spec, front, view, out);
  out += labels;
  out += "</svg>";
  return out;
}

}  // namespace rcsim::replay::svg
