#include "replay/import/rigid_transform.hpp"

#include <cmath>
#include <fmt/format.h>
#include <vector>

namespace rcsim::replay {

Eigen::Matrix4d read_rigid_transform(const JsonField& field, std::string_view key) {
  const std::vector<JsonField> rows = field.array(key);
  if (rows.size() != 4) field.fail(key, "must be a 4 x 4 matrix");
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    const nlohmann::json& row = rows[static_cast<std::size_t>(r)].json();
    if (!row.is_array() || row.size() != 4) field.fail(key, fmt::format("row {} must hold 4 numbers", r));
    for (int c = 0; c < 4; ++c) {
      const auto& v = row[static_cast<std::size_t>(c)];
      if (!v.is_number() || !std::isfinite(v.get<double>())) {
        field.fail(key, fmt::format("element ({}, {}) is not a finite number", r, c));
      }
      m(r, c) = v.get<double>();
    }
  }
  if (const auto flaw = rigid_transform_flaw(m)) field.fail(key, *flaw);
  return m;
}

std::optional<std::string> rigid_transform_flaw(const Eigen::Matrix4d& m) {
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if (!m.allFinite() || (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
      R.determinant() < 0.0 || m.row(3) != Eigen::RowVector4d(0.0, 0.0, 0.0, 1.0)) {
    return std::string("is no rigid transform (rotation not orthonormal, or last row not 0 0 0 1)");
  }
  return std::nullopt;
}

}  // namespace rcsim::replay
