// Foxglove's JSON messages as `rcsim import --from mcap` reads them (replay/import/foxglove_messages.hpp):
// base64 by RFC 4648's own examples, a point cloud's fields of several numeric types at their
// offsets, a scene update's first cube per entity; and what is refused.
#include "replay/import/foxglove_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>

namespace rcsim::replay::foxglove::foxglove_messages_test {
namespace {

TEST(FoxgloveMessages, Base64ByTheRfcsExamples) {
  EXPECT_EQ(decode_base64(""), "");
  EXPECT_EQ(decode_base64("Zg=="), "f");
  EXPECT_EQ(decode_base64("Zm8="), "fo");
  EXPECT_EQ(decode_base64("Zm9v"), "foo");
  EXPECT_EQ(decode_base64("Zm9vYmFy"), "foobar");
  EXPECT_EQ(decode_base64("Zm9vYg"), "foob");  // padding optional
  EXPECT_EQ(decode_base64("//+/"), std::string("\xff\xff\xbf", 3));
  EXPECT_THROW(decode_base64("Zm9v!"), std::invalid_argument);
  EXPECT_THROW(decode_base64("Zm9vY"), std::invalid_argument);  // cut inside a byte
}

// Two points of 12 bytes: x, y float32 at 0 and 4, z int16 at 8, range_rate int8 at 10, amplitude
// uint8 at 11.
std::string cloud_json(const std::string& fields, const std::string& data_base64, int stride = 12) {
  return R"({"timestamp": {"sec": 3, "nsec": 250}, "frame_id": "front", "pose": {"position": {"x": 1, "y": 2, "z": 0},
    "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}}, "point_stride": )" + std::to_string(stride) + R"(, "fields": )" + fields +
         R"(, "data": ")" + data_base64 + R"("})";
}

std::string two_points() {
  std::string b(24, '\0');
  const auto put = [&b](std::size_t at, auto v) { std::memcpy(b.data() + at, &v, sizeof v); };
  put(0, 10.5f), put(4, -2.0f), put(8, std::int16_t{-3}), put(10, std::int8_t{-7}), put(11, std::uint8_t{200});
  put(12, 0.25f), put(16, 8.0f), put(20, std::int16_t{4}), put(22, std::int8_t{5}), put(23, std::uint8_t{1});
  // base64 by hand is the test's job only where the RFC's examples are; this one the decoder round trips.
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < b.size(); i += 3) {
    const std::uint32_t v = (static_cast<std::uint8_t>(b[i]) << 16) | (static_cast<std::uint8_t>(b[i + 1]) << 8) | static_cast<std::uint8_t>(b[i + 2]);
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  return out;
}

const std::string kFields = R"([{"name": "x", "offset": 0, "type": 7}, {"name": "y", "offset": 4, "type": 7},
  {"name": "z", "offset": 8, "type": 4}, {"name": "range_rate", "offset": 10, "type": 2}, {"name": "amplitude", "offset": 11, "type": 1}])";

TEST(FoxgloveMessages, APointCloudsFieldsAtTheirOffsetsAndTypes) {
  simdjson::ondemand::parser parser;
  const PointCloud cloud = decode_point_cloud(parser, cloud_json(kFields, two_points()), {"x", "y", "z", "range_rate", "amplitude"});
  EXPECT_EQ(cloud.t_ns, 3'000'000'250LL);
  EXPECT_EQ(cloud.frame_id, "front");
  EXPECT_EQ(cloud.position[0], 1.0);
  EXPECT_EQ(cloud.position[1], 2.0);
  ASSERT_EQ(cloud.size(), 2u);
  const auto values = [](std::span<const double> p) { return std::vector<double>(p.begin(), p.end()); };
  EXPECT_EQ(values(cloud.point(0)), (std::vector<double>{10.5, -2.0, -3.0, -7.0, 200.0}));
  EXPECT_EQ(values(cloud.point(1)), (std::vector<double>{0.25, 8.0, 4.0, 5.0, 1.0}));
  // Asked in another order, fewer fields.
  EXPECT_EQ(values(decode_point_cloud(parser, cloud_json(kFields, two_points()), {"amplitude", "x"}).point(1)), (std::vector<double>{1.0, 0.25}));
}

TEST(FoxgloveMessages, WhatAPointCloudLacksIsNamed) {
  simdjson::ondemand::parser parser;
  const auto refusal = [&](const std::string& json, const std::vector<std::string>& fields) {
    try {
      decode_point_cloud(parser, json, fields);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(cloud_json(kFields, two_points()), {"x", "doppler"}), "fields: no field 'doppler'");
  EXPECT_NE(refusal(cloud_json(R"([{"name": "x", "offset": 10, "type": 8}])", two_points()), {"x"}).find("run past the stride 12"),
            std::string::npos);
  EXPECT_NE(refusal(cloud_json(kFields, two_points().substr(0, 28)), {"x"}).find("no whole number of 12-byte points"), std::string::npos);
  EXPECT_NE(refusal(cloud_json(R"([{"name": "x", "offset": 0, "type": 9}])", two_points()), {"x"}).find("no numeric type"), std::string::npos);
  EXPECT_NE(refusal(R"({"timestamp": {"sec": 1}})", {"x"}), "accepted");
}

std::string cloud_refusal(const std::string& json, const std::vector<std::string>& fields, std::uint64_t max_points = limits::kMaxReturnsPerScan) {
  simdjson::ondemand::parser parser;
  try {
    decode_point_cloud(parser, json, fields, max_points);
  } catch (const std::exception& e) {
    return std::string(e.what());
  }
  return std::string("accepted");
}

const std::vector<std::string> kFive = {"x", "y", "z", "range_rate", "amplitude"};

// Issue 51, HIGH 5: a stride of 1 with five uint8 fields at offset 0 made every byte of the data a
// point of five values, each a heap vector (2.4 GB from 97 KB). The fields asked for may not
// overlap, so a point costs at least their bytes; the points are told from the base64 text's
// length and bounded by the scan's limit and what the log has left before anything is decoded.
TEST(FoxgloveMessages, OverlappingFieldsAndMorePointsThanTheLimitAreRefused) {
  const std::string stride_one = R"([{"name": "x", "offset": 0, "type": 1}, {"name": "y", "offset": 0, "type": 1},
    {"name": "z", "offset": 0, "type": 1}, {"name": "range_rate", "offset": 0, "type": 1}, {"name": "amplitude", "offset": 0, "type": 1}])";
  EXPECT_EQ(cloud_refusal(cloud_json(stride_one, two_points(), 1), kFive), "fields[x] (bytes 0 to 0) and fields[y] (bytes 0 to 0) overlap");
  // Overlapping by a byte: y's float32 from byte 3.
  const std::string by_a_byte = R"([{"name": "x", "offset": 0, "type": 7}, {"name": "y", "offset": 3, "type": 7},
    {"name": "z", "offset": 8, "type": 4}, {"name": "range_rate", "offset": 10, "type": 2}, {"name": "amplitude", "offset": 11, "type": 1}])";
  EXPECT_EQ(cloud_refusal(cloud_json(by_a_byte, two_points()), kFive), "fields[x] (bytes 0 to 3) and fields[y] (bytes 3 to 6) overlap");
  // A field named twice.
  const std::string twice = R"([{"name": "x", "offset": 0, "type": 7}, {"name": "x", "offset": 4, "type": 7}])";
  EXPECT_EQ(cloud_refusal(cloud_json(twice, two_points()), {"x"}), "fields[x]: named twice");
  // Two points where the log has one left; kMaxReturnsPerScan + 1 points of 12 bytes in one
  // cloud (4 MiB of base64 'A's), refused from the text's length.
  EXPECT_EQ(cloud_refusal(cloud_json(kFields, two_points()), kFive, 1), "data: 2 points exceed the 1 the log has left");
  EXPECT_EQ(cloud_refusal(cloud_json(kFields, two_points()), kFive, 2), "accepted");
  const std::string many(std::size_t{12} * (limits::kMaxReturnsPerScan + 1) / 3 * 4, 'A');
  EXPECT_EQ(cloud_refusal(cloud_json(kFields, many), kFive), "data: 262145 points in one cloud exceed the limit of 262144 (schemas/limits.md)");
}

// Issue 51, HIGH 6: a field at offset 2^63 - 4 overflowed `at + type_bytes(t) > stride` and the
// read landed outside the data (SIGSEGV). The offset is compared without a sum.
TEST(FoxgloveMessages, AFieldOffsetNearTwoToTheSixtyThreeIsRefusedWithoutOverflow) {
  for (const char* offset : {"9223372036854775804", "9223372036854775807", "9223372036854775800", "13"}) {
    const std::string fields = std::string(R"([{"name": "x", "offset": )") + offset + R"(, "type": 7}])";
    EXPECT_EQ(cloud_refusal(cloud_json(fields, two_points()), {"x"}),
              std::string("fields[x]: offset ") + offset + " and its 4 bytes run past the stride 12");
  }
  EXPECT_EQ(cloud_refusal(cloud_json(R"([{"name": "x", "offset": 8, "type": 7}])", two_points()), {"x"}), "accepted");
}

TEST(FoxgloveMessages, ASceneUpdatesBoxesAreEachEntitysFirstCube) {
  const std::string update = R"({"deletions": [], "entities": [
    {"timestamp": {"sec": 2, "nsec": 5}, "frame_id": "odom", "id": "car_1",
     "metadata": [{"key": "class", "value": "car"}, {"key": "speed_mps", "value": "12.5"}],
     "cubes": [{"pose": {"position": {"x": 30, "y": -1.5, "z": 0.7}, "orientation": {"x": 0, "y": 0, "z": 0.7071067811865476, "w": 0.7071067811865476}},
                "size": {"x": 4.6, "y": 1.9, "z": 1.5}},
               {"pose": {"position": {"x": 99, "y": 99, "z": 0}, "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}}, "size": {"x": 1, "y": 1, "z": 1}}]},
    {"timestamp": {"sec": 2, "nsec": 5}, "frame_id": "odom", "id": "label", "texts": []},
    {"timestamp": {"sec": 2, "nsec": 5}, "frame_id": "odom", "id": "van", "cubes": [{"pose": {"position": {"x": 1, "y": 2, "z": 0},
     "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}}, "size": {"x": 5, "y": 2, "z": 2}}]}]})";
  simdjson::ondemand::parser parser;
  std::vector<std::tuple<std::string, std::string, double, double, double, double, double, double>> boxes;
  for_each_scene_box(parser, update, [&](const SceneBox& b) {
    boxes.emplace_back(std::string(b.id), std::string(b.log_class), static_cast<double>(b.t_ns), b.x_m, b.yaw_rad, b.length_m,
                       b.width_m, b.speed_mps.value_or(-1.0));
  });
  ASSERT_EQ(boxes.size(), 2u);  // the entity without a cube is no box
  const auto& [id, log_class, t_ns, x_m, yaw_rad, length_m, width_m, speed_mps] = boxes[0];
  EXPECT_EQ(id, "car_1");
  EXPECT_EQ(log_class, "car");
  EXPECT_EQ(t_ns, 2'000'000'005.0);
  EXPECT_EQ(x_m, 30.0);
  EXPECT_NEAR(yaw_rad, M_PI / 2, 1e-12);  // a quarter turn about z
  EXPECT_EQ(length_m, 4.6);
  EXPECT_EQ(width_m, 1.9);
  EXPECT_EQ(speed_mps, 12.5);
  EXPECT_EQ(std::get<0>(boxes[1]), "van");
  EXPECT_EQ(std::get<7>(boxes[1]), -1.0);  // no speed given
}

}  // namespace
}  // namespace rcsim::replay::foxglove::foxglove_messages_test
