#pragma once
// The cells and rows the report's HTML tables are made of. Every text is escaped here; numbers
// are formatted by svg::fixed (no locale, no "-0").
#include <cstdint>
#include <fmt/format.h>
#include <initializer_list>
#include <optional>
#include <string>

#include "common/angles.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

// Where figures need the targets, which a run stored with `rcsim replay --store summary` lacks;
// `figures` is plural ("The residual histograms").
inline std::string needs_full_store(const std::string& figures) {
  return fmt::format(R"(<p class="hint needs-full-store">{} need the targets, which this run does not hold: it was )"
                     R"(stored with <code>rcsim replay --store summary</code>. Replay it with <code>--store full</code> )"
                     R"(to see them.</p>)",
                     svg::escape(figures));
}

inline std::string num(double value, int decimals) { return svg::fixed(value, decimals); }

inline std::string opt(const std::optional<double>& value, int decimals, const char* none = "never") {
  return value ? svg::fixed(*value, decimals) : std::string(none);
}

inline std::string deg(double angle_rad, int decimals) { return svg::fixed(rad_to_deg(angle_rad), decimals); }

// A two-column row of a key-value table; `key` names the value for machine checks.
inline std::string kv(const char* key, const std::string& label, const std::string& value, const std::string& unit,
                      bool text = false) {
  return fmt::format(R"(<tr><th>{}</th><td class="{}" data-key="{}">{}</td><td>{}</td></tr>)", svg::escape(label),
                     text ? "text" : "num", key, svg::escape(value), svg::escape(unit));
}

inline std::string header_row(std::initializer_list<const char*> names) {
  std::string out = "<tr>";
  for (const char* n : names) out += fmt::format("<th>{}</th>", n);
  return out + "</tr>";
}

inline std::string cell(const std::string& text) { return "<td>" + svg::escape(text) + "</td>"; }
inline std::string cell_num(const std::string& text) { return R"(<td class="num">)" + svg::escape(text) + "</td>"; }

inline std::string percent(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? fmt::format("{:.1f} %", 100.0 * static_cast<double>(part) / static_cast<double>(whole)) : "-";
}

}  // namespace rcsim::replay::report
