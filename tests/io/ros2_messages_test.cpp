// ROS 2 messages in CDR (src/io/ros2_messages.hpp), byte by byte as the XCDR1 rules lay them out:
// the encapsulation header, then every primitive aligned to its size counted from after it.
#include "io/ros2_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <algorithm>
#include <string>
#include <vector>

namespace rcsim::ros2::ros2_messages_test {
namespace {

// Little-endian bytes of a value.
template <typename T>
std::string le(T value) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}
template <typename T>
std::string be(T value) {
  std::string bytes = le(value);
  return std::string(bytes.rbegin(), bytes.rend());
}

// A RadarScan stamped 12 s + 500 ns in frame "fl" with one return, laid out by hand:
// header 4 | sec 4 | nanosec 4 | frame_id: count 3 ("fl\0") + 1 pad | returns: count 1 | 5 floats.
std::string scan_bytes(bool little) {
  const auto put = [little](auto v) { return little ? le(v) : be(v); };
  std::string b = little ? std::string("\x00\x01\x00\x00", 4) : std::string("\x00\x00\x00\x00", 4);
  b += put(std::int32_t{12}) + put(std::uint32_t{500});
  b += put(std::uint32_t{3}) + std::string("fl\0", 3) + std::string(1, '\0');  // pad to 4
  b += put(std::uint32_t{1});
  for (const float f : {25.5f, 0.25f, -0.03125f, -4.0f, 17.0f}) b += put(f);
  return b;
}

TEST(Ros2Messages, ARadarScanByHandInBothByteOrders) {
  for (const bool little : {true, false}) {
    const std::string bytes = scan_bytes(little);
    ASSERT_EQ(bytes.size(), 4u + 8u + 8u + 4u + 20u);
    const RadarScan scan = decode_radar_scan(bytes);
    EXPECT_EQ(scan.header.stamp.ns(), 12'000'000'500LL);
    EXPECT_EQ(scan.header.frame_id, "fl");
    ASSERT_EQ(scan.returns.size(), 1u);
    EXPECT_EQ(scan.returns[0].range, 25.5f);
    EXPECT_EQ(scan.returns[0].azimuth, 0.25f);
    EXPECT_EQ(scan.returns[0].elevation, -0.03125f);
    EXPECT_EQ(scan.returns[0].doppler_velocity, -4.0f);
    EXPECT_EQ(scan.returns[0].amplitude, 17.0f);
  }
}

TEST(Ros2Messages, DamagedScansAreRefusedNamingTheField) {
  const std::string bytes = scan_bytes(true);
  const auto refusal = [](const std::string& b) {
    try {
      decode_radar_scan(b);
    } catch (const CdrError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(bytes.substr(0, bytes.size() - 2)).find("returns: 1 element(s) of 20 bytes or more, but 18 bytes are left"),
            std::string::npos)
      << refusal(bytes.substr(0, bytes.size() - 2));
  std::string many = bytes;
  many.replace(20, 4, le(std::uint32_t{1'000'000}));  // the returns' count, beyond what is left
  EXPECT_NE(refusal(many).find("returns: 1000000 element(s)"), std::string::npos) << refusal(many);
  EXPECT_NE(refusal(std::string("\x00\x07\x00\x00", 4)).find("not plain CDR"), std::string::npos);
  EXPECT_NE(refusal(std::string("\x00\x01", 2)).find("encapsulation header"), std::string::npos);
  std::string late = bytes;
  late.replace(8, 4, le(std::uint32_t{1'000'000'000}));
  EXPECT_NE(refusal(late).find("nanosec"), std::string::npos);
}

// Issue 51, HIGH 4: scans of millions of zero returns, which zstd packs into a few bytes, were
// imported whole. A scan holds at most limits::kMaxReturnsPerScan returns, and no more than the
// caller has left (the log's bound): both told from the count, before a return is allocated.
TEST(Ros2Messages, AScanOfMoreReturnsThanTheLimitIsRefusedAtItsCount) {
  const auto refusal = [](const std::string& b, std::uint64_t max_returns) {
    try {
      decode_radar_scan(b, max_returns);
    } catch (const CdrError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // kMaxReturnsPerScan + 1 returns of zeros, every byte of them there.
  std::string zeros = scan_bytes(true).substr(0, 20) + le(std::uint32_t{limits::kMaxReturnsPerScan + 1});
  zeros.append(std::size_t{20} * (limits::kMaxReturnsPerScan + 1), '\0');
  EXPECT_EQ(refusal(zeros, limits::kMaxReturnsPerScan), "returns: 262145 in one scan exceed the limit of 262144 (schemas/limits.md)");
  EXPECT_EQ(refusal(zeros, 10), "returns: 262145 in one scan exceed the limit of 262144 (schemas/limits.md)");
  // One return where the caller has none left; one where it has one.
  EXPECT_EQ(refusal(scan_bytes(true), 0), "returns: 1 exceed the 0 the log has left");
  EXPECT_EQ(refusal(scan_bytes(true), 1), "accepted");
}

// Odometry: doubles aligned to 8 from after the header; the covariances skipped.
TEST(Ros2Messages, OdometryByHand) {
  std::string b("\x00\x01\x00\x00", 4);
  b += le(std::int32_t{3}) + le(std::uint32_t{0});
  b += le(std::uint32_t{5}) + std::string("odom\0", 5);  // to byte 21
  b += std::string(3, '\0');                             // to 24 (4-aligned counted from 4)
  b += le(std::uint32_t{10}) + std::string("base_link\0", 10);  // to 38
  b += std::string(6, '\0');                                    // to 44 (8-aligned counted from 4)
  const double yaw = 0.5;
  for (const double v : {10.0, -2.0, 0.0, 0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)}) b += le(v);
  for (int i = 0; i < 36; ++i) b += le(0.0);
  for (const double v : {29.5, 0.1, 0.0, 0.0, 0.0, 0.02}) b += le(v);
  for (int i = 0; i < 36; ++i) b += le(0.0);
  Odometry o;
  try {
    o = decode_odometry(b);
  } catch (const CdrError& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(o.header.frame_id, "odom");
  EXPECT_EQ(o.child_frame_id, "base_link");
  EXPECT_EQ(o.x_m, 10.0);
  EXPECT_EQ(o.y_m, -2.0);
  EXPECT_NEAR(yaw_of_quaternion(o.qx, o.qy, o.qz, o.qw), yaw, 1e-15);
  EXPECT_EQ(o.vx_mps, 29.5);
  EXPECT_EQ(o.wz_radps, 0.02);
  EXPECT_THROW(decode_odometry(b.substr(0, b.size() - 8)), CdrError);
  // A zero quaternion is no rotation: refused as /tf refuses it (issue 51, LOW).
  std::string zero = b;
  std::memset(zero.data() + 44 + 5 * 8, 0, 16);
  try {
    decode_odometry(zero);
    ADD_FAILURE() << "a zero quaternion was read";
  } catch (const CdrError& e) {
    EXPECT_STREQ(e.what(), "pose.pose.orientation: a zero quaternion is no rotation");
  }
}

// A PointCloud2 laid out by hand, big-endian: 2 rows of 2 points, 12-byte points (x INT16 at 0, a
// UINT8 "flags" at 2, speed FLOAT32 at 4, power UINT16 at 8, 2 bytes of padding), rows 28 bytes
// apart (4 of padding); read for x, speed and power in that order (issue 50).
std::string cloud_bytes(std::uint32_t data_bytes, std::uint8_t x_type = 3) {
  std::string b("\x00\x00\x00\x00", 4);  // big-endian CDR
  b += be(std::int32_t{7}) + be(std::uint32_t{0});
  b += be(std::uint32_t{2}) + std::string("r\0", 2) + std::string(2, '\0');  // frame "r", to byte 20
  b += be(std::uint32_t{2}) + be(std::uint32_t{2});                            // height, width
  b += be(std::uint32_t{4});                                                   // 4 fields
  const auto field = [&](const std::string& name, std::uint32_t offset, std::uint8_t type) {
    b += be(static_cast<std::uint32_t>(name.size() + 1)) + name + '\0';
    while ((b.size() - 4) % 4 != 0) b += '\0';
    b += be(offset) + std::string(1, static_cast<char>(type)) + std::string(3, '\0') + be(std::uint32_t{1});
  };
  field("x", 0, x_type), field("flags", 2, 2), field("speed", 4, 7), field("power", 8, 4);
  b += std::string(1, '\1');  // is_bigendian
  b += std::string(3, '\0') + be(std::uint32_t{12}) + be(std::uint32_t{28});  // point_step, row_step
  b += be(data_bytes);
  std::string data;
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) {
      const int k = 2 * row + col;
      data += be(static_cast<std::int16_t>(-100 * (k + 1))) + std::string(1, '\x55') + std::string(1, '\0');
      data += be(0.5f * static_cast<float>(k)) + be(static_cast<std::uint16_t>(60000 + k)) + std::string(2, '\0');
    }
    data += std::string(4, '\0');  // the row's padding
  }
  b += data.substr(0, std::min<std::size_t>(data.size(), data_bytes));
  b += std::string(1, '\1');  // is_dense
  return b;
}

TEST(Ros2Messages, PointCloud2ByHandBigEndianPaddedRows) {
  CloudPoints c;
  try {
    c = decode_point_cloud2(cloud_bytes(56), {"x", "speed", "power"});
  } catch (const CdrError& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(c.header.frame_id, "r");
  EXPECT_EQ(c.field_names, (std::vector<std::string>{"x", "flags", "speed", "power"}));
  ASSERT_EQ(c.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(c.values[3 * k], -100.0 * static_cast<double>(k + 1)) << k;
    EXPECT_EQ(c.values[3 * k + 1], 0.5 * static_cast<double>(k)) << k;
    EXPECT_EQ(c.values[3 * k + 2], 60000.0 + static_cast<double>(k)) << k;
  }
  const auto refusal = [](const std::string& bytes, const std::vector<std::string>& fields) {
    try {
      decode_point_cloud2(bytes, fields);
    } catch (const CdrError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(cloud_bytes(56), {"x", "velocity"}), "fields: no field 'velocity' (the cloud's fields: x, flags, speed, power)");
  EXPECT_EQ(refusal(cloud_bytes(55), {"x"}), "data: 2 x 2 points of 12 bytes in rows of 28 bytes need more than its 55 bytes");
  // x as FLOAT64 (8 bytes at 0) runs over flags and speed: an overlap with speed, asked for.
  EXPECT_EQ(refusal(cloud_bytes(56, 8), {"x", "speed"}), "fields['speed'] and fields['x'] overlap");
  EXPECT_EQ(refusal(cloud_bytes(56, 9), {"x"}), "fields['x'].datatype: 9 is no PointField datatype (1 to 8)");
}

// A TFMessage of two transforms: each one's doubles aligned to 8 from after the header, the
// second transform's header starting 4-aligned right after the first's last double.
TEST(Ros2Messages, TransformsByHand) {
  std::string b("\x00\x01\x00\x00", 4);
  b += le(std::uint32_t{2});                                  // to 8
  b += le(std::int32_t{7}) + le(std::uint32_t{250});          // to 16
  b += le(std::uint32_t{5}) + std::string("odom\0", 5);       // to 25
  b += std::string(3, '\0');                                  // to 28
  b += le(std::uint32_t{10}) + std::string("base_link\0", 10);  // to 42
  b += std::string(2, '\0');                                  // to 44 (8-aligned counted from 4)
  for (const double v : {1.5, -2.5, 0.25, 0.0, 0.0, std::sin(0.15), std::cos(0.15)}) b += le(v);  // to 100
  b += le(std::int32_t{7}) + le(std::uint32_t{0});            // to 108
  b += le(std::uint32_t{10}) + std::string("base_link\0", 10);  // to 122
  b += std::string(2, '\0');                                  // to 124
  b += le(std::uint32_t{3}) + std::string("fl\0", 3);         // to 131
  b += std::string(1, '\0');                                  // to 132 (8-aligned counted from 4)
  for (const double v : {3.8, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0}) b += le(v);
  std::vector<TransformStamped> tf;
  try {
    tf = decode_tf_message(b);
  } catch (const CdrError& e) {
    FAIL() << e.what();
  }
  ASSERT_EQ(tf.size(), 2u);
  EXPECT_EQ(tf[0].header.stamp.ns(), 7'000'000'250LL);
  EXPECT_EQ(tf[0].header.frame_id, "odom");
  EXPECT_EQ(tf[0].child_frame_id, "base_link");
  EXPECT_EQ(tf[0].x_m, 1.5);
  EXPECT_EQ(tf[0].y_m, -2.5);
  EXPECT_EQ(tf[0].z_m, 0.25);
  EXPECT_NEAR(yaw_of_quaternion(tf[0].qx, tf[0].qy, tf[0].qz, tf[0].qw), 0.3, 1e-15);
  EXPECT_EQ(tf[1].header.frame_id, "base_link");
  EXPECT_EQ(tf[1].child_frame_id, "fl");
  EXPECT_EQ(tf[1].x_m, 3.8);
  EXPECT_EQ(tf[1].qw, 1.0);
  EXPECT_THROW(decode_tf_message(b.substr(0, b.size() - 1)), CdrError);
  std::string many = b;
  many.replace(4, 4, le(std::uint32_t{3}));  // a third transform that is not there
  EXPECT_THROW(decode_tf_message(many), CdrError);
}

}  // namespace
}  // namespace rcsim::ros2::ros2_messages_test
