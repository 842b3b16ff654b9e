#include "synth/svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/angles.hpp"
#include "common/pose2.hpp"
#include "io/csv_reader.hpp"

namespace rcsim::synth {
namespace {

struct PlotTarget {
  int cycle = 0;
  int sensor = 0;
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0;
};

std::vector<PlotTarget> read_target_list(const std::string& path, const Recording& rec) {
  CsvReader csv(path, {"cycle", "sensor", "range_m", "azimuth_rad", "range_rate_mps"});
  const int c = csv.column("cycle"), s = csv.column("sensor"), r = csv.column("range_m");
  const int az = csv.column("azimuth_rad"), rr = csv.column("range_rate_mps");
  std::vector<PlotTarget> out;
  while (csv.next()) {
    const int sensor = rec.sensor_index(csv.text(s));
    if (sensor < 0) csv.fail(s, "sensor '" + csv.text(s) + "' is not a sensor of the recording");
    out.push_back({static_cast<int>(csv.integer(c)), sensor, csv.number(r), csv.number(az), csv.number(rr)});
  }
  return out;
}

class Canvas {
 public:
  Canvas(double x_min, double x_max, double y_min, double y_max, double px_per_m)
      : x_min_(x_min), y_max_(y_max), scale_(px_per_m), width_(std::ceil((x_max - x_min) * px_per_m)),
        height_(std::ceil((y_max - y_min) * px_per_m)) {}
  double px(double x_m) const { return (x_m - x_min_) * scale_; }
  double py(double y_m) const { return (y_max_ - y_m) * scale_; }
  double width() const { return width_; }
  double height() const { return height_; }
  double scale() const { return scale_; }

 private:
  double x_min_, y_max_, scale_, width_, height_;
};

void polygon(std::string& out, const Canvas& cv, const std::vector<Vec2>& pts, const char* style) {
  out += "<polygon points=\"";
  for (const auto& p : pts) out += fmt::format("{:.1f},{:.1f} ", cv.px(p.x()), cv.py(p.y()));
  out += fmt::format("\" style=\"{}\"/>\n", style);
}

std::vector<Vec2> box_corners(const Pose2& X_VB, double length_m, double width_m) {
  std::vector<Vec2> pts;
  for (const auto& [sx, sy] : {std::pair{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}}) {
    pts.push_back(transform_point(X_VB, Vec2(sx * 0.5 * length_m, sy * 0.5 * width_m)));
  }
  return pts;
}

void marker(std::string& out, const Canvas& cv, const Vec2& p, bool star, const char* color, bool filled) {
  const double x = cv.px(p.x()), y = cv.py(p.y());
  const std::string fill = filled ? color : "none";
  if (star) {
    std::string pts;
    for (int i = 0; i < 10; ++i) {
      const double r = i % 2 == 0 ? 6.0 : 2.6;
      const double a = -kPi / 2 + i * kPi / 5;
      pts += fmt::format("{:.1f},{:.1f} ", x + r * std::cos(a), y + r * std::sin(a));
    }
    out += fmt::format("<polygon points=\"{}\" style=\"fill:{};stroke:{};stroke-width:1\"/>\n", pts, fill, color);
  } else {
    out += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4.5\" style=\"fill:{};stroke:{};stroke-width:1.2\"/>\n", x,
                       y, fill, color);
  }
}

}  // namespace

std::string birds_eye_svg(const Recording& rec, const SvgOptions& options) {
  int last = rec.cycle_count() - 1;
  if (options.time_s >= 0.0) {
    for (int k = 0; k < rec.cycle_count(); ++k) {
      if (rec.ego[k].t_s <= options.time_s + 1e-9) last = k;
    }
  }
  const int first = std::max(0, last - options.cycles + 1);
  const EgoSample& ego = rec.ego[last];
  const Pose2 X_WV{ego.x_m, ego.y_m, ego.yaw_rad};
  // Everything is drawn in the ego frame of the snapshot cycle.
  const auto to_snapshot = [&](int cycle, const Pose2& X_VS, double range_m, double azimuth_rad) {
    const EgoSample& e = rec.ego[cycle];
    const Vec2 p_W = transform_point(compose(Pose2{e.x_m, e.y_m, e.yaw_rad}, X_VS),
                                     Vec2(range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad)));
    return inverse_transform_point(X_WV, p_W);
  };

  struct Layer {
    std::vector<PlotTarget> targets;
    const char* color;
    bool filled;
    std::string label;
  };
  std::vector<Layer> layers;
  {
    std::vector<PlotTarget> reference;
    for (const auto& t : rec.targets) reference.push_back({t.cycle, t.sensor, t.range_m, t.azimuth_rad, t.range_rate_mps});
    layers.push_back({reference, "#1f5fbf", true, "reference (rcsim synth)"});
  }
  if (!options.compare_path.empty()) {
    layers.push_back({read_target_list(options.compare_path, rec), "#d62728", false, "compared target list"});
  }

  // Extent: the ego, the boxes, the fields of view to 15 m and the plotted targets.
  double x_min = -2.0, x_max = 18.0, y_min = -9.0, y_max = 9.0;
  const auto grow = [&](const Vec2& p) {
    x_min = std::min(x_min, p.x() - 1.0);
    x_max = std::max(x_max, p.x() + 1.0);
    y_min = std::min(y_min, p.y() - 1.0);
    y_max = std::max(y_max, p.y() + 1.0);
  };
  std::vector<std::pair<std::size_t, AnnotatedBox>> boxes;
  for (std::size_t i = 0; i < rec.boxes.size(); ++i) {
    for (const auto& b : rec.boxes[i]) {
      if (std::abs(b.t_s - ego.t_s) < 1e-6) boxes.emplace_back(i, b);
    }
  }
  for (const auto& [i, b] : boxes) {
    const Pose2 X_VB{inverse_transform_point(X_WV, Vec2(b.x_m, b.y_m)).x(),
                     inverse_transform_point(X_WV, Vec2(b.x_m, b.y_m)).y(), b.yaw_rad - X_WV.yaw_rad};
    for (const auto& p : box_corners(X_VB, rec.objects[i].length_m, rec.objects[i].width_m)) grow(p);
  }
  for (const auto& layer : layers) {
    for (const auto& t : layer.targets) {
      if (t.cycle < first || t.cycle > last) continue;
      const auto& s = rec.sensors[t.sensor];
      grow(to_snapshot(t.cycle, Pose2{s.x_m, s.y_m, s.yaw_rad}, t.range_m, t.azimuth_rad));
    }
  }
  x_min = std::max(x_min, -10.0), x_max = std::min(x_max, 45.0);
  y_min = std::max(y_min, -30.0), y_max = std::min(y_max, 30.0);
  const double px_per_m = std::clamp(900.0 / std::max(x_max - x_min, y_max - y_min), 10.0, 60.0);
  const Canvas cv(x_min, x_max, y_min, y_max, px_per_m);

  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {:.0f} {:.0f}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      cv.width(), cv.height() + 60, cv.width(), cv.height() + 60);
  // 5 m grid.
  for (double x = std::ceil(x_min / 5.0) * 5.0; x <= x_max; x += 5.0) {
    out += fmt::format("<line x1=\"{0:.1f}\" y1=\"0\" x2=\"{0:.1f}\" y2=\"{1:.1f}\" style=\"stroke:#eee\"/>\n", cv.px(x), cv.height());
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"#999\">{:.0f} m</text>\n", cv.px(x) + 2, cv.height() - 3, x);
  }
  for (double y = std::ceil(y_min / 5.0) * 5.0; y <= y_max; y += 5.0) {
    out += fmt::format("<line x1=\"0\" y1=\"{0:.1f}\" x2=\"{1:.1f}\" y2=\"{0:.1f}\" style=\"stroke:#eee\"/>\n", cv.py(y), cv.width());
  }
  // Ego vehicle and the sensors' fields of view (+-35 deg, 15 m).
  polygon(out, cv, box_corners(Pose2{1.5, 0.0, 0.0}, 4.8, 1.8), "fill:#ddd;stroke:#555");
  for (const auto& s : rec.sensors) {
    const Pose2 X_VS{s.x_m, s.y_m, s.yaw_rad};
    polygon(out, cv,
            {X_VS.translation(), transform_point(X_VS, Vec2(15.0 * std::cos(0.6109), 15.0 * std::sin(0.6109))),
             transform_point(X_VS, Vec2(15.0 * std::cos(0.6109), -15.0 * std::sin(0.6109)))},
            "fill:#f4f4f4;fill-opacity:0.5;stroke:#bbb;stroke-dasharray:4,3");
  }
  // Annotated boxes at the snapshot.
  for (const auto& [i, b] : boxes) {
    const Vec2 c = inverse_transform_point(X_WV, Vec2(b.x_m, b.y_m));
    polygon(out, cv, box_corners(Pose2{c.x(), c.y(), b.yaw_rad - X_WV.yaw_rad}, rec.objects[i].length_m, rec.objects[i].width_m),
            "fill:none;stroke:#333;stroke-width:1.5");
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"#333\">{}</text>\n", cv.px(c.x()),
                       cv.py(c.y()) - 4, rec.objects[i].id);
  }
  // Targets of the last cycles: position and a range-rate line along the line of sight (0.5 s).
  for (const auto& layer : layers) {
    for (const auto& t : layer.targets) {
      if (t.cycle < first || t.cycle > last) continue;
      const auto& s = rec.sensors[t.sensor];
      const Pose2 X_VS{s.x_m, s.y_m, s.yaw_rad};
      const Vec2 p = to_snapshot(t.cycle, X_VS, t.range_m, t.azimuth_rad);
      const Vec2 q = to_snapshot(t.cycle, X_VS, std::max(0.0, t.range_m + 0.5 * t.range_rate_mps), t.azimuth_rad);
      out += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" style=\"stroke:{};stroke-width:1\"/>\n",
                         cv.px(p.x()), cv.py(p.y()), cv.px(q.x()), cv.py(q.y()), layer.color);
      marker(out, cv, p, s.y_m > 0.0, layer.color, layer.filled);
    }
  }
  // Legend.
  double ly = cv.height() + 18;
  out += fmt::format("<text x=\"8\" y=\"{:.0f}\" font-size=\"13\">{} - t = {:.2f} s, targets of cycles {}..{} (stars: left sensor, circles: right sensor; lines: range rate x 0.5 s)</text>\n",
                     ly, options.title, ego.t_s, first, last);
  for (const auto& layer : layers) {
    ly += 18;
    out += fmt::format("<circle cx=\"14\" cy=\"{:.0f}\" r=\"5\" style=\"fill:{};stroke:{}\"/><text x=\"26\" y=\"{:.0f}\" font-size=\"12\">{}</text>\n",
                       ly - 4, layer.filled ? layer.color : "none", layer.color, ly, layer.label);
  }
  out += "</svg>\n";
  return out;
}

}  // namespace rcsim::synth
