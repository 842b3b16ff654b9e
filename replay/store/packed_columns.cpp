#include "replay/store/packed_columns.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace rcsim::replay::packed {

namespace {

std::uint64_t zigzag(std::int64_t v) { return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63); }

}  // namespace

const std::vector<std::uint8_t> ColumnWriter::kEmpty;

void ColumnWriter::put_varint(std::uint64_t value) {
  if (value != 0) all_zero_ = false;
  while (value >= 0x80) {
    bytes_.push_back(static_cast<std::uint8_t>(value | 0x80));
    value >>= 7;
  }
  bytes_.push_back(static_cast<std::uint8_t>(value));
}

void ColumnWriter::put_unsigned(std::uint64_t value) { put_varint(value); }

void ColumnWriter::put_signed(std::int64_t value) { put_varint(zigzag(value)); }

void ColumnWriter::put_float32(double value) {
  all_zero_ = false;  // an f4 column is stored as it is
  const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(value));
  for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
}

void ColumnWriter::put_exact(double value, double prediction) {
  // Modulo 2^64, so that any two patterns have a difference and it undoes exactly.
  const std::uint64_t difference = std::bit_cast<std::uint64_t>(value) - std::bit_cast<std::uint64_t>(prediction);
  put_varint(zigzag(static_cast<std::int64_t>(difference)));
}

void ColumnWriter::clear() {
  bytes_.clear();
  all_zero_ = true;
}

ColumnReader::ColumnReader(const void* data, std::size_t size, std::string column)
    : p_(static_cast<const std::uint8_t*>(data)), end_(p_ + size), all_zero_(size == 0), column_(std::move(column)) {
  if (size == 0) p_ = end_ = nullptr;
}

void ColumnReader::damaged() const {
  throw std::runtime_error("report database: the column " + column_ + " of a block ends early (damaged)");
}

double ColumnReader::get_exact(double prediction) {
  const auto difference = static_cast<std::uint64_t>(unzigzag(get_varint()));
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(prediction) + difference);
}

double LinearPrediction::predict() const {
  if (seen_ == 0) return 0.0;
  if (seen_ == 1) return last_;
  return 2.0 * last_ - before_;
}

void LinearPrediction::push(double value) {
  before_ = last_;
  last_ = value;
  if (seen_ < 2) ++seen_;
}

double rounded_product(double x, double y) {
  volatile double product = x * y;  // stored, hence rounded: no contraction into a later addition
  return product;
}

}  // namespace rcsim::replay::packed
