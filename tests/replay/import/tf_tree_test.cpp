// The tree of /tf and /tf_static transforms (replay/import/tf_tree.hpp): chains composed through
// static and moving frames, interpolation between stamps, and the refusals, by hand.
#include "replay/import/tf_tree.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::replay::tf_tree_test {
namespace {

using ::testing::HasSubstr;

constexpr std::int64_t kSecond_ns = 1'000'000'000;

ros2::TransformStamped transform(const std::string& parent, const std::string& child, std::int64_t t_ns, double x_m, double y_m,
                                 double z_m, double yaw_rad) {
  ros2::TransformStamped tf;
  tf.header.frame_id = parent, tf.child_frame_id = child;
  tf.header.stamp.sec = static_cast<std::int32_t>(t_ns / kSecond_ns);
  tf.header.stamp.nanosec = static_cast<std::uint32_t>(t_ns % kSecond_ns);
  tf.x_m = x_m, tf.y_m = y_m, tf.z_m = z_m;
  tf.qz = std::sin(yaw_rad / 2), tf.qw = std::cos(yaw_rad / 2);
  return tf;
}

double yaw_of(const Eigen::Isometry3d& X) { return std::atan2(X.linear()(1, 0), X.linear()(0, 0)); }

// odom -> base_footprint moving (at 0 s and 1 s), base_footprint -> base_link and base_link -> fl
// static: the vehicle 0.3 m above its footprint, the radar 3.8 m ahead, 0.5 m left, turned 0.1 rad.
TfTree vehicle() {
  TfTree tree;
  tree.add({transform("base_footprint", "base_link", 0, 0.0, 0.0, 0.3, 0.0), transform("base_link", "fl", 0, 3.8, 0.5, 0.0, 0.1)},
           true);
  tree.add({transform("odom", "base_footprint", kSecond_ns, 10.0, 0.0, 0.0, 0.2)}, false);  // out of order: finish() sorts
  tree.add({transform("odom", "base_footprint", 0, 0.0, 0.0, 0.0, 0.0)}, false);
  tree.add({transform("odom", "base_footprint", 0, 5.0, 5.0, 0.0, 0.0)}, false);  // a repeated stamp: ignored, as tf2 does
  tree.finish();
  return tree;
}

TEST(TfTree, AChainThroughStaticAndMovingFramesByHand) {
  const TfTree tree = vehicle();
  const Eigen::Isometry3d X_OV = tree.pose("base_link", "odom", kSecond_ns / 2);  // halfway: 5 m on, yaw 0.1 (slerp)
  EXPECT_NEAR(X_OV.translation().x(), 5.0, 1e-12);
  EXPECT_NEAR(X_OV.translation().y(), 0.0, 1e-12);
  EXPECT_NEAR(X_OV.translation().z(), 0.3, 1e-12);
  EXPECT_NEAR(yaw_of(X_OV), 0.1, 1e-12);
  const Eigen::Isometry3d X_VS = tree.pose("fl", "base_link", 0);
  EXPECT_NEAR(X_VS.translation().x(), 3.8, 1e-12);
  EXPECT_NEAR(X_VS.translation().y(), 0.5, 1e-12);
  EXPECT_NEAR(yaw_of(X_VS), 0.1, 1e-12);
  // The radar in odom at 1 s: the footprint at (10, 0) turned 0.2, the radar's offset turned with it.
  const Eigen::Isometry3d X_OS = tree.pose("fl", "odom", kSecond_ns);
  EXPECT_NEAR(X_OS.translation().x(), 10.0 + 3.8 * std::cos(0.2) - 0.5 * std::sin(0.2), 1e-12);
  EXPECT_NEAR(X_OS.translation().y(), 3.8 * std::sin(0.2) + 0.5 * std::cos(0.2), 1e-12);
  EXPECT_NEAR(yaw_of(X_OS), 0.3, 1e-12);
  // And the other way round: odom in the radar's frame is its inverse.
  EXPECT_TRUE(tree.pose("odom", "fl", kSecond_ns).isApprox(X_OS.inverse(), 1e-12));
  // Held within 0.1 s beyond the last stamp, refused beyond.
  EXPECT_NEAR(tree.pose("base_link", "odom", kSecond_ns + kSecond_ns / 20).translation().x(), 10.0, 1e-12);
  try {
    tree.pose("base_link", "odom", 2 * kSecond_ns);
    FAIL() << "2 s accepted";
  } catch (const TfError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the transform of 'base_footprint' in 'odom' is known from 0 to 1000000000 ns, not at 2000000000 ns"));
  }
}

TEST(TfTree, TheEgoStampsAreTheDensestMovingTransformsWhereAllAreKnown) {
  TfTree tree;
  for (int k = 0; k <= 3; ++k) tree.add({transform("map", "odom", k * kSecond_ns, 0.0, 0.0, 0.0, 0.0)}, false);  // 1 Hz, 0-3 s
  for (int k = 0; k <= 50; ++k) {
    tree.add({transform("odom", "base_link", k * kSecond_ns / 10, 0.1 * k, 0.0, 0.0, 0.0)}, false);  // 10 Hz, 0-5 s
  }
  tree.finish();
  const std::vector<std::int64_t> stamps = tree.chain_stamps("base_link", "map");
  ASSERT_EQ(stamps.size(), 32u);  // 0 to 3.1 s: the map's last stamp plus the 0.1 s it is held
  EXPECT_EQ(stamps.front(), 0);
  EXPECT_EQ(stamps.back(), 31 * kSecond_ns / 10);
  EXPECT_EQ(tree.chain_stamps("odom", "map").size(), 4u);
}

TEST(TfTree, RefusalsNameTheFrames) {
  TfTree tree = vehicle();
  const auto refusal = [&](const auto& call) {
    try {
      call();
    } catch (const TfError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(refusal([&] { tree.add({transform("map", "base_link", 0, 0, 0, 0, 0)}, true); }),
              HasSubstr("frame 'base_link' has two parents: 'base_footprint' (static) and 'map' (static)"));
  EXPECT_THAT(refusal([&] { tree.add({transform("odom", "base_footprint", 0, 0, 0, 0, 0)}, true); }),
              HasSubstr("the transform of 'base_footprint' in 'odom' comes both on the static topic and the moving one"));
  EXPECT_THAT(refusal([&] { tree.pose("radar", "odom", 0); }), HasSubstr("no transform names frame 'radar' (the frames: base_footprint, base_link, fl, odom)"));
  tree.add({transform("world", "gps", 0, 0, 0, 0, 0)}, true);
  EXPECT_THAT(refusal([&] { tree.pose("gps", "fl", 0); }),
              HasSubstr("no chain of transforms joins 'gps' and 'fl' (one ends at 'world', the other at 'odom')"));
  ros2::TransformStamped zero = transform("odom", "x", 0, 0, 0, 0, 0);
  zero.qw = 0.0;
  EXPECT_THAT(refusal([&] { tree.add({zero}, false); }), HasSubstr("no unit quaternion"));
  // Issue 51 (MEDIUM): a chain of 10,000 frames made every lookup walk it, quadratically (163 s for
  // a 1 MB log); a chain deeper than kMaxChainDepth is refused at once.
  const auto f = [](int i) { return std::string("f").append(std::to_string(i)); };  // (GCC 12 warns on "f" + std::string)
  TfTree deep;
  for (int i = 0; i < 10'000; ++i) deep.add({transform(f(i), f(i + 1), 0, 0, 0, 0, 0)}, true);
  EXPECT_THAT(refusal([&] { deep.pose("f10000", "f0", 0); }), HasSubstr("the chain from 'f10000' up to its root holds more than 64 transforms"));
  TfTree shallow;
  for (int i = 0; i < 64; ++i) shallow.add({transform(f(i), f(i + 1), 0, 1, 0, 0, 0)}, true);
  EXPECT_NEAR(shallow.pose("f64", "f0", 0).translation().x(), 64.0, 1e-9);
}

}  // namespace
}  // namespace rcsim::replay::tf_tree_test
