// The importers' one reader of a 4 x 4 rigid transform: accepted as written, refused naming the
// field otherwise.
#include "replay/import/rigid_transform.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "common/input_error.hpp"

namespace rcsim::replay {
namespace {

std::string refusal(const nlohmann::json& matrix) {
  const nlohmann::json doc = {{"T", matrix}};
  try {
    (void)read_rigid_transform(JsonField(doc, "calibration.json", ""), "T");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RigidTransform, ARotationAndTranslationIsReadAsWritten) {
  // A quarter turn about z and (1.5, -0.2, 0.7).
  const nlohmann::json doc = {{"T", {{0, -1, 0, 1.5}, {1, 0, 0, -0.2}, {0, 0, 1, 0.7}, {0, 0, 0, 1}}}};
  const Eigen::Matrix4d m = read_rigid_transform(JsonField(doc, "calibration.json", ""), "T");
  EXPECT_EQ(m(0, 1), -1.0);
  EXPECT_EQ(m(1, 0), 1.0);
  EXPECT_EQ(m(0, 3), 1.5);
  EXPECT_EQ(m(2, 3), 0.7);
}

TEST(RigidTransform, AnythingElseIsRefusedNamingTheField) {
  const std::string scaled = refusal({{2, 0, 0, 0}, {0, 2, 0, 0}, {0, 0, 2, 0}, {0, 0, 0, 1}});
  EXPECT_NE(scaled.find("calibration.json"), std::string::npos) << scaled;
  EXPECT_NE(scaled.find("no rigid transform"), std::string::npos) << scaled;
  // A mirror (determinant -1) is orthonormal but no rotation.
  EXPECT_NE(refusal({{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}).find("no rigid transform"), std::string::npos);
  EXPECT_NE(refusal({{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}).find("4 x 4"), std::string::npos);
  EXPECT_NE(refusal({{1, 0, 0, 0}, {0, 1, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}).find("row 1"), std::string::npos);
  EXPECT_NE(refusal({{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, "x"}, {0, 0, 0, 1}}).find("element (2, 3)"), std::string::npos);
}

}  // namespace
}  // namespace rcsim::replay
