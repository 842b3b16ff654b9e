#pragma once
// The column codecs of the report database's block tables (`rcsim-report` v4,
// schemas/report-database.md, "Blocks"): one BLOB holds one column of a block of cycles, as
//   u   unsigned LEB128 varints;
//   z   zigzag LEB128 varints (signed: 0, -1, 1, -2, ... as 0, 1, 2, 3, ...);
//   f4  little-endian IEEE 754 binary32, rounded to nearest;
//   x   exact binary64: the zigzag LEB128 varint of bits(value) - bits(prediction) modulo 2^64,
//       where bits() is the value's IEEE 754 binary64 pattern as a 64-bit integer. Any double,
//       NaN and infinities included, comes back bit for bit; a good prediction costs one byte.
// A zero-length BLOB of a u, z or x column stands for a column whose every varint is 0.
// The predictions use only +, -, *, / and sqrt, each rounded once (IEEE 754 correctly rounded),
// so that any reader on any platform computes them bit for bit as the writer did.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rcsim::replay::packed {

// The signed value of a zigzag varint.
inline std::int64_t unzigzag(std::uint64_t u) { return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1); }

class ColumnWriter {
 public:
  void put_unsigned(std::uint64_t value);
  void put_signed(std::int64_t value);
  void put_float32(double value);
  void put_exact(double value, double prediction);

  // The BLOB to store: empty when every varint is 0 (never for f4 values).
  const std::vector<std::uint8_t>& bytes() const { return all_zero_ ? kEmpty : bytes_; }
  void clear();

 private:
  static const std::vector<std::uint8_t> kEmpty;
  void put_varint(std::uint64_t value);
  std::vector<std::uint8_t> bytes_;
  bool all_zero_ = true;
};

// Reads a column back; throws std::runtime_error naming `column` where a BLOB ends early.
class ColumnReader {
 public:
  ColumnReader(const void* data, std::size_t size, std::string column);
  // Inline (every stored target's dozen values: a call each was a third of a report's pass).
  std::uint64_t get_unsigned() { return get_varint(); }
  std::int64_t get_signed() { return unzigzag(get_varint()); }
  double get_float32() {
    if (end_ - p_ < 4) damaged();
    std::uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(p_[i]) << (8 * i);
    p_ += 4;
    return static_cast<double>(std::bit_cast<float>(bits));
  }
  double get_exact(double prediction);
  bool at_end() const { return p_ == end_; }

 private:
  std::uint64_t get_varint() {
    if (all_zero_) return 0;
    std::uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (p_ == end_) damaged();
      const std::uint8_t byte = *p_++;
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    damaged();
  }
  [[noreturn]] void damaged() const;
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  bool all_zero_;
  std::string column_;
};

// The prediction of a smooth series from its last two values: 0 before any, the last one after
// one, then 2 last - the one before (2 last is exact, so a fused multiply-add gives the same).
class LinearPrediction {
 public:
  double predict() const;
  void push(double value);

 private:
  double last_ = 0.0, before_ = 0.0;
  int seen_ = 0;
};

// x * y rounded once, never fused with a following addition.
double rounded_product(double x, double y);

}  // namespace rcsim::replay::packed
