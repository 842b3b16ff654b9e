#pragma once
// Strict reading of our JSON files: every lookup knows its field path, every number is checked
// finite, unknown fields are refused (a misspelt or wrongly-united key is an error, not ignored).
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"

namespace rcsim {

// The deepest nesting of arrays and objects any of our JSON formats may hold (a scene needs 6):
// deeper text is refused before it is parsed, so that neither memory nor a recursive walk
// (comparing, printing, destroying) grows with an attacker's nesting (schemas/limits.md).
inline constexpr int kMaxJsonDepth = 64;

// The byte offset in JSON text where arrays and objects first nest deeper than `max_depth`
// (brackets inside strings do not count); nullopt if they never do. Linear, allocates nothing.
std::optional<std::size_t> json_too_deep_at(std::string_view text, int max_depth = kMaxJsonDepth);

// Parses JSON text; syntax errors and nesting deeper than kMaxJsonDepth name the file, line and column.
nlohmann::json parse_json_text(std::string_view text, const std::string& file);

// Parses JSON text stored by rcsim (a report database's parameters, provenance, manifest): a
// discarded value if it is not JSON or nests deeper than kMaxJsonDepth, never an exception.
nlohmann::ordered_json parse_stored_json(std::string_view text);
// Reads and parses a file.
nlohmann::json parse_json_file(const std::string& path);

// A dotted field name as a JSON pointer: "amplitude.range_exponent" -> /amplitude/range_exponent.
inline nlohmann::json::json_pointer field_pointer(const std::string& dotted_field) {
  std::string path = "/" + dotted_field;
  for (char& c : path) c = c == '.' ? '/' : c;
  return nlohmann::json::json_pointer(path);
}

class JsonField {
 public:
  JsonField(const nlohmann::json& value, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const nlohmann::json& json() const { return *value_; }

  bool has(std::string_view key) const;
  JsonField member(std::string_view key) const;  // required member
  std::optional<JsonField> optional_member(std::string_view key) const;

  double number(std::string_view key) const;  // required, finite
  // Required, within [min, max] (schemas/limits.md); the unit names the bound in the message.
  double number_within(std::string_view key, double min, double max, std::string_view unit) const;
  // A required angle in radians within ±max_rad; beyond, the message asks whether it is in degrees.
  double angle_rad(std::string_view key, double max_rad) const;
  std::optional<double> optional_number(std::string_view key) const;
  double number_or(std::string_view key, double fallback) const;
  std::string string(std::string_view key) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::vector<JsonField> array(std::string_view key) const;  // required array
  std::vector<JsonField> elements() const;                   // this field as array

  // Refuses any member not listed.
  void expect_only(std::initializer_list<std::string_view> keys) const;
  // Checks "format" and "version".
  void expect_format(std::string_view format, int version) const;
  // Checks "format" and that "version" is one of min_version..max_version; returns it.
  int expect_format_versions(std::string_view format, int min_version, int max_version) const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string child_path(std::string_view key) const;
  const nlohmann::json& require(std::string_view key) const;

  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
};

// Checks on numbers that every loader needs.
void require_positive(const JsonField& field, std::string_view key, double value);
void require_non_negative(const JsonField& field, std::string_view key, double value);

}  // namespace rcsim
