#include "model/model_library.hpp"

#include <fmt/format.h>

#include <set>
#include <stdexcept>

#include "common/angles.hpp"
#include "common/embedded_data.hpp"
#include "common/limits.hpp"

namespace rcsim {
namespace {

VisibilityFunction parse_visibility(const JsonField& field) {
  field.expect_only({"center_deg", "full_halfwidth_deg", "falloff_deg"});
  const double center_deg = field.number_within("center_deg", -360.0, 360.0, "deg");
  const double full_deg = field.number("full_halfwidth_deg");
  const double falloff_deg = field.number_within("falloff_deg", -360.0, 360.0, "deg");
  require_non_negative(field, "full_halfwidth_deg", full_deg);
  require_non_negative(field, "falloff_deg", falloff_deg);
  if (full_deg > 180.0) field.fail("full_halfwidth_deg", "must be at most 180");
  return {deg_to_rad(center_deg), deg_to_rad(full_deg), deg_to_rad(falloff_deg)};
}

// A height above the road (version 2): 0 to 100 m.
double parse_height_m(const JsonField& f, std::string_view key) { return f.number_within(key, 0.0, 100.0, "m"); }

// A reflector's micro-Doppler (version 2, object_model.hpp Swing).
Swing parse_swing(const JsonField& f) {
  f.expect_only({"relative_amplitude", "period_s", "rolling_radius_m", "phase_deg"});
  Swing swing;
  swing.relative_amplitude = f.number_within("relative_amplitude", 0.0, 10.0, "");
  require_positive(f, "relative_amplitude", swing.relative_amplitude);
  if (f.has("period_s") == f.has("rolling_radius_m")) {
    f.fail("needs one of period_s (a gait or a crank) and rolling_radius_m (a point on a wheel)");
  }
  if (f.has("period_s")) {
    swing.period_s = f.number_within("period_s", 0.0, 60.0, "s");
    require_positive(f, "period_s", swing.period_s);
  } else {
    swing.rolling_radius_m = f.number_within("rolling_radius_m", 0.0, 10.0, "m");
    require_positive(f, "rolling_radius_m", swing.rolling_radius_m);
  }
  swing.phase_rad = deg_to_rad(f.number_or("phase_deg", 0.0));
  if (!(std::abs(swing.phase_rad) <= kTwoPi)) f.fail("phase_deg", "must be in [-360, 360]");
  return swing;
}

PolylineTemplate parse_polyline_template(const JsonField& f, int version) {
  if (version >= 2) {
    f.expect_only({"spacing_m", "post_ercs", "post_visibility", "face_ercs_per_m", "z_m"});
  } else {
    f.expect_only({"spacing_m", "post_ercs", "post_visibility", "face_ercs_per_m"});
  }
  PolylineTemplate t;
  t.spacing_m = f.number("spacing_m");
  if (!(t.spacing_m >= 0.1 && t.spacing_m <= 1000.0)) f.fail("spacing_m", "must be in [0.1, 1000] m");
  t.post_ercs = f.number_or("post_ercs", 0.0);
  t.face_ercs_per_m = f.number_or("face_ercs_per_m", 0.0);
  require_non_negative(f, "post_ercs", t.post_ercs);
  require_non_negative(f, "face_ercs_per_m", t.face_ercs_per_m);
  if (t.post_ercs > limits::kMaxErcs) f.fail("post_ercs", fmt::format("must be at most {}", limits::kMaxErcs));
  if (t.face_ercs_per_m > limits::kMaxErcs) {
    f.fail("face_ercs_per_m", fmt::format("must be at most {} per m", limits::kMaxErcs));
  }
  if (!(t.post_ercs > 0.0) && !(t.face_ercs_per_m > 0.0)) f.fail("needs post_ercs or face_ercs_per_m above 0");
  if (t.post_ercs > 0.0) t.post_visibility = parse_visibility(f.member("post_visibility"));
  if (version >= 2 && f.has("z_m")) t.z_m = parse_height_m(f, "z_m");
  return t;
}

}  // namespace

ObjectModel parse_object_model(const JsonField& root) {
  // Version 2 adds heights (z_m, height_m, clearance_m) and micro-Doppler (swing); a version 1
  // file is read as before, its reflectors on the road (z 0).
  const int version = root.expect_format_versions("rcsim-object-model", 1, 2);
  if (version >= 2) {
    root.expect_only({"format", "version", "name", "description", "length_m", "width_m", "height_m", "clearance_m",
                      "diffuse_ercs_factor",
                      "point_reflectors", "plane_reflectors", "polyline"});
  } else {
    root.expect_only({"format", "version", "name", "description", "length_m", "width_m", "point_reflectors",
                      "plane_reflectors", "polyline"});
  }
  ObjectModel model;
  model.name = root.string("name");
  model.description = root.has("description") ? root.string("description") : "";
  model.length_m = root.number_within("length_m", 0.0, limits::kMaxSize_m, "m");
  model.width_m = root.number_within("width_m", 0.0, limits::kMaxSize_m, "m");
  // A model is a few reflection centres (paper II); thousands are a generated or broken file.
  constexpr std::size_t kMaxReflectors = 10'000;
  for (const char* key : {"point_reflectors", "plane_reflectors"}) {
    if (root.has(key) && root.json().at(key).is_array() && root.json().at(key).size() > kMaxReflectors) {
      root.fail(key, fmt::format("more than {} reflectors (schemas/limits.md)", kMaxReflectors));
    }
  }
  const auto offset_m = [](const JsonField& f, std::string_view key) {
    return f.number_within(key, -limits::kMaxSize_m, limits::kMaxSize_m, "m");
  };
  require_positive(root, "length_m", model.length_m);
  require_positive(root, "width_m", model.width_m);
  if (version >= 2) {
    model.height_m = root.has("height_m") ? parse_height_m(root, "height_m") : 0.0;
    model.clearance_m = root.has("clearance_m") ? parse_height_m(root, "clearance_m") : 0.0;
    model.diffuse_ercs_factor = root.has("diffuse_ercs_factor") ? root.number_within("diffuse_ercs_factor", 0.0, 1.0, "") : 1.0;
    if (model.clearance_m > 0.0 && model.height_m > 0.0 && model.clearance_m >= model.height_m) {
      root.fail("clearance_m", "must be below height_m (the free height under the object, within its height)");
    }
  }
  const auto height_of = [&](const JsonField& f) { return version >= 2 && f.has("z_m") ? parse_height_m(f, "z_m") : 0.0; };
  if (root.has("point_reflectors")) {
    for (const auto& p : root.array("point_reflectors")) {
      if (version >= 2) {
        p.expect_only({"name", "x_m", "y_m", "z_m", "ercs", "visibility", "swing"});
      } else {
        p.expect_only({"name", "x_m", "y_m", "ercs", "visibility"});
      }
      PointReflector point;
      point.name = p.string("name");
      point.p_OR_O = {offset_m(p, "x_m"), offset_m(p, "y_m")};
      point.z_m = height_of(p);
      if (version >= 2) {
        if (const auto swing = p.optional_member("swing")) {
          point.swing = parse_swing(*swing);
          model.has_swinging_points = true;
        }
      }
      point.ercs_max = p.number_within("ercs", 0.0, limits::kMaxErcs, "");
      require_positive(p, "ercs", point.ercs_max);
      point.visibility = parse_visibility(p.member("visibility"));
      model.points.push_back(std::move(point));
    }
  }
  if (root.has("plane_reflectors")) {
    for (const auto& p : root.array("plane_reflectors")) {
      if (version >= 2) {
        p.expect_only({"name", "from_x_m", "from_y_m", "to_x_m", "to_y_m", "z_m", "sagitta_m", "ercs"});
      } else {
        p.expect_only({"name", "from_x_m", "from_y_m", "to_x_m", "to_y_m", "sagitta_m", "ercs"});
      }
      const Vec2 from{offset_m(p, "from_x_m"), offset_m(p, "from_y_m")};
      const Vec2 to{offset_m(p, "to_x_m"), offset_m(p, "to_y_m")};
      const double sagitta_m = offset_m(p, "sagitta_m");
      const double ercs = p.number_within("ercs", 0.0, limits::kMaxErcs, "");
      require_positive(p, "ercs", ercs);
      require_positive(p, "sagitta_m", sagitta_m);
      if ((to - from).norm() <= 0.0) p.fail("to_x_m", "chord has zero length (from and to coincide)");
      if (sagitta_m > 0.5 * (to - from).norm()) p.fail("sagitta_m", "must be at most half the chord length");
      model.planes.push_back(plane_from_chord(p.string("name"), from, to, sagitta_m, ercs));
      model.planes.back().z_m = height_of(p);
    }
  }
  if (const auto polyline = root.optional_member("polyline")) {
    if (!model.points.empty() || !model.planes.empty()) {
      root.fail("polyline", "a polyline model has no point or plane reflectors of its own (its polyline makes them)");
    }
    model.polyline = parse_polyline_template(*polyline, version);
    return model;
  }
  if (model.points.empty() && model.planes.empty()) root.fail("a model needs at least one reflector");
  std::set<std::string> names;
  for (const auto& p : model.points) {
    if (!names.insert(p.name).second) root.fail("point_reflectors", "duplicate reflector name \"" + p.name + "\"");
  }
  for (const auto& p : model.planes) {
    if (!names.insert(p.name).second) root.fail("plane_reflectors", "duplicate reflector name \"" + p.name + "\"");
  }
  return model;
}

ObjectModel load_object_model_file(const std::string& path) {
  const auto json = parse_json_file(path);
  return parse_object_model(JsonField(json, path, ""));
}

ModelLibrary ModelLibrary::builtin() {
  ModelLibrary library;
  for (const auto& file : embedded_object_models()) {
    const std::string name = "builtin:" + std::string(file.name) + ".json";
    const auto json = parse_json_text(file.text, name);
    library.add(parse_object_model(JsonField(json, name, "")));
  }
  return library;
}

void ModelLibrary::add(ObjectModel model) {
  const std::string name = model.name;
  models_.insert_or_assign(name, std::move(model));
}

const ObjectModel& ModelLibrary::at(std::string_view name) const {
  const auto it = models_.find(std::string(name));
  if (it == models_.end()) {
    std::string known;
    for (const auto& [n, m] : models_) known += (known.empty() ? "" : ", ") + n;
    throw std::out_of_range(fmt::format("unknown object model \"{}\" (known: {})", name, known));
  }
  return it->second;
}

}  // namespace rcsim
