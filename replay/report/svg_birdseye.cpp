#include "replay/report/svg_birdseye.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <unordered_set>

#include "replay/report/svg_plot.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::svg {

namespace {

std::array<Vec2, 4> box_corners_V(const BirdsEyeBox& box) {
  const double a = 0.5 * box.length_m, b = 0.5 * box.width_m;
  return {transform_point(box.X_VO, {a, b}), transform_point(box.X_VO, {-a, b}), transform_point(box.X_VO, {-a, -b}),
          transform_point(box.X_VO, {a, -b})};
}

struct Bounds {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  void add(const Vec2& p) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
    x_lo = std::min(x_lo, p.x());
    x_hi = std::max(x_hi, p.x());
    y_lo = std::min(y_lo, p.y());
    y_hi = std::max(y_hi, p.y());
  }
};

// Opacity of a target drawn `age` cycles before the pictured one.
double fade(int age, int trace_cycles) {
  if (age <= 0) return 1.0;
  return 0.12 + 0.45 * (1.0 - static_cast<double>(age) / (trace_cycles + 1));
}

// The picture's geometry: the view in metres (equal scale on both axes) and where it sits on screen.
struct View {
  double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;  // metres, vehicle frame
  double m_per_px = 0.0;
  double left = 0.0, top = 0.0, width = 0.0, height = 0.0, right = 0.0, bottom = 0.0;  // pixels: the plot area
  int width_px = 0, height_px = 0;
  // Screen: x (forward) up, y (left) to the left.
  LinearScale sx, sy;
  std::string px(const Vec2& p_V) const { return fmt::format("{},{}", coord(sx(p_V.y())), coord(sy(p_V.x()))); }
};

// How far from the ego a target of no annotated object still widens the view.
constexpr double kNearFieldM = 40.0;
// A view much longer than wide (a road ahead and behind) gets a plot up to this many times taller
// than wide, at the scale that fits its length: on a real drive, boxes 200 m apart on a 30 m wide
// road were drawn 2 px wide in a square.
constexpr double kMaxPlotAspect = 2.0;

// Everything worth seeing (targets, sensors, the vehicle origin, boxes near the sensors), padded;
// the plot as wide as spec.size_px and as tall as the view's length needs, up to kMaxPlotAspect.
View make_view(const BirdsEyeSpec& spec) {
  double reach_m = 0.0;
  for (const auto& s : spec.sensors) reach_m = std::max(reach_m, s.max_range_m);
  Bounds bounds;
  bounds.add(Vec2::Zero());
  for (const auto& s : spec.sensors) bounds.add(s.X_VS.translation());
  // The annotated objects and their targets set the view; the background and other targets only
  // within the near field: on a real drive they reach 170 m ahead and behind, and a view that held
  // them all drew the cars 2 px wide. Those farther out are clipped (the plot area's viewport).
  for (const auto& t : spec.targets) {
    const bool unannotated = t.target_class == "background" || t.target_class == "other";
    if (!unannotated || t.p_V.norm() <= kNearFieldM) bounds.add(t.p_V);
  }
  for (const auto& box : spec.boxes) {
    if (box.X_VO.translation().norm() > reach_m + 10.0) continue;
    for (const Vec2& c : box_corners_V(box)) bounds.add(c);
  }
  widen(bounds.x_lo, bounds.x_hi, 10.0, 0.0);
  widen(bounds.y_lo, bounds.y_hi, 10.0, 0.0);
  bounds.x_lo -= 2.0, bounds.x_hi += 2.0, bounds.y_lo -= 2.0, bounds.y_hi += 2.0;
  View v;
  const double length_m = bounds.x_hi - bounds.x_lo, width_m = bounds.y_hi - bounds.y_lo;
  const double aspect = std::clamp(length_m / width_m, 1.0, kMaxPlotAspect);
  v.width = spec.size_px, v.height = std::round(spec.size_px * aspect);
  v.m_per_px = std::max(length_m / v.height, width_m / v.width);
  const double half_length_m = 0.5 * v.m_per_px * v.height, half_width_m = 0.5 * v.m_per_px * v.width;
  const double cx = 0.5 * (bounds.x_lo + bounds.x_hi), cy = 0.5 * (bounds.y_lo + bounds.y_hi);
  v.x_lo = cx - half_length_m, v.x_hi = cx + half_length_m, v.y_lo = cy - half_width_m, v.y_hi = cy + half_width_m;
  v.left = 58.0, v.top = 30.0 + 14.0 * static_cast<double>(spec.notes.size());
  v.right = v.left + v.width, v.bottom = v.top + v.height;
  v.width_px = static_cast<int>(v.right + 16.0), v.height_px = static_cast<int>(v.bottom + (spec.class_legend ? 122.0 : 104.0));
  v.sx = LinearScale{v.y_hi, v.y_lo, v.left, v.right};
  v.sy = LinearScale{v.x_lo, v.x_hi, v.bottom, v.top};
  return v;
}

void draw_header(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  out += fmt::format(R"(<svg class="birdseye" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" role="img" aria-label="{2}">)",
                     v.width_px, v.height_px, escape(spec.title));
  if (spec.standalone) {
    // The text styles of the report's page (html_report.cpp), for a picture opened on its own.
    out += "<style>text{font-family:system-ui,sans-serif}.title{font-size:13px;font-weight:600}"
           ".note{font-size:11px;fill:#666}.axis-label,.legend{font-size:12px;fill:#333}"
           ".box-label{font-size:10px;fill:#343a40}</style>";
  }
  out += fmt::format(R"(<rect class="bg" x="0" y="0" width="{}" height="{}" fill="#fff"/>)", v.width_px, v.height_px);
  out += fmt::format(R"(<text x="8" y="16" class="title">{}</text>)", escape(spec.title));
  for (std::size_t i = 0; i < spec.notes.size(); ++i) {
    out += fmt::format(R"(<text x="8" y="{}" class="note">{}</text>)", 31 + 14 * i, escape(spec.notes[i]));
  }
}

// Axes with a metre grid.
void draw_axes(const View& v, std::string& out) {
  const auto& [sx, sy] = std::tie(v.sx, v.sy);
  const Ticks tx = nice_ticks(v.x_lo, v.x_hi, static_cast<int>(std::lround(8.0 * v.height / v.width))),
              ty = nice_ticks(v.y_lo, v.y_hi, 8);
  out += R"(<g class="grid" stroke="#e6e6e6" stroke-width="1">)";
  for (const double tick : ty.values) {
    out += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}"/>)", coord(sx(tick)), coord(v.top), coord(v.bottom));
  }
  for (const double tick : tx.values) {
    out += fmt::format(R"(<line x1="{1}" y1="{0}" x2="{2}" y2="{0}"/>)", coord(sy(tick)), coord(v.left), coord(v.right));
  }
  out += "</g>";
  out += R"(<g class="ticks" font-size="11" fill="#333">)";
  for (const double tick : ty.values) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">{}</text>)", coord(sx(tick)), coord(v.bottom + 14),
                       fixed(tick, ty.decimals));
  }
  for (const double tick : tx.values) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", coord(v.left - 5), coord(sy(tick) + 4),
                       fixed(tick, tx.decimals));
  }
  out += "</g>";
  out += fmt::format(R"(<text class="axis-label" x="{}" y="{}" text-anchor="middle">y / m (vehicle frame, left positive)</text>)",
                     coord(0.5 * (v.left + v.right)), coord(v.bottom + 32));
  out += fmt::format(R"~(<text class="axis-label" x="14" y="{0}" text-anchor="middle" transform="rotate(-90 14 {0})">x / m (vehicle frame, forward)</text>)~",
                     coord(0.5 * (v.top + v.bottom)));

}

void draw_fields_of_view(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  out += R"(<g class="fovs">)";
  for (const auto& s : spec.sensors) {
    std::string points = v.px(s.X_VS.translation());
    constexpr int kArcSegments = 32;
    for (int i = 0; i <= kArcSegments; ++i) {
      const double a = -s.azimuth_half_rad + 2.0 * s.azimuth_half_rad * i / kArcSegments;
      points += ' ';
      points += v.px(transform_point(s.X_VS, {s.max_range_m * std::cos(a), s.max_range_m * std::sin(a)}));
    }
    out += fmt::format(R"(<polygon class="fov" points="{}" fill="#2b8a3e" fill-opacity="0.06" stroke="#2b8a3e" stroke-opacity="0.5" stroke-dasharray="5 4"/>)",
                       points);
  }
  out += "</g>";
}

// A label's place on screen, its width guessed from its characters (10 px text).
struct LabelRect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool overlaps(const LabelRect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Beside the box (right of it on screen), moved up or down a line at a time, nearest first, until
// it overlaps no label placed before it; after 8 lines either way it stays where it is.
LabelRect place_label(double x_px, double y_px, std::size_t characters, const std::vector<LabelRect>& placed) {
  constexpr double kLineHeightPx = 11.0, kCharWidthPx = 5.6;
  const double width_px = kCharWidthPx * static_cast<double>(characters);
  const auto at = [&](double dy) { return LabelRect{x_px, y_px + dy - 8.0, x_px + width_px, y_px + dy + 2.0}; };
  for (int step = 0; step <= 16; ++step) {
    const double dy = (step % 2 == 1 ? -1.0 : 1.0) * kLineHeightPx * ((step + 1) / 2);
    const LabelRect candidate = at(dy);
    if (std::none_of(placed.begin(), placed.end(), [&](const LabelRect& r) { return r.overlaps(candidate); })) return candidate;
  }
  return at(0.0);
}

void draw_boxes(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  out += R"(<g class="boxes">)";
  std::vector<LabelRect> labels;
  for (const auto& box : spec.boxes) {
    std::string points;
    double right_px = -1e9, centre_y_px = 0.0;
    for (const Vec2& c : box_corners_V(box)) {
      if (!points.empty()) points += ' ';
      points += v.px(c);
      right_px = std::max(right_px, v.sx(c.y()));
    }
    centre_y_px = v.sy(box.X_VO.translation().x());
    out += fmt::format(R"(<polygon class="box" points="{}" fill="#868e96" fill-opacity="0.18" stroke="{}" stroke-width="{}"/>)",
                       points, box.in_merge_pair ? "#862e9c" : "#495057", box.in_merge_pair ? "2" : "1.2");
    labels.push_back(place_label(right_px + 3.0, centre_y_px + 3.0, box.label.size(), labels));
    out += fmt::format(R"(<text class="box-label" x="{}" y="{}">{}</text>)", coord(labels.back().x0),
                       coord(labels.back().y1 - 2.0), escape(box.label));
  }
  out += "</g>";
}

// The ego vehicle's reference point, its sensors and the assigned pairs' links.
void draw_ego_sensors_and_links(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  const auto& [sx, sy] = std::tie(v.sx, v.sy);
  out += fmt::format(R"(<g class="ego" stroke="#111" stroke-width="1.5"><line x1="{0}" y1="{1}" x2="{0}" y2="{2}"/><line x1="{3}" y1="{4}" x2="{5}" y2="{4}"/></g>)",
                     coord(sx(0.0)), coord(sy(-0.8)), coord(sy(0.8)), coord(sx(0.8)), coord(sy(0.0)), coord(sx(-0.8)));
  for (const auto& s : spec.sensors) {
    const double k = v.m_per_px;  // a marker of fixed pixel size
    const Vec2 tip = transform_point(s.X_VS, {9.0 * k, 0.0}), l = transform_point(s.X_VS, {-4.0 * k, 5.0 * k}),
               r = transform_point(s.X_VS, {-4.0 * k, -5.0 * k});
    out += fmt::format(R"(<polygon class="sensor" points="{} {} {}" fill="#2b8a3e" stroke="#111" stroke-width="0.8"><title>{}</title></polygon>)",
                       v.px(tip), v.px(l), v.px(r), escape(s.label));
  }
  out += R"(<g class="links" stroke="#444" stroke-width="0.8">)";
  for (const auto& link : spec.links) {
    out += fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}"/>)", coord(sx(link.p_recorded_V.y())),
                       coord(sy(link.p_recorded_V.x())), coord(sx(link.p_simulated_V.y())),
                       coord(sy(link.p_simulated_V.x())));
  }
  out += "</g>";
}


const char* target_colour(const BirdsEyeTarget& t) {
  if (t.target_class == "background") return kBackgroundColour;
  if (t.target_class == "other") return kOtherColour;
  return t.simulated ? kSimulatedColour : kRecordedColour;
}

// Marks that would land on one another are drawn once: per origin and class, one mark of the
// pictured cycle per kCurrentCellPx square (under half its mark's size) and one trace mark (the
// youngest) per trace square of kTraceCellPx (about its mark's size); the background's and other
// targets' trace squares doubled until the traces keep at most kMaxTraceMarks. A point cloud's 2,000 targets a cycle and their traces drew 15,000
// marks a picture (3 MB of markup), most of them covered by a neighbour; merge artefacts are
// always drawn. What the screen loses: a trace's accumulated opacity, and at point-cloud scale
// the traces' finest detail.
constexpr double kCurrentCellPx = 2.0, kTraceCellPx = 4.0;
constexpr std::size_t kMaxTraceMarks = 1500;

// Keeps the first target of each (square of cell_px, series) of `order`.
std::vector<const BirdsEyeTarget*> one_per_cell(const std::vector<const BirdsEyeTarget*>& order, const View& v, double cell_px) {
  std::unordered_set<std::uint64_t> taken;
  std::vector<const BirdsEyeTarget*> kept;
  for (const BirdsEyeTarget* t : order) {
    const double x = v.sx(t->p_V.y()), y = v.sy(t->p_V.x());
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    const auto column = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / cell_px)) & 0xFFFFF);
    const auto row = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(y / cell_px)) & 0xFFFFF);
    const std::uint64_t series = (t->simulated ? 1u : 0u) | (t->target_class == "background" ? 2u : t->target_class == "other" ? 4u : 0u);
    const bool is_new = taken.insert(column << 40 | row << 20 | series).second;
    if (is_new || (t->merge_artefact && t->age == 0)) kept.push_back(t);
  }
  return kept;
}

std::vector<const BirdsEyeTarget*> visible_targets(const BirdsEyeSpec& spec, const View& v) {
  std::vector<const BirdsEyeTarget*> current, object_traces, other_traces;
  for (const auto& t : spec.targets) {
    const bool of_object = t.target_class != "background" && t.target_class != "other";
    (t.age == 0 ? current : of_object ? object_traces : other_traces).push_back(&t);
  }
  // Youngest first: the trace mark kept in a square is the one drawn on top.
  for (auto* traces : {&object_traces, &other_traces}) {
    std::stable_sort(traces->begin(), traces->end(), [](const auto* a, const auto* b) { return a->age < b->age; });
  }
  std::vector<const BirdsEyeTarget*> kept = one_per_cell(current, v, kCurrentCellPx);
  // The objects' traces (their paths) at the mark's size; the background's and other targets'
  // coarsened to what is left of the budget.
  std::vector<const BirdsEyeTarget*> kept_traces = one_per_cell(object_traces, v, kTraceCellPx);
  kept.insert(kept.end(), kept_traces.begin(), kept_traces.end());
  const std::size_t left = kMaxTraceMarks > kept_traces.size() ? kMaxTraceMarks - kept_traces.size() : 0;
  for (double cell_px = kTraceCellPx;; cell_px *= 2.0) {
    kept_traces = one_per_cell(other_traces, v, cell_px);
    if (kept_traces.size() <= left || cell_px > 1000.0) break;
  }
  kept.insert(kept.end(), kept_traces.begin(), kept_traces.end());
  return kept;
}

// Oldest first, so that the pictured cycle is drawn on top; the marks of one cycle, origin and
// class share their paint in one group (a mark's own markup: its class and place).
void draw_targets(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  const auto& [sx, sy] = std::tie(v.sx, v.sy);
  std::vector<const BirdsEyeTarget*> order = visible_targets(spec, v);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return std::make_tuple(-a->age, a->simulated, std::string_view(target_colour(*a))) <
           std::make_tuple(-b->age, b->simulated, std::string_view(target_colour(*b)));
  });
  out += R"(<g class="targets">)";
  const BirdsEyeTarget* group = nullptr;
  for (const BirdsEyeTarget* t : order) {
    if (group == nullptr || group->age != t->age || group->simulated != t->simulated ||
        std::string_view(target_colour(*group)) != target_colour(*t)) {
      if (group != nullptr) out += "</g>";
      group = t;
      const double opacity = fade(t->age, spec.trace_cycles);
      if (t->simulated) {
        out += fmt::format(R"(<g fill="none" stroke="{}" stroke-width="1.8" opacity="{:.2f}">)", target_colour(*t), opacity);
      } else {
        out += fmt::format(R"(<g fill="{}" opacity="{:.2f}">)", target_colour(*t), opacity);
      }
    }
    const double x = sx(t->p_V.y()), y = sy(t->p_V.x());
    const double r = t->age == 0 ? 4.5 : 3.0;
    const char* kind = t->age == 0 ? "current" : "trace";
    if (t->simulated) {
      const double d = r + 1.5;
      out += fmt::format(R"(<polygon class="t sim {}" points="{},{} {},{} {},{} {},{}"/>)", kind, coord(x), coord(y - d),
                         coord(x + d), coord(y), coord(x), coord(y + d), coord(x - d), coord(y));
    } else {
      out += fmt::format(R"(<circle class="t rec {}" cx="{}" cy="{}" r="{}"/>)", kind, coord(x), coord(y), coord(r));
    }
  }
  if (group != nullptr) out += "</g>";
  for (const BirdsEyeTarget* t : order) {
    if (t->merge_artefact && t->age == 0) {
      out += fmt::format(R"(<circle class="merge" cx="{}" cy="{}" r="9" fill="none" stroke="#862e9c" stroke-width="1.5"/>)",
                         coord(sx(t->p_V.y())), coord(sy(t->p_V.x())));
    }
  }
  out += "</g>";
}

// Legend under the axis label, three rows.
void draw_legend(const BirdsEyeSpec& spec, const View& v, std::string& out) {
  const double ly = v.bottom + 54.0, ly2 = v.bottom + 72.0, ly3 = v.bottom + 90.0;
  const double l0 = v.left + 8.0, l1 = v.left + 160.0, l2 = v.left + 310.0;
  out += R"(<g class="legend-block">)";
  out += fmt::format(R"(<circle cx="{}" cy="{}" r="4.5" fill="{}"/><text x="{}" y="{}" class="legend">{}</text>)",
                     coord(l0), coord(ly - 4), kRecordedColour, coord(l0 + 10), coord(ly), escape(spec.recorded_label));
  out += fmt::format(R"(<polygon points="{0},{1} {2},{3} {0},{4} {5},{3}" fill="none" stroke="{6}" stroke-width="1.8"/><text x="{7}" y="{8}" class="legend">{9}</text>)",
                     coord(l1), coord(ly - 10), coord(l1 + 6), coord(ly - 4), coord(ly + 2), coord(l1 - 6),
                     kSimulatedColour, coord(l1 + 10), coord(ly), escape(spec.simulated_label));
  out += fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#444"/><text x="{}" y="{}" class="legend">assigned pair (GOSPA)</text>)",
                     coord(l2 - 8), coord(ly - 4), coord(l2 + 6), coord(ly - 4), coord(l2 + 10), coord(ly));
  out += fmt::format(R"(<circle cx="{}" cy="{}" r="7" fill="none" stroke="#862e9c" stroke-width="1.5"/><text x="{}" y="{}" class="legend">merge artefact</text>)",
                     coord(l0), coord(ly2 - 4), coord(l0 + 10), coord(ly2));
  out += fmt::format(R"(<polygon points="{},{} {},{} {},{}" fill="#2b8a3e" stroke="#111" stroke-width="0.8"/><text x="{}" y="{}" class="legend">sensor, with its field of view (dashed)</text>)",
                     coord(l1 + 6), coord(ly2 - 4), coord(l1 - 5), coord(ly2 - 9), coord(l1 - 5), coord(ly2 + 1),
                     coord(l1 + 10), coord(ly2));
  out += fmt::format(R"(<rect x="{}" y="{}" width="12" height="8" fill="#868e96" fill-opacity="0.18" stroke="#495057"/><text x="{}" y="{}" class="legend">annotated box; purple outline: shares a range-speed cell with another</text>)",
                     coord(l0 - 6), coord(ly3 - 8), coord(l0 + 10), coord(ly3));
  if (spec.class_legend) {
    const double ly4 = v.bottom + 108.0;
    out += fmt::format(R"(<text x="{}" y="{}" class="legend">targets on no box:</text>)", coord(l0 - 6), coord(ly4));
    out += fmt::format(R"(<circle cx="{}" cy="{}" r="4.5" fill="{}"/><text x="{}" y="{}" class="legend">stationary background</text>)",
                       coord(l0 + 118), coord(ly4 - 4), kBackgroundColour, coord(l0 + 128), coord(ly4));
    out += fmt::format(R"(<circle cx="{}" cy="{}" r="4.5" fill="{}"/><text x="{}" y="{}" class="legend">other (moving, unannotated)</text>)",
                       coord(l2), coord(ly4 - 4), kOtherColour, coord(l2 + 10), coord(ly4));
  }
  out += "</g>";
}

}  // namespace

std::string birdseye_svg(const BirdsEyeSpec& spec) {
  const View v = make_view(spec);
  std::string out;
  draw_header(spec, v, out);
  draw_axes(v, out);
  // The drawing, clipped to the plot area by a nested viewport.
  out += fmt::format(R"(<svg x="{0}" y="{1}" width="{2}" height="{3}" viewBox="{0} {1} {2} {3}" overflow="hidden">)",
                     coord(v.left), coord(v.top), coord(v.width), coord(v.height));
  draw_fields_of_view(spec, v, out);
  draw_boxes(spec, v, out);
  draw_ego_sensors_and_links(spec, v, out);
  draw_targets(spec, v, out);
  out += "</svg>";
  out += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555"/>)", coord(v.left),
                     coord(v.top), coord(v.width), coord(v.height));
  draw_legend(spec, v, out);
  out += "</svg>";
  return out;
}

}  // namespace rcsim::replay::svg
