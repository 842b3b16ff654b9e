// The Astyx importer (replay/import/astyx_importer.hpp) on the real frames in ../shared/realdata
// (never part of the project; skipped, saying so, where they are absent): checked against an
// independent reading of the files (counts, points, boxes, classes), the yaw convention (the
// points near a car lie inside its box, and would not with the box turned), the Doppler sign, the
// demo frames' CAN ego motion, --frames, and refusals of damaged copies.
#include "replay/import/astyx_importer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <sys/stat.h>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "fuzz/astyx_targets.hpp"
#include "peak_memory.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace astyx_importer_test {

namespace fs = std::filesystem;

using rcsim::testing::kAstyxRaw;

const fs::path kHires = kAstyxRaw / "dataset_astyx_hires2019";
const fs::path kDemo = kAstyxRaw / "dataset_astyx_demo";

// ---- an independent reading of the dataset's files, in plain code ----

struct PlainPoint {
  double x, y, z, v_r, mag;
};

std::vector<PlainPoint> plain_points(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // blank
  std::getline(in, line);  // header
  std::vector<PlainPoint> points;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    PlainPoint p{};
    if (row >> p.x >> p.y >> p.z >> p.v_r >> p.mag) points.push_back(p);
  }
  return points;
}

nlohmann::json plain_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

double plain_yaw(const nlohmann::json& q) {  // (w, x, y, z)
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

double plain_yaw_read_as_xyzw(const nlohmann::json& q) {  // the other order, for the check of the convention
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

bool skip_without_data() { return !fs::is_directory(kHires) || !fs::is_directory(kDemo); }
#define ASTYX_SKIP_WITHOUT_DATA()                                                                    \
  if (skip_without_data()) GTEST_SKIP() << "real data absent (" << kAstyxRaw.string() << "): Astyx importer tests skipped"

class AstyxImporter : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (skip_without_data()) return;
    hires_ = new DatasetRecording(import_astyx(kHires));
    demo_ = new DatasetRecording(import_astyx(kDemo));
  }
  static void TearDownTestSuite() {
    delete hires_;
    delete demo_;
    hires_ = demo_ = nullptr;
  }
  void SetUp() override { ASTYX_SKIP_WITHOUT_DATA(); }
  static const Recording& hires() { return hires_->recording; }
  static const Recording& demo() { return demo_->recording; }

  static DatasetRecording* hires_;
  static DatasetRecording* demo_;
};
DatasetRecording* AstyxImporter::hires_ = nullptr;
DatasetRecording* AstyxImporter::demo_ = nullptr;

TEST_F(AstyxImporter, TheHiresSetIsOneSnapshotRecordingOfItsRadar) {
  const Recording& r = hires();
  EXPECT_EQ(r.cycle_count(), 400);
  EXPECT_EQ(r.timeline, Timeline::snapshots);
  EXPECT_FALSE(r.ego_motion_known);
  EXPECT_DOUBLE_EQ(r.cycle_time_s, 1.0);
  ASSERT_EQ(r.sensors.size(), 1u);
  const RecordingSensor& s = r.sensors[0];
  EXPECT_EQ(s.id, "radar_6455");
  EXPECT_EQ(s.type, "astyx_hires");
  EXPECT_EQ(s.reports, ListLevel::detections);
  EXPECT_EQ(s.amplitude_unit, AmplitudeUnit::relative_db);
  EXPECT_DOUBLE_EQ(s.x_m, 0.0);
  EXPECT_DOUBLE_EQ(s.yaw_rad, 0.0);  // the radar is the reference frame
  ASSERT_TRUE(s.range_rate_interval_mps.has_value());
  EXPECT_NEAR(s.range_rate_interval_mps->min_mps, -5.2374, 1e-12);
  EXPECT_NEAR(s.range_rate_interval_mps->max_mps, 5.1562, 1e-12);
  EXPECT_NEAR(s.range_rate_interval_mps->max_mps - s.range_rate_interval_mps->min_mps, 128 * 0.0812, 1e-9);
  for (int k = 0; k < r.cycle_count(); ++k) {
    const EgoSample& e = r.ego[static_cast<std::size_t>(k)];
    EXPECT_EQ(e.t_s, k);
    EXPECT_EQ(e.x_m, 0.0);
    EXPECT_GE(e.speed_mps, 0.0);  // the Doppler speed (fit_speed_aliased)
    EXPECT_EQ(e.yaw_rate_radps, 0.0);
  }
  // The speeds against a brute force over 0..25 m/s in 0.05-m/s steps, counting the points with
  // |V_r - v cos(angle)| within 0.1 m/s (wrapped; angle from the forward axis in 3-D), done apart
  // in Python: frame 0 stands (831 points at V_r 0), frames 50, 100, 350 at 19.85, 10.9, 9.0.
  EXPECT_NEAR(r.ego[0].speed_mps, 0.0, 0.05);  // least squares over the inliers within 0.1 m/s: 0.035
  EXPECT_NEAR(r.ego[50].speed_mps, 19.85, 0.1);
  EXPECT_NEAR(r.ego[100].speed_mps, 10.9, 0.1);
  EXPECT_NEAR(r.ego[350].speed_mps, 9.0, 0.1);
  EXPECT_EQ(r.source.at("ego_motion").at("frames_fitted"), 400);
  EXPECT_EQ(r.source.at("frames").size(), 400u);
  EXPECT_EQ(r.source.at("frames")[155], 155);
  EXPECT_EQ(r.source.at("frame_index")[155], plain_json(kHires / "groundtruth_obj3d/000155.json").at("frame_index"));
  EXPECT_NE(r.source.at("licence").get<std::string>().find("CC BY-NC-SA 4.0"), std::string::npos);
  EXPECT_NE(r.source.at("ego_motion").at("why").get<std::string>().find("neither compares radial speeds"), std::string::npos);
  EXPECT_NE(r.source.at("boxes").get<std::string>().find("no velocities"), std::string::npos);
}

// Counts of every frame, and classes over the whole set, read again in plain code.
TEST_F(AstyxImporter, CountsAndClassesAsThePlainReadingHasThem) {
  std::size_t points = 0;
  std::map<std::string, int> classes;
  for (int f = 0; f < 400; ++f) {
    points += plain_points(kHires / fmt::format("radar_6455/{:06}.txt", f)).size();
    const nlohmann::json labels = plain_json(kHires / fmt::format("groundtruth_obj3d/{:06}.json", f));
    for (const auto& o : labels.at("objects")) {
      ++classes[o.at("classname").get<std::string>()];
    }
  }
  EXPECT_EQ(hires().targets.size(), points);
  std::map<std::string, int> models;
  for (const RecordingObject& o : hires().objects) ++models[o.object_class];
  EXPECT_EQ(models["passenger_car"], classes["Car"]);
  EXPECT_EQ(models["truck_trailer"], classes["Truck"] + classes["Bus"] + classes["Trailer"] + classes["Towed Object"] +
                                          classes["Other Vehicle"]);
  // People are pedestrians (Person, Person with Object), riders of bicycles cyclists: nothing left out.
  EXPECT_EQ(models["pedestrian"], classes["Person"] + classes["Person with Object"] + classes["Person_with_Object"]);
  EXPECT_EQ(models["cyclist"], classes["Cyclist"]);
  EXPECT_TRUE(hires_->warnings.empty()) << hires_->warnings.front();
  // Measured on these 400 frames.
  EXPECT_EQ(points, 894216u);
  EXPECT_EQ(models["passenger_car"], 2161);
  EXPECT_EQ(models["truck_trailer"], 127);
  // The road under the boxes: 1.59 m below the radar, pitched 2.55 deg down (docs/importers.md).
  ASSERT_EQ(hires().sensors.size(), 1u);
  EXPECT_NEAR(hires().sensors[0].z_m, 1.59, 0.01);
  EXPECT_NEAR(hires().sensors[0].pitch_rad * 180.0 / kPi, 2.55, 0.01);
}

// Three frames point by point and box by box against the plain reading.
TEST_F(AstyxImporter, ThreeFramesAgreeWithThePlainReading) {
  for (const int f : {0, 155, 399}) {
    SCOPED_TRACE(fmt::format("frame {}", f));
    const std::vector<PlainPoint> points = plain_points(kHires / fmt::format("radar_6455/{:06}.txt", f));
    std::vector<const RecordedTarget*> targets;
    for (const RecordedTarget& t : hires().targets) {
      if (t.cycle == f) targets.push_back(&t);
    }
    ASSERT_EQ(targets.size(), points.size());
    ASSERT_GT(points.size(), 100u);
    for (const std::size_t i : {std::size_t{0}, points.size() / 2, points.size() - 1}) {
      const PlainPoint& p = points[i];
      const RecordedTarget& t = *targets[i];
      EXPECT_NEAR(t.range_m, std::hypot(p.x, p.y), 1e-9);
      EXPECT_NEAR(t.azimuth_rad, std::atan2(p.y, p.x), 1e-9);
      EXPECT_NEAR(t.elevation_rad, std::atan2(p.z, std::hypot(p.x, p.y)), 1e-9);
      EXPECT_NEAR(t.range_rate_mps, -p.v_r, 1e-9);  // V_r is positive approaching
      EXPECT_DOUBLE_EQ(t.amplitude_db, p.mag);
      EXPECT_DOUBLE_EQ(t.t_s, f);
      EXPECT_TRUE(std::isnan(t.snr_db));  // Mag is no SNR
    }
    const nlohmann::json labels = plain_json(kHires / fmt::format("groundtruth_obj3d/{:06}.json", f));
    int compared = 0;
    for (std::size_t i = 0; i < labels.at("objects").size(); ++i) {
      const nlohmann::json& o = labels.at("objects")[i];
      const std::string id = fmt::format("f{:06}_{:02}", f, i);
      const int index = [&] {
        for (std::size_t j = 0; j < hires().objects.size(); ++j) {
          if (hires().objects[j].id == id) return static_cast<int>(j);
        }
        return -1;
      }();
      if (o.at("classname") == "Person") {
        EXPECT_EQ(index, -1) << id;
        continue;
      }
      ASSERT_GE(index, 0) << id;
      const RecordingObject& object = hires().objects[static_cast<std::size_t>(index)];
      const std::vector<AnnotatedBox>& boxes = hires().boxes[static_cast<std::size_t>(index)];
      ASSERT_EQ(boxes.size(), 1u);
      EXPECT_DOUBLE_EQ(boxes[0].t_s, f);
      EXPECT_NEAR(boxes[0].x_m, o.at("center3d")[0].get<double>(), 1e-12);
      EXPECT_NEAR(boxes[0].y_m, o.at("center3d")[1].get<double>(), 1e-12);
      EXPECT_NEAR(boxes[0].yaw_rad, plain_yaw(o.at("orientation_quat")), 1e-9);
      EXPECT_EQ(boxes[0].speed_mps, 0.0);
      EXPECT_DOUBLE_EQ(object.length_m, o.at("dimension3d")[0].get<double>());
      EXPECT_DOUBLE_EQ(object.width_m, o.at("dimension3d")[1].get<double>());
      EXPECT_EQ(object.object_class, o.at("classname") == "Car" ? "passenger_car" : "truck_trailer");
      EXPECT_EQ(object.attributes.at("dataset_class"), o.at("classname"));
      EXPECT_EQ(object.attributes.at("occlusion"), o.at("occlusion"));
      EXPECT_EQ(object.attributes.at("label_certainty"), o.at("label_certainty"));
      EXPECT_DOUBLE_EQ(object.attributes.at("height_m").get<double>(), o.at("dimension3d")[2].get<double>());
      EXPECT_DOUBLE_EQ(object.attributes.at("z_m").get<double>(), o.at("center3d")[2].get<double>());
      EXPECT_EQ(object.attributes.at("frame"), f);
      ++compared;
    }
    EXPECT_GT(compared, 0);
  }
}

// The yaw convention: of the points within 1 m of the circle round a car's box, most lie inside the
// box (grown by 0.25 m for the labels' slack), far fewer with the box turned by 90 degrees or its
// quaternion read as (x, y, z, w). Measured over all 400 frames: 71 %, 26 % and 57 %.
TEST_F(AstyxImporter, ThePointsNearACarLieInsideItsBox) {
  // Each cycle's targets: they are in cycle order.
  std::vector<std::size_t> first_of_cycle(static_cast<std::size_t>(hires().cycle_count()) + 1, hires().targets.size());
  for (std::size_t i = hires().targets.size(); i-- > 0;) first_of_cycle[static_cast<std::size_t>(hires().targets[i].cycle)] = i;
  for (std::size_t k = first_of_cycle.size() - 1; k-- > 0;) first_of_cycle[k] = std::min(first_of_cycle[k], first_of_cycle[k + 1]);
  const auto inside_fraction = [&](auto yaw_of) {
    long inside = 0, near = 0;
    for (std::size_t o = 0; o < hires().objects.size(); ++o) {
      const RecordingObject& object = hires().objects[o];
      if (object.object_class != "passenger_car") continue;
      const AnnotatedBox& box = hires().boxes[o][0];
      const double yaw = yaw_of(object, box);
      const double reach = std::hypot(object.length_m, object.width_m) / 2.0 + 1.0;
      const auto k = static_cast<std::size_t>(box.t_s);
      for (std::size_t i = first_of_cycle[k]; i < first_of_cycle[k + 1]; ++i) {
        const RecordedTarget& t = hires().targets[i];
        const double dx = t.range_m * std::cos(t.azimuth_rad) - box.x_m, dy = t.range_m * std::sin(t.azimuth_rad) - box.y_m;
        if (std::hypot(dx, dy) > reach) continue;
        ++near;
        const double along = std::cos(yaw) * dx + std::sin(yaw) * dy, across = -std::sin(yaw) * dx + std::cos(yaw) * dy;
        inside += std::abs(along) <= object.length_m / 2.0 + 0.25 && std::abs(across) <= object.width_m / 2.0 + 0.25;
      }
    }
    EXPECT_GT(near, 20000);
    return static_cast<double>(inside) / static_cast<double>(near);
  };
  const double right = inside_fraction([](const RecordingObject&, const AnnotatedBox& b) { return b.yaw_rad; });
  const double turned = inside_fraction([](const RecordingObject&, const AnnotatedBox& b) { return b.yaw_rad + kPi / 2.0; });
  const double xyzw = inside_fraction([](const RecordingObject& object, const AnnotatedBox&) {
    const int frame = object.attributes.at("frame");
    const int index = std::stoi(object.id.substr(8));
    return plain_yaw_read_as_xyzw(plain_json(kHires / fmt::format("groundtruth_obj3d/{:06}.json", frame))
                                      .at("objects")[static_cast<std::size_t>(index)]
                                      .at("orientation_quat"));
  });
  EXPECT_GT(right, 0.65);
  EXPECT_LT(turned, 0.35);
  EXPECT_LT(xyzw, right - 0.1);
}

// The demo frames: CAN speed and yaw rate, the demo's radar and class names, the Doppler sign.
TEST_F(AstyxImporter, TheDemoFramesCarryTheirCanEgoMotion) {
  const Recording& r = demo();
  EXPECT_EQ(r.cycle_count(), 5);
  EXPECT_TRUE(r.ego_motion_known);
  ASSERT_EQ(r.sensors.size(), 1u);
  EXPECT_EQ(r.sensors[0].id, "radar_hires1");
  const double kmh[] = {0.0, 2.0, 28.0, 55.0, 0.0};
  for (int k = 0; k < 5; ++k) {
    const nlohmann::json can = nlohmann::json::parse(std::regex_replace(
        rcsim::testing::read_file(kDemo / fmt::format("canbus/{:06}.json", k)), std::regex(R"(\bNaN\b)"), "null"));
    EXPECT_NEAR(r.ego[static_cast<std::size_t>(k)].speed_mps, kmh[k] / 3.6, 1e-12);
    EXPECT_DOUBLE_EQ(can.at("vehicle_speed").get<double>(), kmh[k]);
    EXPECT_NEAR(r.ego[static_cast<std::size_t>(k)].yaw_rate_radps, can.at("YAW_RATE").get<double>() * kPi / 180.0, 1e-12);
  }
  EXPECT_EQ(r.source.at("frame_index"), nlohmann::json({0, 1, 2, 3, 8}));
  // Towed_Object (the demo's spelling) is a truck; Person and Person_with_Object are pedestrians.
  int towed = 0;
  for (const RecordingObject& o : r.objects) {
    if (o.attributes.at("dataset_class") != "Towed_Object") continue;
    ++towed;
    EXPECT_EQ(o.object_class, "truck_trailer");
  }
  EXPECT_EQ(towed, 1);
  EXPECT_TRUE(demo_->warnings.empty()) << demo_->warnings.front();
  int pedestrians = 0;
  for (const RecordingObject& o : r.objects) pedestrians += o.object_class == "pedestrian" ? 1 : 0;
  EXPECT_EQ(pedestrians, 4 + 2);  // 4 Person and 2 Person_with_Object boxes
  // The Doppler sign: driving at 55 km/h (frame 3), the stationary world ahead (within 10 degrees)
  // reads v cos(angle) wrapped into the interval with range rate -V_r, not +V_r.
  const RangeRateInterval interval = *r.sensors[0].range_rate_interval_mps;
  const double width = interval.max_mps - interval.min_mps;
  const auto wrapped = [&](double v) { return interval.min_mps + std::fmod(std::fmod(v - interval.min_mps, width) + width, width); };
  int closing = 0, receding = 0;
  for (const RecordedTarget& t : r.targets) {
    if (t.cycle != 3 || std::abs(t.azimuth_rad) > 0.17) continue;
    const double v = r.ego[3].speed_mps * std::cos(t.azimuth_rad) * std::cos(t.elevation_rad);
    closing += std::abs(t.range_rate_mps - wrapped(-v)) < 0.5;
    receding += std::abs(t.range_rate_mps - wrapped(v)) < 0.5;
  }
  EXPECT_GT(closing, 3 * receding) << closing << " vs " << receding;
}

// ---- --frames ----

TEST_F(AstyxImporter, FramesChooseByTheirNumberForFitAndHeldOutSets) {
  const DatasetRecording fit = import_astyx(kHires, {{}, "0-199"}), held_out = import_astyx(kHires, {{}, "200-399"});
  EXPECT_EQ(fit.recording.cycle_count(), 200);
  EXPECT_EQ(held_out.recording.cycle_count(), 200);
  EXPECT_EQ(fit.recording.targets.size() + held_out.recording.targets.size(), hires().targets.size());
  EXPECT_EQ(fit.recording.objects.size() + held_out.recording.objects.size(), hires().objects.size());
  EXPECT_EQ(held_out.recording.source.at("frames")[0], 200);
  EXPECT_EQ(held_out.recording.objects[0].attributes.at("frame"), 200);
  EXPECT_EQ(held_out.recording.boxes[0][0].t_s, 0.0);  // cycle 0 of its own recording
  EXPECT_NE(held_out.recording.name.find("frames 200-399"), std::string::npos) << held_out.recording.name;

  const DatasetRecording some = import_astyx(kHires, {{}, "0-9,20"});
  EXPECT_EQ(some.recording.cycle_count(), 11);
  EXPECT_EQ(some.recording.source.at("frames"), nlohmann::json({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 20}));
  std::size_t frame_20 = 0;
  for (const RecordedTarget& t : hires().targets) frame_20 += t.cycle == 20;
  std::size_t cycle_10 = 0;
  for (const RecordedTarget& t : some.recording.targets) cycle_10 += t.cycle == 10;
  EXPECT_EQ(cycle_10, frame_20);
  const DatasetRecording standing = import_astyx(kDemo, {{}, "0,4"});
  EXPECT_EQ(standing.recording.cycle_count(), 2);
  EXPECT_EQ(standing.recording.ego[1].speed_mps, 0.0);
  EXPECT_EQ(standing.recording.source.at("frame_index"), nlohmann::json({0, 8}));
}

std::string refusal_of(const fs::path& dir, const DatasetImportOptions& options = {}) {
  try {
    import_astyx(dir, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AstyxFrames, ListsAreRefusedNamingTheOptionAndTheFrame) {
  ASTYX_SKIP_WITHOUT_DATA();
  const auto expect = [](const std::string& list, const std::vector<std::string>& parts) {
    const std::string message = refusal_of(kDemo, {{}, list});
    EXPECT_EQ(message.rfind("--frames: ", 0), 0u) << list << ": " << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << list << ": " << message;
  };
  expect("5", {"frame 5 is not in", "dataset_info.json", "it lists frames 0-4"});
  expect("0-9", {"frame 5 is not in"});
  expect("3-1", {"runs backwards", "1-3"});
  expect("0,,2", {"'' in '0,,2'"});
  expect("0;2", {"'0;2'"});
  expect("-1", {"not a frame number"});
  expect("1,0-2", {"frame 1 is chosen twice"});
  expect("99999999999", {"not a frame number"});
  const std::string huge = refusal_of(kHires, {{}, "0-1000000000"});
  EXPECT_NE(huge.find("frame 400 is not in"), std::string::npos) << huge;
  EXPECT_NE(refusal_of(kDemo, {"ego.csv", ""}).find("--ego-log"), std::string::npos);
}

// ---- refusals of damaged copies of one frame ----

class AstyxDamaged : public rcsim::testing::ScratchDirTest {
 protected:
  AstyxDamaged() : ScratchDirTest("astyx") {}
  void SetUp() override {
    ASTYX_SKIP_WITHOUT_DATA();
    ScratchDirTest::SetUp();
    data_ = dir_ / "dataset_copy";
    for (const char* folder : {"radar_6455", "groundtruth_obj3d", "calibration"}) {
      fs::create_directories(data_ / folder);
      const std::string ext = std::string(folder) == "radar_6455" ? ".txt" : ".json";
      fs::copy_file(kHires / folder / ("000007" + ext), data_ / folder / ("000007" + ext));
    }
    std::ofstream(data_ / "dataset.json") << R"({"data": {"7": {"calibration": "calibration/000007.json",
        "groundtruth_obj3d": "groundtruth_obj3d/000007.json", "radar_6455": "radar_6455/000007.txt"}}})";
  }
  fs::path radar() const { return data_ / "radar_6455/000007.txt"; }
  fs::path labels() const { return data_ / "groundtruth_obj3d/000007.json"; }
  // Replaces the text of `file` (the first match of `pattern` by `with`); the import's refusal.
  std::string damaged(const fs::path& file, const std::string& pattern, const std::string& with) {
    const std::string text = rcsim::testing::read_file(file);
    const std::string changed = std::regex_replace(text, std::regex(pattern), with, std::regex_constants::format_first_only);
    EXPECT_NE(changed, text) << pattern;
    std::ofstream(file, std::ios::trunc) << changed;
    const std::string message = refusal_of(data_);
    std::ofstream(file, std::ios::trunc) << text;
    return message;
  }
  // The radar file with field `column` of its first row (line 3) replaced by `value` (dropped
  // where empty); the import's refusal.
  std::string damaged_first_row(std::size_t column, const std::string& value) {
    const std::string text = rcsim::testing::read_file(radar());
    const std::size_t begin = text.find("Mag\n") + 4, end = text.find('\n', begin);
    std::istringstream row(text.substr(begin, end - begin));
    std::vector<std::string> fields{std::istream_iterator<std::string>(row), std::istream_iterator<std::string>()};
    EXPECT_EQ(fields.size(), 5u);
    fields[column] = value;
    std::string line;
    for (const std::string& f : fields) line += (line.empty() || f.empty() ? "" : " ") + f;
    std::ofstream(radar(), std::ios::trunc) << text.substr(0, begin) + line + text.substr(end);
    const std::string message = refusal_of(data_);
    std::ofstream(radar(), std::ios::trunc) << text;
    return message;
  }
  fs::path data_;
};

TEST_F(AstyxDamaged, TheUndamagedCopyImports) {
  const DatasetRecording r = import_astyx(data_);
  EXPECT_EQ(r.recording.cycle_count(), 1);
  EXPECT_EQ(r.recording.source.at("frames"), nlohmann::json({7}));
  EXPECT_EQ(r.recording.targets.size(), plain_points(radar()).size());
}

TEST_F(AstyxDamaged, RadarFilesAreRefusedNamingFileLineAndColumn) {
  const auto expect = [&](const std::string& message, const std::vector<std::string>& parts) {
    EXPECT_NE(message.find("000007.txt"), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(damaged(radar(), "X Y Z V_r Mag", "X Y Z Vr Mag"), {"line 2", "expected the header 'X Y Z V_r Mag'", "Vr"});
  expect(damaged(radar(), "X Y Z V_r Mag", "X Y Z V_r"), {"line 2"});
  // Line 3 is the first row: a field made a word, the last dropped, NaN, values out of bounds.
  expect(damaged_first_row(2, "zero"), {"line 3, column 'Z'", "'zero' is not a number"});
  expect(damaged_first_row(4, ""), {"line 3", "4 fields, expected 5", "truncated"});
  expect(damaged_first_row(3, "nan"), {"line 3, column 'V_r'", "not finite"});
  expect(damaged_first_row(3, "7.5"), {"line 3, column 'V_r'", "Doppler levels"});
  expect(damaged_first_row(0, "20000"), {"line 3, column 'X'", "10000 m"});
  expect(damaged_first_row(4, "1e300"), {"line 3, column 'Mag'", "1000 dB"});
  std::ofstream(radar(), std::ios::trunc) << "";
  expect(refusal_of(data_), {"no header"});
  fs::remove(radar());
  expect(refusal_of(data_), {"missing"});
}

TEST_F(AstyxDamaged, LabelsAreRefusedNamingFileAndField) {
  const auto expect = [&](const std::string& message, const std::vector<std::string>& parts) {
    EXPECT_NE(message.find("groundtruth_obj3d/000007.json"), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(damaged(labels(), R"("orientation_quat": \[[^\]]*\])", R"("orientation_quat": [0.0, 0.0, 0.0, 0.0])"),
         {"objects[0].orientation_quat", "zero norm"});
  expect(damaged(labels(), R"("center3d")", R"("centre")"), {"objects[0].center3d", "missing"});
  expect(damaged(labels(), R"("center3d": \[[^\]]*\])", R"("center3d": [1.0, 2.0])"), {"objects[0].center3d", "3 numbers"});
  expect(damaged(labels(), R"("dimension3d": \[\s*[-0-9.e]+)", R"("dimension3d": [-4.2)"), {"objects[0].dimension3d"});
  expect(damaged(labels(), R"("occlusion": [0-9]+)", R"("occlusion": "high")"), {"objects[0].occlusion", "must be a number"});
  expect(damaged(labels(), R"("classname": "[^"]*")", R"("classname": "Car\nX")"), {"objects[0].classname", "newline"});
  std::ofstream(labels(), std::ios::trunc) << "{\"objects\": [";
  expect(refusal_of(data_), {"invalid JSON"});
}

TEST_F(AstyxDamaged, CalibrationAndListingAreRefusedNamingFileAndField) {
  const fs::path calibration = data_ / "calibration/000007.json";
  std::string message = damaged(calibration, R"("radar_6455")", R"("radar_9999")");
  EXPECT_NE(message.find("calibration/000007.json: sensors: no sensor with sensor_uid \"radar_6455\""), std::string::npos)
      << message;
  message = damaged(calibration, R"(\[\s*1\.0,)", "[2.0,");
  EXPECT_NE(message.find("T_to_ref_COS: is no rigid transform"), std::string::npos) << message;
  const std::string listing = rcsim::testing::read_file(data_ / "dataset.json");
  std::ofstream(data_ / "dataset.json", std::ios::trunc) << std::regex_replace(listing, std::regex("radar_6455/"), "../../radar_6455/");
  message = refusal_of(data_);
  EXPECT_NE(message.find("dataset.json: data.7.radar_6455: must not leave the dataset directory"), std::string::npos) << message;
  std::ofstream(data_ / "dataset.json", std::ios::trunc) << std::regex_replace(listing, std::regex("\"radar_6455\":"), "\"radar\":");
  message = refusal_of(data_);
  EXPECT_NE(message.find("data.7: no radar file (radar_6455 or radar_hires1)"), std::string::npos) << message;
  std::ofstream(data_ / "dataset.json", std::ios::trunc) << std::regex_replace(listing, std::regex("\"7\""), "\"seven\"");
  message = refusal_of(data_);
  EXPECT_NE(message.find("data.seven: a frame's key must be its number"), std::string::npos) << message;
}

// Through the command line: exit 2, the file and line named, nothing written.
TEST_F(AstyxDamaged, TheCommandRefusesWithExitTwoAndWritesNothing) {
  std::ofstream(radar(), std::ios::app) << "\n1.0 2.0 3.0\n";
  const auto r = rcsim::testing::run_rcsim("import --from astyx " + data_.string() + " -o " + (dir_ / "rec").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("000007.txt: line"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 fields, expected 5"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "rec"));
}

// What is imported is written and read back as it was.
TEST_F(AstyxDamaged, AnImportIsWrittenAndReadBack) {
  const DatasetRecording imported = import_astyx(kDemo);
  write_recording(dir_ / "rec", imported.recording);
  const Recording back = read_recording(dir_ / "rec");
  EXPECT_EQ(back.timeline, Timeline::snapshots);
  EXPECT_TRUE(back.ego_motion_known);
  EXPECT_EQ(back.targets.size(), imported.recording.targets.size());
  EXPECT_EQ(back.objects.size(), imported.recording.objects.size());
  EXPECT_EQ(back.sensors[0].amplitude_unit, AmplitudeUnit::relative_db);
  EXPECT_EQ(back.objects[0].attributes, imported.recording.objects[0].attributes);
}

// The fuzz harness's made-up base (tests/fuzz/base/astyx.txt) is accepted, so that the fuzzer
// starts from inputs rcsim takes; and its corpus seeds too.
TEST(AstyxFuzzBase, TheBaseAndTheSeedsImportAndReadBack) {
  replay::DatasetImportOptions options;
  const fs::path dir = fuzz::write_astyx_dataset({}, options);
  const Recording recording = fuzz::import_astyx_and_read_back(dir, options);
  EXPECT_EQ(recording.cycle_count(), 3);
  EXPECT_EQ(recording.objects.size(), 12u);  // car, truck, towed object and person of each frame
  EXPECT_EQ(recording.targets.size(), 3u * 20u);
  EXPECT_TRUE(recording.ego_motion_known);
  for (const char* seed : {"frames_0_and_2", "snapshots_without_canbus", "demo_radar_hires1"}) {
    const std::string text = fuzz::read_source_file(fs::path("tests/fuzz/corpus/astyx") / seed);
    replay::DatasetImportOptions seed_options;
    const fs::path seed_dir = fuzz::write_astyx_dataset(
        {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, seed_options);
    EXPECT_EQ(fuzz::import_astyx_and_read_back(seed_dir, seed_options).cycle_count(),
              std::string(seed) == "snapshots_without_canbus" ? 3 : 2)
        << seed;
  }
}

// ---- issue 51: hostile datasets and lists, on the made-up base (no real data needed) ----

// A repeated range was expanded whole before its duplicates were found (21,000 copies of the
// dataset's frames, 6.8 GB): overlapping ranges are refused before any is expanded.
TEST(AstyxHostile, ARepeatedRangeIsRefusedBeforeItIsExpanded) {
  replay::DatasetImportOptions options;
  const fs::path dir = fuzz::write_astyx_dataset({}, options);
  std::string list = "0-2";
  for (int i = 0; i < 200000; ++i) list += ",0-2";
  options.frames = list;
  std::string message;
  const auto added = rcsim::testing::peak_memory_added_by([&] {
    try {
      import_astyx(dir / "raw" / "dataset_astyx_fuzz", options);
    } catch (const InputError& e) {
      message = e.what();
    }
  });
  EXPECT_EQ(message.rfind("--frames: frame 0 is chosen twice (0-2 and 0-2 overlap)", 0), 0u) << message.substr(0, 200);
  EXPECT_LT(message.size(), 200u);
  if (added) {
    EXPECT_LT(*added, 64 << 20) << "bytes added";
  }
}

// A symbolic link inside the dataset led out of it, and the refusal of its header printed the
// linked file's first line: it is refused as leading out, naming the listing's field; nothing of
// the file is read. A radar file that is a FIFO is "not a regular file", not "missing".
TEST(AstyxHostile, ALinkLeadingOutOfTheDatasetAndAFifoAreRefusedForWhatTheyAre) {
  replay::DatasetImportOptions options;
  const fs::path dir = fuzz::write_astyx_dataset({}, options);
  const fs::path dataset = dir / "raw" / "dataset_astyx_fuzz";
  const fs::path secret = dir / "secret.txt";
  std::ofstream(secret) << "root:$6$hash:19000:0:99999:7:::\n";
  fs::remove(dataset / "radar_6455" / "000001.txt");
  fs::create_symlink(secret, dataset / "radar_6455" / "000001.txt");
  std::string message;
  try {
    import_astyx(dataset, options);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("dataset.json"), std::string::npos) << message;
  EXPECT_NE(message.find("leads out of the dataset directory through a symbolic link"), std::string::npos) << message;
  EXPECT_EQ(message.find("root:"), std::string::npos) << message;
  // A link that stays inside is followed as before.
  fs::remove(dataset / "radar_6455" / "000001.txt");
  fs::copy_file(dataset / "radar_6455" / "000000.txt", dataset / "radar_6455" / "copy.txt");
  fs::create_symlink("copy.txt", dataset / "radar_6455" / "000001.txt");
  EXPECT_NO_THROW(import_astyx(dataset, options));
  fs::remove(dataset / "radar_6455" / "000001.txt");
  ASSERT_EQ(::mkfifo((dataset / "radar_6455" / "000001.txt").c_str(), 0600), 0);
  message.clear();
  try {
    import_astyx(dataset, options);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("000001.txt: not a regular file"), std::string::npos) << message;
}

#undef ASTYX_SKIP_WITHOUT_DATA

}  // namespace astyx_importer_test
}  // namespace rcsim::replay
