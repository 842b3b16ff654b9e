#include "replay/report/svg_object_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>
#include <fmt/format.h>

#include "replay/report/svg_plot.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::svg {

std::string object_frame_svg(const ObjectFrameSpec& spec) {
  constexpr double kMargin_m = 1.5;  // beyond the box: the association gate and a little more
  const double half_m = std::max(0.5 * std::max(spec.length_m, spec.width_m) + kMargin_m, 2.0);
  const double left = 44.0, top = 34.0 + 14.0 * static_cast<double>(spec.notes.size()), size = spec.size_px;
  const LinearScale sx{half_m, -half_m, left, left + size};  // y (left) to the left
  const LinearScale sy{-half_m, half_m, top + size, top};    // x (forward) up
  const int width_px = static_cast<int>(left + size + 12.0), height_px = static_cast<int>(top + size + 58.0);
  std::string out = fmt::format(
      R"(<svg class="object-frame" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" role="img" aria-label="{2}">)",
      width_px, height_px, escape(spec.title));
  out += fmt::format(R"(<rect x="0" y="0" width="{}" height="{}" fill="#fff"/>)", width_px, height_px);
  out += fmt::format(R"(<text x="{}" y="18" class="title">{}</text>)", coord(left), escape(spec.title));
  for (std::size_t i = 0; i < spec.notes.size(); ++i) {
    out += fmt::format(R"(<text x="{}" y="{}" class="note">{}</text>)", coord(left), coord(32.0 + 14.0 * static_cast<double>(i)),
                       escape(spec.notes[i]));
  }
  // Grid and ticks, in metres from the box centre.
  const Ticks ticks = nice_ticks(-half_m, half_m, 5);
  out += R"(<g class="grid" stroke="#e9ecef">)";
  for (const double v : ticks.values) {
    out += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}"/><line x1="{3}" y1="{4}" x2="{5}" y2="{4}"/>)",
                       coord(sx(v)), coord(top), coord(top + size), coord(left), coord(sy(v)), coord(left + size));
  }
  out += R"(</g><g class="ticks" font-size="10" fill="#555">)";
  for (const double v : ticks.values) {
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">{}</text>)", coord(sx(v)), coord(top + size + 13),
                       fixed(v, ticks.decimals));
    out += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", coord(left - 4), coord(sy(v) + 3),
                       fixed(v, ticks.decimals));
  }
  out += "</g>";
  out += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle" class="axis-label">y (left) / m</text>)",
                     coord(left + 0.5 * size), coord(top + size + 28));
  out += fmt::format(R"svg(<text x="12" y="{0}" text-anchor="middle" class="axis-label" transform="rotate(-90 12 {0})">x (forward) / m</text>)svg",
                     coord(top + 0.5 * size));
  // The box, its front edge marked.
  const double a = 0.5 * spec.length_m, b = 0.5 * spec.width_m;
  out += fmt::format(R"(<rect class="box" x="{}" y="{}" width="{}" height="{}" fill="#868e96" fill-opacity="0.15" stroke="#495057"/>)",
                     coord(sx(b)), coord(sy(a)), coord(sx(-b) - sx(b)), coord(sy(-a) - sy(a)));
  out += fmt::format(R"(<line class="front" x1="{0}" y1="{2}" x2="{1}" y2="{2}" stroke="#212529" stroke-width="3"/>)",
                     coord(sx(b)), coord(sx(-b)), coord(sy(a)));
  // Recorded dots under simulated diamonds, each origin's paint once; marks on one pixel square
  // (of either origin) drawn once: 2,000 a side drew 500 KB, most of them on one another.
  out += R"(<g class="targets">)";
  for (const bool simulated : {false, true}) {
    out += simulated ? fmt::format(R"(<g fill="none" stroke="{}" stroke-width="1.2" opacity="0.7">)", kSimulatedColour)
                     : fmt::format(R"(<g fill="{}" opacity="0.45">)", kRecordedColour);
    std::unordered_set<std::int64_t> taken;
    for (const ObjectFramePoint& t : spec.targets) {
      if (t.simulated != simulated) continue;
      const double px = std::clamp(sx(t.p_OT_O.y()), left, left + size);
      const double py = std::clamp(sy(t.p_OT_O.x()), top, top + size);
      if (!taken.insert(static_cast<std::int64_t>(std::floor(px)) * 100000 + static_cast<std::int64_t>(std::floor(py))).second) continue;
      if (simulated) {
        out += fmt::format(R"(<polygon class="t sim" points="{},{} {},{} {},{} {},{}"/>)", coord(px), coord(py - 4), coord(px + 4),
                           coord(py), coord(px), coord(py + 4), coord(px - 4), coord(py));
      } else {
        out += fmt::format(R"(<circle class="t rec" cx="{}" cy="{}" r="2.6"/>)", coord(px), coord(py));
      }
    }
    out += "</g>";
  }
  out += "</g>";
  out += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555"/>)", coord(left), coord(top),
                     coord(size), coord(size));
  out += fmt::format(R"(<text x="{}" y="{}" class="note">dot recorded, diamond simulated; bar: front</text>)",
                     coord(left), coord(top + size + 46));
  return out + "</svg>";
}

}  // namespace rcsim::replay::svg
