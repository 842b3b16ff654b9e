#include "common/json_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "common/text_file.hpp"

namespace rcsim {

namespace {

// "line L, column C" of a byte offset, for a person to jump to.
std::string line_and_column(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return fmt::format("line {}, column {}", line, column);
}

// The most values (numbers, strings, literals, arrays, objects) one document may hold. Parsed,
// a value costs 16 bytes in its array and an object's member some 100 (a map node and its key):
// bounded by bytes alone, 231 MB of `{"a0":0,"a1":0,...}` took more than 6 GB (issue 51). No
// rcsim format comes near: a scene's hour-long trajectory at 10 Hz holds 180,000
// (schemas/limits.md).
constexpr std::size_t kMaxJsonValues = std::size_t{1} << 22;

// The byte offset where a document's values first exceed kMaxJsonValues; nullopt if they never
// do. Counts an upper bound in one pass: every value but the first of an array or object follows
// a comma, and the first its bracket. Linear, allocates nothing.
std::optional<std::size_t> json_too_wide_at(std::string_view text) {
  std::size_t values = 1;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == ',' || c == '[' || c == '{') {
      if (++values > kMaxJsonValues) return i;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::size_t> json_too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character, a quote too
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::nullopt;
}

nlohmann::json parse_json_text(std::string_view text, const std::string& file) {
  if (const auto at = json_too_deep_at(text)) {
    throw InputError(file, line_and_column(text, *at),
                     fmt::format("arrays and objects nest deeper than {} levels; no rcsim format needs that many",
                                 kMaxJsonDepth));
  }
  if (const auto at = json_too_wide_at(text)) {
    throw InputError(file, line_and_column(text, *at),
                     fmt::format("more than {} values (numbers, strings, arrays, objects) in one document; no rcsim "
                                 "format needs that many (schemas/limits.md)",
                                 kMaxJsonValues));
  }
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& error) {
    std::string message = error.what();
    if (const auto pos = message.find("syntax error"); pos != std::string::npos) message = message.substr(pos);
    throw InputError(file, line_and_column(text, error.byte > 0 ? error.byte - 1 : 0), "invalid JSON: " + message);
  } catch (const nlohmann::json::exception& error) {
    // e.g. a number too large for a double ("number overflow parsing '1e999'")
    std::string message = error.what();
    if (const auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    throw InputError(file, "", "invalid JSON: " + message);
  }
}

nlohmann::json parse_json_file(const std::string& path) { return parse_json_text(read_text_file(path), path); }

nlohmann::ordered_json parse_stored_json(std::string_view text) {
  if (json_too_deep_at(text) || json_too_wide_at(text)) return nlohmann::ordered_json(nlohmann::ordered_json::value_t::discarded);
  return nlohmann::ordered_json::parse(text.begin(), text.end(), nullptr, false);
}

JsonField::JsonField(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonField::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void JsonField::fail(std::string_view key, const std::string& message) const {
  throw InputError(file_, child_path(key), message);
}

void JsonField::fail(const std::string& message) const {
  throw InputError(file_, path_.empty() ? "(top level)" : path_, message);
}

bool JsonField::has(std::string_view key) const {
  return value_->is_object() && value_->contains(key);
}

const nlohmann::json& JsonField::require(std::string_view key) const {
  if (!value_->is_object()) fail("must be a JSON object");
  const auto it = value_->find(key);
  if (it == value_->end()) fail(key, "missing required field");
  return *it;
}

JsonField JsonField::member(std::string_view key) const {
  const auto& value = require(key);
  if (!value.is_object()) fail(key, "must be a JSON object");
  return {value, file_, child_path(key)};
}

std::optional<JsonField> JsonField::optional_member(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return member(key);
}

double JsonField::number(std::string_view key) const {
  const auto& value = require(key);
  if (!value.is_number()) fail(key, "must be a number, got " + std::string(value.type_name()));
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  return x;
}

double JsonField::number_within(std::string_view key, double min, double max, std::string_view unit) const {
  const double x = number(key);
  if (!(x >= min && x <= max)) {
    fail(key, fmt::format("{} is beyond the limits [{}, {}]{}{} (schemas/limits.md)", x, min, max, unit.empty() ? "" : " ",
                          unit));
  }
  return x;
}

double JsonField::angle_rad(std::string_view key, double max_rad) const {
  const double x = number(key);
  if (std::abs(x) > max_rad) fail(key, fmt::format("{} rad is beyond ±{} rad: is it in degrees?", x, max_rad));
  return x;
}

std::optional<double> JsonField::optional_number(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return number(key);
}

double JsonField::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

std::string JsonField::string(std::string_view key) const {
  const auto& value = require(key);
  if (!value.is_string()) fail(key, "must be a string, got " + std::string(value.type_name()));
  auto text = value.get<std::string>();
  if (text.empty()) fail(key, "must not be empty");
  return text;
}

bool JsonField::boolean_or(std::string_view key, bool fallback) const {
  if (!has(key)) return fallback;
  const auto& value = require(key);
  if (!value.is_boolean()) fail(key, "must be true or false, got " + std::string(value.type_name()));
  return value.get<bool>();
}

std::vector<JsonField> JsonField::array(std::string_view key) const {
  const auto& value = require(key);
  if (!value.is_array()) fail(key, "must be an array, got " + std::string(value.type_name()));
  return JsonField(value, file_, child_path(key)).elements();
}

std::vector<JsonField> JsonField::elements() const {
  if (!value_->is_array()) fail("must be an array");
  std::vector<JsonField> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) {
    out.emplace_back((*value_)[i], file_, fmt::format("{}[{}]", path_, i));
  }
  return out;
}

void JsonField::expect_only(std::initializer_list<std::string_view> keys) const {
  if (!value_->is_object()) fail("must be a JSON object");
  for (const auto& [key, unused] : value_->items()) {
    bool known = false;
    for (const auto& k : keys) known = known || key == k;
    if (!known) {
      std::string expected;
      for (const auto& k : keys) expected += (expected.empty() ? "" : ", ") + std::string(k);
      fail(key, "unknown field (expected one of: " + expected + ")");
    }
  }
}

void JsonField::expect_format(std::string_view format, int version) const {
  const std::string found = string("format");
  if (found != format) fail("format", fmt::format("expected \"{}\", got \"{}\"", format, found));
  const double v = number("version");
  if (v != version) fail("version", fmt::format("unsupported version {} (this rcsim reads version {})", v, version));
}

int JsonField::expect_format_versions(std::string_view format, int min_version, int max_version) const {
  const std::string found = string("format");
  if (found != format) fail("format", fmt::format("expected \"{}\", got \"{}\"", format, found));
  const double v = number("version");
  for (int version = min_version; version <= max_version; ++version) {
    if (v == version) return version;
  }
  fail("version", fmt::format("unsupported version {} (this rcsim reads versions {} to {})", v, min_version, max_version));
}

void require_positive(const JsonField& field, std::string_view key, double value) {
  if (!(value > 0.0)) field.fail(key, fmt::format("must be positive, got {}", value));
}

void require_non_negative(const JsonField& field, std::string_view key, double value) {
  if (!(value >= 0.0)) field.fail(key, fmt::format("must not be negative, got {}", value));
}

}  // namespace rcsim
