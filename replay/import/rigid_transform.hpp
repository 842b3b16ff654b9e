#pragma once
// A dataset's 4 x 4 homogeneous transform (a sensor's mounting in the aiMotive and Astyx
// calibration files), read and checked: the one reader of both importers.
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <string_view>

#include "common/json_reader.hpp"

namespace rcsim::replay {

// field[key]: 4 rows of 4 finite numbers forming a rigid transform (orthonormal rotation with
// determinant +1 within 1e-3, last row 0 0 0 1); an InputError naming the field otherwise.
Eigen::Matrix4d read_rigid_transform(const JsonField& field, std::string_view key);

// What keeps m from being a rigid transform (those bounds), or nothing where it is one: for the
// importers that read a matrix from a text file of their own (a KITTI calibration).
std::optional<std::string> rigid_transform_flaw(const Eigen::Matrix4d& m);

}  // namespace rcsim::replay
