#pragma once
// One value of a derived sensor profile with its evidence (`rcsim profile derive`,
// docs/profile-derive.md): where it came from, the figure that shows it, how much data it rests on.
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
};

}  // namespace rcsim::replay::profile
