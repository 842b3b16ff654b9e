#pragma once
// Reading a column of the report database into a plain value.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>

namespace rcsim::replay {

// A REAL column that may be NULL.
inline std::optional<double> optional_double(const SQLite::Column& column) {
  if (column.isNull()) return std::nullopt;
  return column.getDouble();
}

// An INTEGER column that may be NULL (a figure not known in runs stored before its column).
inline std::optional<std::int64_t> optional_int64(const SQLite::Column& column) {
  if (column.isNull()) return std::nullopt;
  return column.getInt64();
}

}  // namespace rcsim::replay
