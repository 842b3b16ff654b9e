#pragma once
// Small helpers for the SVG pictures and the HTML page of `rcsim report`: escaping of any text
// that may come from a recording, compact number formatting, and axis scales with round ticks.
#include <string>
#include <string_view>
#include <vector>

namespace rcsim::replay::svg {

// The plot frame's margins inside a chart (px): room for the axis labels and the title.
inline constexpr double kMarginLeft = 64.0, kMarginRight = 14.0, kMarginTop = 40.0, kMarginBottom = 44.0;

// Escapes text for HTML/SVG element content and double- or single-quoted attribute values
// (& < > " '). Every string that came from a recording or the database goes through this.
std::string escape(std::string_view text);

// At most `max_chars` characters (UTF-8 code points) of `text`, with an ellipsis if cut.
std::string shorten(std::string_view text, std::size_t max_chars);

// A coordinate in SVG user units: one decimal, no "-0".
std::string coord(double value);

// A value for a table or a tick label with `decimals` decimals; "–" (dash) for NaN.
std::string fixed(double value, int decimals);

// Maps the data interval [d0, d1] linearly onto the pixel interval [p0, p1].
struct LinearScale {
  double d0 = 0.0, d1 = 1.0, p0 = 0.0, p1 = 1.0;
  double operator()(double value) const { return p0 + (value - d0) * (p1 - p0) / (d1 - d0); }
};

// Round tick positions (1, 2, 5 times a power of ten) covering [lo, hi] with about `count` ticks.
struct Ticks {
  std::vector<double> values;
  double step = 1.0;
  int decimals = 0;  // enough to tell neighbouring ticks apart
};
Ticks nice_ticks(double lo, double hi, int count);

// Widens [lo, hi] to a non-empty interval (a degenerate one by `min_span` about its centre)
// and pads it by `pad_fraction` of its span on both sides.
void widen(double& lo, double& hi, double min_span, double pad_fraction);

}  // namespace rcsim::replay::svg
