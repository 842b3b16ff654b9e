// The column codecs of the block tables (replay/store/packed_columns.hpp), by hand: varints of
// known bytes, exact doubles bit for bit whatever the prediction, float32 rounding, the empty
// BLOB of an all-zero column, a damaged BLOB named, the linear prediction.
#include "replay/store/packed_columns.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

namespace rcsim::replay::packed {
namespace {

ColumnReader read_back(const ColumnWriter& w) { return {w.bytes().data(), w.bytes().size(), "test_column"}; }

TEST(PackedColumns, VarintsHaveTheirKnownBytes) {
  ColumnWriter w;
  w.put_unsigned(1);
  w.put_unsigned(300);     // 0b10'0101100: 0xac 0x02
  w.put_signed(-1);        // zigzag 1
  w.put_signed(-64);       // zigzag 127: one byte
  w.put_signed(64);        // zigzag 128: two bytes
  EXPECT_EQ(w.bytes(), (std::vector<std::uint8_t>{0x01, 0xac, 0x02, 0x01, 0x7f, 0x80, 0x01}));
  ColumnReader r = read_back(w);
  EXPECT_EQ(r.get_unsigned(), 1u);
  EXPECT_EQ(r.get_unsigned(), 300u);
  EXPECT_EQ(r.get_signed(), -1);
  EXPECT_EQ(r.get_signed(), -64);
  EXPECT_EQ(r.get_signed(), 64);
  EXPECT_TRUE(r.at_end());
}

TEST(PackedColumns, ExtremeIntegersRoundTrip) {
  const std::int64_t values[] = {0, 1, -1, std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min()};
  ColumnWriter w;
  for (const auto v : values) w.put_signed(v);
  w.put_unsigned(std::numeric_limits<std::uint64_t>::max());
  ColumnReader r = read_back(w);
  for (const auto v : values) EXPECT_EQ(r.get_signed(), v);
  EXPECT_EQ(r.get_unsigned(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_TRUE(r.at_end());
}

// Any double against any prediction, NaN payloads, signed zeros, infinities and subnormals
// included, comes back with the same bits.
TEST(PackedColumns, ExactDoublesComeBackBitForBit) {
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(), std::bit_cast<double>(0x7ff8dead0000beefULL),
                                0.1 + 0.2, 3600.0 - 0.04};
  std::mt19937_64 rng(19);
  for (int i = 0; i < 2000; ++i) values.push_back(std::bit_cast<double>(rng()));
  ColumnWriter w;
  for (std::size_t i = 0; i < values.size(); ++i) w.put_exact(values[i], values[(i * 7 + 3) % values.size()]);
  ColumnReader r = read_back(w);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double back = r.get_exact(values[(i * 7 + 3) % values.size()]);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(values[i])) << i;
  }
  EXPECT_TRUE(r.at_end());
}

// A right prediction costs one byte; a prediction one ulp off one byte too; a column of right
// predictions is an empty BLOB, and an empty BLOB reads as every varint 0.
TEST(PackedColumns, GoodPredictionsCostOneByteAndAllRightNothing) {
  ColumnWriter w;
  w.put_exact(0.3, 0.3);
  w.put_exact(0.1 + 0.2, 0.3);  // 0.30000000000000004: one ulp above
  EXPECT_EQ(w.bytes().size(), 2u);
  ColumnWriter right;
  for (int i = 0; i < 100; ++i) right.put_exact(i * 0.5, i * 0.5);
  for (int i = 0; i < 100; ++i) right.put_unsigned(0);
  EXPECT_TRUE(right.bytes().empty());
  ColumnReader r = read_back(right);
  EXPECT_EQ(r.get_exact(2.5), 2.5);
  EXPECT_EQ(r.get_unsigned(), 0u);
  EXPECT_EQ(r.get_signed(), 0);
}

TEST(PackedColumns, Float32RoundsToNearestAndKeepsWhatItHolds) {
  ColumnWriter w;
  w.put_float32(5.6222);  // a recorded range: the nearest float is 5.6222000122...
  w.put_float32(0.5);
  w.put_float32(std::numeric_limits<double>::quiet_NaN());
  w.put_float32(0.0);
  EXPECT_EQ(w.bytes().size(), 16u);  // never elided, even a zero
  ColumnReader r = read_back(w);
  EXPECT_EQ(r.get_float32(), static_cast<double>(5.6222f));
  EXPECT_EQ(r.get_float32(), 0.5);
  EXPECT_TRUE(std::isnan(r.get_float32()));
  EXPECT_EQ(r.get_float32(), 0.0);
  EXPECT_TRUE(r.at_end());
}

TEST(PackedColumns, ADamagedBlobIsNamed) {
  const std::uint8_t truncated[] = {0x80, 0x80};  // a varint that never ends
  ColumnReader r(truncated, sizeof truncated, "gospa_m");
  try {
    r.get_unsigned();
    FAIL() << "a truncated varint was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gospa_m"), std::string::npos) << e.what();
  }
  const std::uint8_t three[] = {1, 2, 3};
  ColumnReader f(three, sizeof three, "range_m");
  EXPECT_THROW(f.get_float32(), std::runtime_error);
}

TEST(PackedColumns, LinearPredictionByHand) {
  LinearPrediction p;
  EXPECT_EQ(p.predict(), 0.0);
  p.push(1.0);
  EXPECT_EQ(p.predict(), 1.0);
  p.push(1.5);
  EXPECT_EQ(p.predict(), 2.0);  // 2 * 1.5 - 1
  p.push(1.75);
  EXPECT_EQ(p.predict(), 2.0);  // 2 * 1.75 - 1.5
}

}  // namespace
}  // namespace rcsim::replay::packed
