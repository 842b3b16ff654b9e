// rcsim calibrate: the fit finds a known ERCS, mirrored reflectors stay symmetric, a written
// calibration replays exactly as fitted, and bad calibration directories are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/input_error.hpp"
#include "model/model_library.hpp"
#include "replay/calibrate/calibration_fit.hpp"
#include "replay/calibrate/snapshot_frames.hpp"
#include "replay/run/model_recording.hpp"
#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::testing {
namespace {

using replay::CalibrationOptions;
using replay::ParameterGroup;

// A car and a pole coming towards a standing sensor from 30 m to 6 m.
Scene approach_scene() {
  Scene scene = single_sensor_scene(4.0);
  add_object(scene, "car", "passenger_car", {sample(0.0, 30.0, -2.0, kPi, 6.0)});
  add_object(scene, "pole", "pole", {sample(0.0, 30.0, 2.0, kPi, 6.0)});
  return scene;
}

// The drive recorded by a sensor for which the pole reflects `pole_ercs` instead of the built-in
// 1, the reference reflector: what the fit has to find. With ERCS 1 the pole passes the 6 dB
// threshold from (26.5 - 6) / 0.75 = 27.3 m (eq. (1)); with 0.25 (-12 dB) only from 11.3 m.
Recording recording_with_pole_ercs(double pole_ercs, std::uint64_t seed) {
  Scene scene = approach_scene();
  scene.objects.back().model.points.front().ercs_max = pole_ercs;
  return replay::model_recording(scene, "pole_ercs", seed);
}

const replay::CalibrationParameter& parameter(const replay::CalibrationResult& r, const std::string& name) {
  for (const auto& p : r.parameters) {
    if (p.name == name) return p;
  }
  throw std::out_of_range("no parameter " + name);
}

TEST(Calibration, FindsThePoleErcsTheRecordingWasMadeWith) {
  const std::vector<Recording> recordings{recording_with_pole_ercs(0.25, 3)};
  CalibrationOptions options;
  options.groups = {ParameterGroup::ercs};
  options.seed = 3;  // the recording's draws: only the parameters differ
  options.initial_step_db = 6.0;
  options.final_step_db = 1.5;
  const auto result = replay::calibrate(recordings, options);
  const auto& pole = parameter(result, "pole.pole.ercs");
  EXPECT_EQ(pole.pointers, std::vector<std::string>{"/point_reflectors/0/ercs"});
  EXPECT_DOUBLE_EQ(pole.initial, 1.0);
  EXPECT_NEAR(20.0 * std::log10(pole.value), -12.0, 1.5) << pole.value;
  ASSERT_EQ(result.recordings.size(), 1u);
  EXPECT_LT(result.recordings[0].gospa_after_m, 0.5 * result.recordings[0].gospa_before_m);
  EXPECT_FALSE(result.flat);
  EXPECT_LT(result.objective_after, result.objective_before);
  EXPECT_GT(result.evaluations, 10);
  // The fitted document holds the value the search ended with.
  EXPECT_DOUBLE_EQ(result.documents.at("model:pole")["point_reflectors"][0]["ercs"].get<double>(), pole.value);
}

// The message check_fittable refuses `r` with at `fidelity`, or "" if it takes it.
std::string fittable_refusal(const Recording& r, Fidelity fidelity) {
  try {
    replay::check_fittable(r, fidelity);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Single frames of raw detections need no 4 cycles for a track to confirm (issue 48): none is
// simulated or compared. Tracks keep the minimum, recorded or simulated (srr24 tracks at full).
TEST(Calibration, FewFramesFitWhereNoTrackConfirms) {
  const Recording frames = snapshot_frames({.frames = 3});
  EXPECT_EQ(fittable_refusal(frames, Fidelity::no_tracking), "");
  EXPECT_EQ(fittable_refusal(frames, Fidelity::full), "");  // aimotive_lrr reports detections
  Recording one = snapshot_frames({.frames = 1});
  EXPECT_EQ(fittable_refusal(one, Fidelity::full), "");

  Recording tracks = frames;
  tracks.sensors[0].reports = ListLevel::tracks;
  EXPECT_NE(fittable_refusal(tracks, Fidelity::no_tracking).find("3 cycles; a fit needs 4 at least"), std::string::npos);
  Recording tracking_profile = frames;
  tracking_profile.sensors[0].type = "srr24";
  EXPECT_NE(fittable_refusal(tracking_profile, Fidelity::full).find("its sensors' profiles track"), std::string::npos);
  EXPECT_EQ(fittable_refusal(tracking_profile, Fidelity::no_tracking), "");
}

// docs/hardening.md: a recording with no annotated object is refused, naming it, by both fits.
TEST(Calibration, ARecordingWithoutObjectsIsRefused) {
  Recording none = snapshot_frames({.frames = 5});
  none.objects.clear();
  none.boxes.clear();
  for (const Fidelity f : {Fidelity::full, Fidelity::no_tracking}) {
    EXPECT_EQ(fittable_refusal(none, f), "snapshot_frames: objects.csv: holds no annotated object: nothing to fit the model's objects to");
  }
  EXPECT_THROW(replay::calibrate({none}, CalibrationOptions{}), InputError);
}

// The multibounce loss on a recording made without multibounce (its declared effects, which the
// replay follows) moves nothing: the objective is flat, and said to be, not fitted.
TEST(Calibration, AnObjectiveNoParameterMovesIsFlat) {
  const std::vector<Recording> close_front{read_recording(std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "close_front")};
  CalibrationOptions options;
  options.groups = {ParameterGroup::multibounce};
  options.initial_step_db = options.final_step_db = 6.0;
  const auto result = replay::calibrate(close_front, options);
  EXPECT_TRUE(result.flat);
  EXPECT_GE(result.evaluations, 2);
  EXPECT_DOUBLE_EQ(result.objective_after, result.objective_before);
}

// The default groups (ercs, slope) on a radar-equation profile: slope is eq. (1)'s, which the
// profile has not; refused naming --fit and pointing to --real-drive (issue 53, trap 1), where it
// was a JSON library's type error.
TEST(Calibration, EquationOneGroupsOnARadarEquationProfileAreRefusedNamingTheOption) {
  const std::vector<Recording> frames{snapshot_frames({.frames = 3})};
  for (const ParameterGroup g : {ParameterGroup::slope, ParameterGroup::level}) {
    CalibrationOptions options;
    options.groups = {ParameterGroup::ercs, g};
    try {
      replay::calibrate(frames, options);
      ADD_FAILURE() << "accepted " << replay::parameter_group_name(g);
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(fmt::format("--fit: {}: the sensor profile aimotive_lrr has the radar-equation amplitude law",
                                       replay::parameter_group_name(g)), 0),
                0u)
          << what;
      EXPECT_NE(what.find("--real-drive"), std::string::npos) << what;
    }
  }
}

TEST(Calibration, MirroredReflectorsShareParametersAndStaySymmetric) {
  const std::vector<Recording> recordings{recording_with_pole_ercs(0.25, 3)};
  CalibrationOptions options;
  options.groups = {ParameterGroup::ercs, ParameterGroup::position, ParameterGroup::visibility, ParameterGroup::slope};
  options.seed = 3;
  options.initial_step_db = 6.0;
  options.final_step_db = 6.0;
  const auto result = replay::calibrate(recordings, options);
  const auto& y = parameter(result, "passenger_car.corner_front_left+corner_front_right.y_m");
  EXPECT_EQ(y.pointers.size(), 2u);
  parameter(result, "passenger_car.side_left+side_right.outward_offset_m");
  parameter(result, "srr24.amplitude.reference_slope_db_per_m");
  EXPECT_THROW(parameter(result, "passenger_car.corner_front_left.ercs"), std::out_of_range);  // only as a pair
  const auto& car = result.documents.at("model:passenger_car");
  for (std::size_t i = 0; i + 1 < car["point_reflectors"].size(); i += 2) {  // left, right, ...
    const auto& l = car["point_reflectors"][i];
    const auto& r = car["point_reflectors"][i + 1];
    EXPECT_DOUBLE_EQ(l["ercs"].get<double>(), r["ercs"].get<double>());
    EXPECT_DOUBLE_EQ(l["x_m"].get<double>(), r["x_m"].get<double>());
    EXPECT_DOUBLE_EQ(l["y_m"].get<double>(), -r["y_m"].get<double>());
    EXPECT_DOUBLE_EQ(l["visibility"]["center_deg"].get<double>(), -r["visibility"]["center_deg"].get<double>());
  }
  const auto& left = car["plane_reflectors"][2];
  const auto& right = car["plane_reflectors"][3];
  EXPECT_DOUBLE_EQ(left["from_y_m"].get<double>(), -right["to_y_m"].get<double>());
}

class CalibrationFiles : public ScratchDirTest {
 protected:
  CalibrationFiles() : ScratchDirTest("calibration") {}
};

TEST_F(CalibrationFiles, AWrittenCalibrationReplaysExactlyAsFitted) {
  std::vector<Recording> recordings{recording_with_pole_ercs(0.25, 5)};
  recordings[0].dir = dir_ / "recording";
  write_recording(recordings[0].dir, recordings[0]);
  recordings[0] = read_recording(recordings[0].dir);
  CalibrationOptions options;
  options.groups = {ParameterGroup::ercs, ParameterGroup::slope};
  options.seed = 5;
  options.final_step_db = 3.0;
  const auto result = replay::calibrate(recordings, options);
  const std::string out = (dir_ / "fitted").string();
  replay::write_calibration(out, result, options, recordings, nullptr);

  const auto calibration = replay::load_calibration(out);
  ASSERT_TRUE(calibration->models.count("passenger_car"));
  ASSERT_TRUE(calibration->sensors.count("srr24"));
  EXPECT_DOUBLE_EQ(calibration->sensors.at("srr24").amplitude.reference_slope_db_per_m,
                   parameter(result, "srr24.amplitude.reference_slope_db_per_m").value);

  // rcsim replay --calibration DIR with the fit's seed gives the fit's figure to the last bit.
  replay::ReplayOptions replay_options;
  replay_options.seed = 5;
  replay_options.import.calibration_dir = out;
  replay::DiscardingSink sink;
  EXPECT_EQ(replay::replay_recording(recordings[0], replay_options, sink).gospa_mean_m, result.recordings[0].gospa_after_m);
  replay_options.import.calibration_dir.clear();
  EXPECT_EQ(replay::replay_recording(recordings[0], replay_options, sink).gospa_mean_m, result.recordings[0].gospa_before_m);

  const auto index = nlohmann::json::parse(read_file(std::filesystem::path(out) / "calibration.json"));
  EXPECT_EQ(index["format"], "rcsim-calibration");
  EXPECT_EQ(index["version"], 1);
  EXPECT_EQ(index["models"]["passenger_car"], "model_passenger_car.json");
  EXPECT_EQ(index["fitted_on"][0]["recording"], "pole_ercs");
  EXPECT_TRUE(index["cross_validation"].is_null());
}

TEST_F(CalibrationFiles, AFitStartedFromACalibrationStartsWhereItStopped) {
  std::vector<Recording> recordings{recording_with_pole_ercs(0.25, 5)};
  CalibrationOptions options;
  options.groups = {ParameterGroup::ercs};
  options.seed = 5;
  options.final_step_db = 3.0;
  const auto first = replay::calibrate(recordings, options);
  const std::string out = (dir_ / "first").string();
  replay::write_calibration(out, first, options, recordings, nullptr);

  options.start_dir = out;
  options.final_step_db = 1.5;
  const auto second = replay::calibrate(recordings, options);
  // Its starting point is the first fit: same GOSPA, same pole ERCS, and it can only improve.
  EXPECT_EQ(second.recordings[0].gospa_before_m, first.recordings[0].gospa_after_m);
  EXPECT_DOUBLE_EQ(parameter(second, "pole.pole.ercs").initial, parameter(first, "pole.pole.ercs").value);
  EXPECT_LE(second.recordings[0].gospa_after_m, second.recordings[0].gospa_before_m);

  const std::string again = (dir_ / "second").string();
  replay::write_calibration(again, second, options, recordings, nullptr);
  const auto index = nlohmann::json::parse(read_file(std::filesystem::path(again) / "calibration.json"));
  EXPECT_EQ(index["started_from"], out);
  const auto pole = nlohmann::json::parse(read_file(std::filesystem::path(again) / "model_pole.json"));
  const std::string description = pole["description"];
  EXPECT_EQ(description.find("Calibrated by"), description.rfind("Calibrated by"));  // said once, not twice

  options.start_dir = (dir_ / "nowhere").string();
  EXPECT_THROW(replay::calibrate(recordings, options), InputError);
}

TEST_F(CalibrationFiles, RefusesDirectoriesThatAreNotCalibrationsNamingTheFileAndField) {
  const auto message = [&](const std::string& index_text) {
    std::ofstream(dir_ / "calibration.json") << index_text;
    try {
      replay::load_calibration(dir_.string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  try {
    replay::load_calibration((dir_ / "missing").string());
    FAIL() << "accepted a directory without calibration.json";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("calibration.json"), std::string::npos) << e.what();
  }
  EXPECT_NE(message(R"({"format": "rcsim-bench", "version": 1, "sensors": {}, "models": {}})").find("format"),
            std::string::npos);
  EXPECT_NE(message(R"({"format": "rcsim-calibration", "version": 1, "sensors": {}, "models": {"passenger_car": "nope.json"}})")
                .find("models.passenger_car"),
            std::string::npos);
  // A file listed under another name than the one it holds.
  std::ofstream(dir_ / "car.json") << ModelLibrary::builtin().at("pole").name;  // not even JSON
  EXPECT_NE(message(R"({"format": "rcsim-calibration", "version": 1, "sensors": {}, "models": {"passenger_car": "car.json"}})")
                .find("car.json"),
            std::string::npos);
  std::ofstream(dir_ / "pole.json") << read_file(std::filesystem::path(RCSIM_SOURCE_DIR) / "src/model/models/pole.json");
  const std::string renamed = message(R"({"format": "rcsim-calibration", "version": 1, "sensors": {}, "models": {"passenger_car": "pole.json"}})");
  EXPECT_NE(renamed.find("holds \"pole\""), std::string::npos) << renamed;
}

}  // namespace
}  // namespace rcsim::testing
