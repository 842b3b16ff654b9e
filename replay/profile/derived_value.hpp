#pragma once
// One value of a derived sensor profile with its evidence (`rcsim profile derive`,
// docs/profile-derive.md): where it came from, the figure that shows it, how much data it rests on.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace rcsim::replay::profile {

enum class ValueSource {
  derived,    // measured on the recordings
  recording,  // read from the recordings' own header (reports, the amplitude's unit, the Doppler interval)
  base,       // the data cannot show it: the base profile's value
};
const char* value_source_name(ValueSource source);

// A value as printed and in the report: a number in %g, a string as it is, anything else as JSON.
std::string value_text(const nlohmann::json& value);

struct DerivedValue {
  std::string field;  // the rcsim-sensor field, dotted: "field_of_view.azimuth_half_deg"
  nlohmann::json value;
  ValueSource source = ValueSource::derived;
  std::string evidence;   // the figure and how it was read ("99.9 % quantile of |azimuth| 16.8 deg ...")
  long long support = 0;  // detections (or pairs) it rests on; 0 for a value taken as it stands
  // A derived number's interval from its evidence (the quantile spread it was read from, the
  // least-squares standard errors, the span over which a gap's edge rises): [low, high] in the
  // value's unit; NaN where the value has none (a word, a value taken as it stands).
  double low = std::nan(""), high = std::nan("");
  // The data barely show it (few detections or pairs, no sharp edge): the value stands, but weakly.
  bool weak = false;
  bool has_interval() const { return std::isfinite(low) && std::isfinite(high); }
};

// "derived", "derived, weak", "base", "recording": the source column of the printed table, the
// JSON and the report.
std::string source_text(const DerivedValue& value);
// "[low, high]" in %g, or "" where the value has no interval.
std::string interval_text(const DerivedValue& value);
// A value with its interval and mark set.
inline DerivedValue with_interval(DerivedValue value, double low, double high, bool weak) {
  value.low = low, value.high = high, value.weak = weak;
  // The interval holds the value as written (rounded to its step).
  if (value.value.is_number() && std::isfinite(low) && std::isfinite(high)) {
    const double v = value.value.get<double>();
    value.low = std::min(value.low, v), value.high = std::max(value.high, v);
  }
  return value;
}

}  // namespace rcsim::replay::profile
