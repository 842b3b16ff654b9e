#pragma once
// The speed-against-error plot of `rcsim bench` for the HTML report, as self-contained SVG text:
// one point per fidelity level, x = sensor cycles per CPU second on a log10 axis, y = error
// (GOSPA mean, m) on a linear axis from zero; the Pareto front joined by a line, the noise floor
// as a dashed horizontal line, the default level highlighted. Every label is escaped here.
#include <optional>
#include <string>
#include <vector>

namespace rcsim::replay::svg {

struct ParetoPoint {
  std::string label;              // the level's name
  double cycles_per_cpu_s = 0.0;  // must be finite and > 0 to be drawn
  double error_m = 0.0;           // must be finite to be drawn
  bool highlighted = false;       // the default level
};

// Data ranges an axis must cover besides the points, so that small multiples share their axes.
struct ParetoExtent {
  double cycles_per_cpu_s_lo = 0.0, cycles_per_cpu_s_hi = 0.0;  // ignored unless finite and > 0
  double error_hi_m = 0.0;
};

struct ParetoSpec {
  std::string title;
  std::string note;  // small text under the title
  std::string x_label, y_label;
  int width_px = 760, height_px = 440;
  bool legend = true;  // the key to the markers and lines, in the title line
  std::vector<ParetoPoint> points;
  std::optional<double> noise_floor_m;  // dashed horizontal line, when known
  std::optional<ParetoExtent> extent;
};

// Per point: whether it is on the Pareto front, i.e. no other drawable point is at least as fast
// and at least as accurate and strictly better in one of the two. Points that cannot be drawn
// (speed not finite and positive, or error not finite) are never on the front and dominate nothing.
std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points);

std::string pareto_svg(const ParetoSpec& spec);

// A speed for a label or a table: whole cycles from 100 up, else three significant digits.
std::string speed_text(double cycles_per_cpu_s);

// "10⁵": a power of ten with a superscript exponent, for log-axis tick labels.
std::string power_of_ten_label(int exponent);

}  // namespace rcsim::replay::svg
