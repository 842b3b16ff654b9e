#pragma once
// Built-in sensor configurations as JSON documents to edit in a test, and the message a parse of
// an edited one gives (the field path it names).
#include <nlohmann/json.hpp>
#include <string>

#include "common/embedded_data.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::testing {

// The built-in configuration `name` as JSON; null when there is none.
inline nlohmann::json builtin_sensor_json(const std::string& name) {
  for (const auto& f : embedded_sensor_configs()) {
    if (f.name == name) return nlohmann::json::parse(f.text);
  }
  return {};
}

// What parse_sensor_config says of `doc` (read as "s.json"); "" when it is accepted.
inline std::string sensor_config_error(const nlohmann::json& doc) {
  try {
    parse_sensor_config(JsonField(doc, "s.json", ""));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace rcsim::testing
