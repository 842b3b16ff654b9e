// Strict JSON reading (common/json_reader.hpp): parse errors with line and column, the nesting
// limit checked before parsing, and every JsonField refusal naming the file and the field path.
#include "common/json_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "common/input_error.hpp"
#include "peak_memory.hpp"
#include "refusal.hpp"

namespace rcsim::json_reader_test {

using testing::refusal_of;

TEST(JsonReader, SyntaxErrorsNameTheLineAndColumn) {
  // Line 2 is `  "b": tru}`: the bad literal ends at column 11, where '}' stands.
  EXPECT_EQ(refusal_of([] { parse_json_text("{\"a\": 1,\n  \"b\": tru}", "x.json"); }),
            "x.json: line 2, column 11: invalid JSON: syntax error while parsing value - invalid literal; last "
            "read: '\"b\": tru}'");
  EXPECT_EQ(refusal_of([] { parse_json_text("", "empty.json"); }),
            "empty.json: line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of input; "
            "expected '[', '{', or a literal");
  // Not a syntax error: a number beyond a double. No place, the reason only.
  EXPECT_EQ(refusal_of([] { parse_json_text("[1e999]", "big.json"); }),
            "big.json: invalid JSON: number overflow parsing '1e999'");
  EXPECT_EQ(parse_json_text("{\"a\": [1, 2]}", "ok.json")["a"][1], 2);
  // Stored JSON never throws: bad text is a discarded value.
  EXPECT_TRUE(parse_stored_json("{\"a\":").is_discarded());
  EXPECT_EQ(parse_stored_json("{\"b\": 1, \"a\": 2}").begin().key(), "b");  // order kept
}

TEST(JsonReader, JsonNestedBeyondTheLimitIsRefusedBeforeItIsParsed) {
  const auto nested = [](int depth, std::string_view open = "[", std::string_view close = "]") {
    std::string text;
    for (int i = 0; i < depth; ++i) text += open;
    for (int i = 0; i < depth; ++i) text += close;
    return text;
  };
  EXPECT_NO_THROW(parse_json_text(nested(kMaxJsonDepth), "ok.json"));
  EXPECT_EQ(refusal_of([&] { parse_json_text(nested(kMaxJsonDepth + 1), "deep.json"); }),
            "deep.json: line 1, column 65: arrays and objects nest deeper than 64 levels; no rcsim format needs that many");
  // 10^7 deep: refused at the 65th bracket, nothing allocated for the rest.
  EXPECT_NE(refusal_of([&] { parse_json_text(nested(10'000'000), "huge.json"); }).find("huge.json: line 1, column 65"),
            std::string::npos);
  // Brackets inside strings, escaped quotes included, do not count.
  const std::string quoted = "{\"a\": \"" + nested(100) + "\\\"" + nested(100) + "\"}";
  EXPECT_NO_THROW(parse_json_text(quoted, "quoted.json"));
  EXPECT_EQ(json_too_deep_at(nested(3, "{\"k\":", "}"), 2), std::size_t{10});
  // Stored JSON (a report's manifest, parameters) nested too deep is not JSON to the reader.
  EXPECT_TRUE(parse_stored_json(nested(100'000)).is_discarded());
  EXPECT_FALSE(parse_stored_json(nested(10)).is_discarded());
}

// Issue 51: bounded by bytes alone, 231 MB of object members took more than 6 GB once parsed. A
// document holds at most 2^22 values, counted in one pass before parsing; commas inside strings
// do not count.
TEST(JsonReader, JsonWiderThanTheLimitIsRefusedBeforeItIsParsed) {
  const auto members = [](std::size_t n) {
    std::string text = "{";
    for (std::size_t i = 0; i < n; ++i) text.append(i ? ",\"" : "\"").append(std::to_string(i)).append("\":0");
    return text + "}";
  };
  const std::string wide = members(std::size_t{1} << 22);  // 2^22 + 1 values: the object and its members
  std::string message;
  const auto added = rcsim::testing::peak_memory_added_by([&] { message = refusal_of([&] { parse_json_text(wide, "wide.json"); }); });
  EXPECT_EQ(message.rfind("wide.json: line 1, column ", 0), 0u) << message;
  EXPECT_NE(message.find("more than 4194304 values (numbers, strings, arrays, objects) in one document"), std::string::npos)
      << message;
  if (added) {
    EXPECT_LT(*added, 16 << 20) << "bytes added";
  }
  EXPECT_TRUE(parse_stored_json(wide).is_discarded());
  EXPECT_NO_THROW(parse_json_text(members(1000), "ok.json"));
  EXPECT_NO_THROW(parse_json_text("[\"" + std::string(5'000'000, ',') + "\"]", "commas_in_a_string.json"));
}

TEST(JsonReader, FieldsAreReadByPathAndRefusedNamingIt) {
  const nlohmann::json doc = nlohmann::json::parse(
      R"({"s": "", "n": "3", "b": 1, "x_m": 2.5, "arr": [1, {"c": "x"}], "sub": {"deep": {"v": -4}}})");
  const JsonField root(doc, "f.json", "");
  EXPECT_DOUBLE_EQ(root.member("sub").member("deep").number("v"), -4.0);
  EXPECT_EQ(root.member("sub").member("deep").path(), "sub.deep");
  EXPECT_EQ(root.array("arr")[1].path(), "arr[1]");
  EXPECT_EQ(root.optional_number("absent"), std::nullopt);
  EXPECT_DOUBLE_EQ(root.number_or("absent", 7.0), 7.0);
  EXPECT_DOUBLE_EQ(root.number_or("x_m", 7.0), 2.5);
  EXPECT_TRUE(root.boolean_or("absent", true));
  EXPECT_FALSE(root.optional_member("absent").has_value());
  EXPECT_EQ(refusal_of([&] { root.string("s"); }), "f.json: s: must not be empty");
  EXPECT_EQ(refusal_of([&] { root.number("n"); }), "f.json: n: must be a number, got string");
  EXPECT_EQ(refusal_of([&] { root.boolean_or("b", true); }), "f.json: b: must be true or false, got number");
  EXPECT_EQ(refusal_of([&] { root.array("arr")[1].number("c"); }), "f.json: arr[1].c: must be a number, got string");
  EXPECT_EQ(refusal_of([&] { root.array("arr")[0].number("c"); }), "f.json: arr[0]: must be a JSON object");
  EXPECT_EQ(refusal_of([&] { root.member("sub").number("missing"); }), "f.json: sub.missing: missing required field");
  EXPECT_EQ(refusal_of([&] { root.array("b"); }), "f.json: b: must be an array, got number");
  EXPECT_EQ(refusal_of([&] { root.member("arr"); }), "f.json: arr: must be a JSON object");
  EXPECT_EQ(refusal_of([&] { root.fail("broken"); }), "f.json: (top level): broken");
  // A dotted field as a JSON pointer.
  EXPECT_EQ(doc.at(field_pointer("sub.deep.v")), -4);
}

TEST(JsonReader, LimitsUnknownFieldsAndFormatsAreNamed) {
  const nlohmann::json doc = nlohmann::json::parse(
      R"({"format": "rcsim-scene", "version": 2, "x_m": 1, "yaw_rad": 90, "length_mm": 4500})");
  const JsonField root(doc, "s.json", "");
  EXPECT_DOUBLE_EQ(root.number_within("x_m", 1.0, 10.0, "m"), 1.0);  // bounds are inclusive
  EXPECT_EQ(refusal_of([&] { root.number_within("x_m", 2.5, 10.0, "m"); }),
            "s.json: x_m: 1 is beyond the limits [2.5, 10] m (schemas/limits.md)");
  EXPECT_EQ(refusal_of([&] { root.number_within("x_m", 2.5, 10.0, ""); }),
            "s.json: x_m: 1 is beyond the limits [2.5, 10] (schemas/limits.md)");
  EXPECT_EQ(refusal_of([&] { root.angle_rad("yaw_rad", 3.1416); }),
            "s.json: yaw_rad: 90 rad is beyond ±3.1416 rad: is it in degrees?");
  EXPECT_EQ(refusal_of([&] { root.expect_only({"format", "version", "x_m", "yaw_rad"}); }),
            "s.json: length_mm: unknown field (expected one of: format, version, x_m, yaw_rad)");
  EXPECT_EQ(refusal_of([&] { root.expect_format("rcsim-scene", 1); }),
            "s.json: version: unsupported version 2 (this rcsim reads version 1)");
  EXPECT_EQ(refusal_of([&] { root.expect_format("rcsim-recording", 2); }),
            "s.json: format: expected \"rcsim-recording\", got \"rcsim-scene\"");
  EXPECT_EQ(root.expect_format_versions("rcsim-scene", 1, 3), 2);
  EXPECT_EQ(refusal_of([&] { root.expect_format_versions("rcsim-scene", 3, 4); }),
            "s.json: version: unsupported version 2 (this rcsim reads versions 3 to 4)");
  EXPECT_EQ(refusal_of([&] { require_positive(root, "x_m", 0.0); }), "s.json: x_m: must be positive, got 0");
  EXPECT_EQ(refusal_of([&] { require_non_negative(root, "x_m", -0.5); }), "s.json: x_m: must not be negative, got -0.5");
  EXPECT_NO_THROW(require_non_negative(root, "x_m", 0.0));
}

}  // namespace rcsim::json_reader_test
