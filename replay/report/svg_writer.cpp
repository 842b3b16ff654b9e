#include "replay/report/svg_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/xml_escape.hpp"

namespace rcsim::replay::svg {

std::string escape(std::string_view text) { return xml_escape(text); }

std::string shorten(std::string_view text, std::size_t max_chars) {
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) continue;  // a continuation byte
    if (chars == max_chars) return std::string(text.substr(0, i)) + "\u2026";
    ++chars;
  }
  return std::string(text);
}

std::string coord(double value) {
  std::string text = fmt::format("{:.1f}", value);
  if (text == "-0.0") text = "0.0";
  if (text.size() > 2 && text.compare(text.size() - 2, 2, ".0") == 0) text.resize(text.size() - 2);
  return text;
}

std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "\u2013";
  std::string text = fmt::format("{:.{}f}", value, std::max(0, decimals));
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

Ticks nice_ticks(double lo, double hi, int count) {
  Ticks ticks;
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) {
    ticks.values = {lo};
    return ticks;
  }
  const double raw = span / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double nice = fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0;
  ticks.step = nice * power;
  ticks.decimals = std::max(0, static_cast<int>(-std::floor(std::log10(ticks.step) + 1e-9)));
  const double first = std::ceil(lo / ticks.step - 1e-9) * ticks.step;
  for (double v = first; v <= hi + ticks.step * 1e-9; v += ticks.step) {
    ticks.values.push_back(std::abs(v) < ticks.step * 1e-9 ? 0.0 : v);
    if (ticks.values.size() > 100) break;
  }
  return ticks;
}

void widen(double& lo, double& hi, double min_span, double pad_fraction) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    lo = 0.0;
    hi = min_span;
  }
  if (hi - lo < min_span) {
    const double centre = 0.5 * (lo + hi);
    lo = centre - 0.5 * min_span;
    hi = centre + 0.5 * min_span;
  }
  const double pad = (hi - lo) * pad_fraction;
  lo -= pad;
  hi += pad;
}

}  // namespace rcsim::replay::svg
