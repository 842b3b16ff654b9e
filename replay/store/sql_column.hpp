#pragma once
// Reading a column of the report database into a plain value.
#include <SQLiteCpp/SQLiteCpp.h>

#include <optional>

namespace rcsim::replay {

// A REAL column that may be NULL.
inline std::optional<double> optional_double(const SQLite::Column& column) {
  if (column.isNull()) return std::nullopt;
  return column.getDouble();
}

}  // namespace rcsim::replay
