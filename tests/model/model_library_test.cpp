// The object model database (model/model_library.hpp): one `rcsim-object-model` document read by
// hand, its refusals naming the field, model files, and the library's built-ins and look-up.
#include "model/model_library.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "scratch_dir.hpp"

namespace rcsim::model_library_test {

namespace fs = std::filesystem;

// One point reflector and one plane reflector, 2 m x 1 m.
const std::string kSmall = R"({"format": "rcsim-object-model", "version": 1, "name": "small",
  "length_m": 2, "width_m": 1,
  "point_reflectors": [{"name": "tip", "x_m": 1, "y_m": 0.5, "ercs": 2,
                        "visibility": {"center_deg": 90, "full_halfwidth_deg": 30, "falloff_deg": 15}}],
  "plane_reflectors": [{"name": "face", "from_x_m": 1, "from_y_m": -0.5, "to_x_m": 1, "to_y_m": 0.5,
                        "sagitta_m": 0.1, "ercs": 0.5}]})";

ObjectModel parsed(const nlohmann::json& doc) { return parse_object_model(JsonField(doc, "m.json", "")); }

std::string refusal_of(const nlohmann::json& doc) {
  try {
    parsed(doc);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ObjectModelDocument, ReflectorsAreReadInRadiansAndFromTheirChordByHand) {
  const ObjectModel m = parsed(nlohmann::json::parse(kSmall));
  EXPECT_EQ(m.name, "small");
  EXPECT_EQ(m.description, "");
  EXPECT_DOUBLE_EQ(m.length_m, 2.0);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].p_OR_O, Vec2(1.0, 0.5));
  EXPECT_DOUBLE_EQ(m.points[0].ercs_max, 2.0);
  // Degrees in the file, radians in the model: 90, 30, 15 deg.
  EXPECT_NEAR(m.points[0].visibility.center_rad(), kPi / 2.0, 1e-15);
  EXPECT_NEAR(m.points[0].visibility.full_halfwidth_rad(), kPi / 6.0, 1e-15);
  EXPECT_NEAR(m.points[0].visibility.falloff_rad(), kPi / 12.0, 1e-15);
  // Chord (1, -0.5) .. (1, 0.5), sagitta 0.1, bulging away from the origin: radius
  // (0.5^2 + 0.1^2) / (2 x 0.1) = 1.3 m, centre at the apex x = 1.1 minus 1.3: (-0.2, 0); the arc
  // spans 2 asin(0.5 / 1.3) about +x.
  ASSERT_EQ(m.planes.size(), 1u);
  EXPECT_NEAR(m.planes[0].radius_m, 1.3, 1e-12);
  EXPECT_NEAR((m.planes[0].center_O - Vec2(-0.2, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(m.planes[0].span_rad, 2.0 * std::asin(0.5 / 1.3), 1e-12);
  EXPECT_DOUBLE_EQ(m.planes[0].ercs, 0.5);
  EXPECT_FALSE(m.polyline.has_value());
}

// Version 2: heights, the body's diffuse factor, the free height under it, a limb's swing; a
// version 1 file that names them is refused, and one without them reads as before (on the road).
TEST(ObjectModelDocument, VersionTwoGivesHeightsAndSwingsAndVersionOneStaysOnTheRoad) {
  nlohmann::json doc = nlohmann::json::parse(kSmall);
  EXPECT_DOUBLE_EQ(parsed(doc).points[0].z_m, 0.0);
  EXPECT_FALSE(parsed(doc).points[0].swing.active());
  doc["version"] = 2;
  doc["height_m"] = 1.8;
  doc["clearance_m"] = 0.5;
  doc["diffuse_ercs_factor"] = 0.25;
  doc["point_reflectors"][0]["z_m"] = 1.2;
  doc["point_reflectors"][0]["swing"] = {{"relative_amplitude", 0.6}, {"period_s", 1.1}, {"phase_deg", 90}};
  doc["plane_reflectors"][0]["z_m"] = 0.7;
  const ObjectModel m = parsed(doc);
  EXPECT_DOUBLE_EQ(m.height_m, 1.8);
  EXPECT_DOUBLE_EQ(m.clearance_m, 0.5);
  EXPECT_DOUBLE_EQ(m.diffuse_ercs_factor, 0.25);
  EXPECT_DOUBLE_EQ(m.points[0].z_m, 1.2);
  EXPECT_DOUBLE_EQ(m.planes[0].z_m, 0.7);
  // k |v| cos(2 pi t / T + phase): at t = 0 and 90 deg, 0; a quarter period later, -k v.
  EXPECT_NEAR(m.points[0].swing.speed_offset_mps(2.0, 0.0), 0.0, 1e-15);
  EXPECT_NEAR(m.points[0].swing.speed_offset_mps(2.0, 1.1 / 4.0), -0.6 * 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.points[0].swing.speed_offset_mps(0.0, 0.3), 0.0);  // standing: no swing
  // Heights survive scaling to an annotated box (a recording gives length and width only).
  EXPECT_DOUBLE_EQ(scale_model(m, 4.0, 2.0).planes[0].z_m, 0.7);
  nlohmann::json both = doc;
  both["point_reflectors"][0]["swing"]["rolling_radius_m"] = 0.3;
  EXPECT_NE(refusal_of(both).find("one of period_s"), std::string::npos) << refusal_of(both);
  nlohmann::json above = doc;
  above["clearance_m"] = 2.0;
  EXPECT_NE(refusal_of(above).find("clearance_m"), std::string::npos) << refusal_of(above);
  nlohmann::json v1 = doc;
  v1["version"] = 1;
  EXPECT_NE(refusal_of(v1).find("unknown field"), std::string::npos) << refusal_of(v1);
}

TEST(ObjectModelDocument, BadReflectorsAreRefusedNamingTheField) {
  const nlohmann::json small = nlohmann::json::parse(kSmall);
  nlohmann::json doc = small;
  doc["point_reflectors"][0]["name"] = "face";
  EXPECT_EQ(refusal_of(doc), "m.json: plane_reflectors: duplicate reflector name \"face\"");
  doc = small;
  doc["plane_reflectors"][0]["to_y_m"] = -0.5;
  EXPECT_EQ(refusal_of(doc), "m.json: plane_reflectors[0].to_x_m: chord has zero length (from and to coincide)");
  doc = small;
  doc["plane_reflectors"][0]["sagitta_m"] = 0.6;  // the chord is 1 m
  EXPECT_EQ(refusal_of(doc), "m.json: plane_reflectors[0].sagitta_m: must be at most half the chord length");
  doc = small;
  doc["point_reflectors"][0]["visibility"]["full_halfwidth_deg"] = 200;
  EXPECT_EQ(refusal_of(doc), "m.json: point_reflectors[0].visibility.full_halfwidth_deg: must be at most 180");
  doc = small;
  doc["point_reflectors"][0]["ercs_db"] = 3;
  EXPECT_EQ(refusal_of(doc),
            "m.json: point_reflectors[0].ercs_db: unknown field (expected one of: name, x_m, y_m, ercs, visibility)");
  doc = small;
  doc.erase("point_reflectors");
  doc.erase("plane_reflectors");
  EXPECT_EQ(refusal_of(doc), "m.json: (top level): a model needs at least one reflector");
  doc = small;
  doc["polyline"] = {{"spacing_m", 4.0}, {"face_ercs_per_m", 0.1}};
  EXPECT_EQ(refusal_of(doc),
            "m.json: polyline: a polyline model has no point or plane reflectors of its own (its polyline makes them)");
  doc = small;
  doc["format"] = "rcsim-scene";
  EXPECT_EQ(refusal_of(doc), "m.json: format: expected \"rcsim-object-model\", got \"rcsim-scene\"");
}

TEST(ObjectModelDocument, APolylineTemplateNeedsASpacingAndSomethingToReflect) {
  nlohmann::json rail = {{"format", "rcsim-object-model"}, {"version", 1}, {"name", "rail"}, {"length_m", 0.3},
                         {"width_m", 0.3}, {"polyline", {{"spacing_m", 2.0}, {"face_ercs_per_m", 0.1}}}};
  const ObjectModel faces_only = parsed(rail);
  ASSERT_TRUE(faces_only.polyline.has_value());
  EXPECT_DOUBLE_EQ(faces_only.polyline->spacing_m, 2.0);
  EXPECT_DOUBLE_EQ(faces_only.polyline->post_ercs, 0.0);  // no posts, so no post_visibility needed
  EXPECT_TRUE(faces_only.points.empty());
  nlohmann::json bad = rail;
  bad["polyline"]["spacing_m"] = 0.05;
  EXPECT_EQ(refusal_of(bad), "m.json: polyline.spacing_m: must be in [0.1, 1000] m");
  bad = rail;
  bad["polyline"]["face_ercs_per_m"] = 0.0;
  EXPECT_EQ(refusal_of(bad), "m.json: polyline: needs post_ercs or face_ercs_per_m above 0");
  bad = rail;
  bad["polyline"]["post_ercs"] = 0.5;  // posts need their visibility
  EXPECT_EQ(refusal_of(bad), "m.json: polyline.post_visibility: missing required field");
}

TEST(ModelLibraryLookup, BuiltinsModelFilesAndUnknownNames) {
  const ModelLibrary builtin = ModelLibrary::builtin();
  EXPECT_EQ(builtin.models().size(), 9u);
  // guard_rail.json: posts every 4 m of ERCS 0.5 visible 60 deg either side, faces 0.05 per m.
  const ObjectModel& rail = builtin.at("guard_rail");
  ASSERT_TRUE(rail.polyline.has_value());
  EXPECT_DOUBLE_EQ(rail.polyline->spacing_m, 4.0);
  EXPECT_DOUBLE_EQ(rail.polyline->post_ercs, 0.5);
  EXPECT_DOUBLE_EQ(rail.polyline->face_ercs_per_m, 0.05);
  EXPECT_NEAR(rail.polyline->post_visibility.full_halfwidth_rad(), kPi / 3.0, 1e-15);
  try {
    builtin.at("hovercraft");
    FAIL() << "an unknown model was found";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(),
                 "unknown object model \"hovercraft\" (known: bicycle, cyclist, guard_rail, guide_board, passenger_car, "
                 "pedestrian, pole, sign_gantry, truck_trailer)");
  }
  // A model file; add() puts it beside the built-ins, and a model of the same name replaces one.
  const fs::path dir = testing::fresh_scratch_dir("model_library");
  std::ofstream(dir / "small.json") << kSmall;
  ModelLibrary library = builtin;
  library.add(load_object_model_file((dir / "small.json").string()));
  EXPECT_TRUE(library.contains("small"));
  ObjectModel replacement = library.at("small");
  replacement.name = "pole";
  library.add(replacement);
  EXPECT_EQ(library.models().size(), 10u);
  EXPECT_EQ(library.at("pole").planes.size(), 1u);  // the built-in pole has none
  // A file's refusal names the file.
  std::ofstream(dir / "bad.json") << R"({"format": "rcsim-object-model", "version": 1, "name": "bad", "length_m": 0,
      "width_m": 1, "point_reflectors": []})";
  try {
    load_object_model_file((dir / "bad.json").string());
    FAIL() << "a model of length 0 was read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "bad.json").string() + ": length_m: must be positive, got 0");
  }
  fs::remove_all(dir);
}

}  // namespace rcsim::model_library_test
