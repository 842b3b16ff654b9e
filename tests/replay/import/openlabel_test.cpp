// ASAM OpenLABEL 1.0 boxes (replay/import/openlabel.hpp) on small files written by hand: the
// cuboid's two rotation forms, frames and objects in order, timestamps to the ns, speeds, static
// cuboids, and each refusal naming the file and the field.
#include "replay/import/openlabel.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "scratch_dir.hpp"

namespace rcsim::openlabel_test {
namespace {

using replay::openlabel::Labels;
using replay::openlabel::LabelledBox;
using replay::openlabel::read_openlabel;
using ::testing::HasSubstr;

// An OpenLABEL document with these "objects" and "frames".
std::string document(const std::string& objects, const std::string& frames) {
  return R"({"openlabel": {"metadata": {"schema_version": "1.0.0"}, "objects": )" + objects + R"(, "frames": )" + frames + "}}";
}

// One frame at `timestamp` (JSON text) holding object "0" with this cuboid val.
std::string one_cuboid(const std::string& val, const std::string& timestamp = "1700000000") {
  return document(R"({"0": {"name": "car0", "type": "Car"}})",
                  R"({"0": {"frame_properties": {"timestamp": )" + timestamp +
                      R"(}, "objects": {"0": {"object_data": {"cuboid": [{"name": "shape", "coordinate_system": "vehicle-iso8855", "val": )" + val +
                      "}]}}}}}");
}

class OpenLabel : public rcsim::testing::ScratchDirTest {
 protected:
  OpenLabel() : ScratchDirTest("openlabel") {}

  Labels read(const std::string& json) const { return read_openlabel(write_file("labels.json", json)); }

  // The InputError's text for `json`, which must be refused.
  std::string refusal(const std::string& json) const {
    try {
      read(json);
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr((dir_ / "labels.json").string()));
      return e.what();
    }
    ADD_FAILURE() << "accepted: " << json;
    return "";
  }

  std::int64_t time_of(const std::string& timestamp) const { return read(one_cuboid("[0, 0, 0, 0, 0, 0, 4, 2, 1.5]", timestamp)).boxes.at(0).t_ns; }
};

TEST_F(OpenLabel, AQuaternionCuboidsCentreSizeAndYaw) {
  const double yaw_rad = 0.5;
  const Labels labels =
      read(one_cuboid(fmt::format("[12.5, -3.25, 0.75, 0, 0, {:.17g}, {:.17g}, 4.5, 1.8, 1.5]", std::sin(yaw_rad / 2), std::cos(yaw_rad / 2))));
  EXPECT_EQ(labels.schema_version, "1.0.0");
  ASSERT_EQ(labels.boxes.size(), 1u);
  const LabelledBox& box = labels.boxes[0];
  EXPECT_EQ(box.uid, "0");
  EXPECT_EQ(box.type, "Car");
  EXPECT_EQ(box.coordinate_system, "vehicle-iso8855");
  EXPECT_EQ(box.t_ns, 1'700'000'000'000'000'000);
  EXPECT_EQ(box.x_m, 12.5);
  EXPECT_EQ(box.y_m, -3.25);
  EXPECT_EQ(box.z_m, 0.75);
  EXPECT_NEAR(box.yaw_rad, yaw_rad, 1e-15);
  EXPECT_EQ(box.length_m, 4.5);
  EXPECT_EQ(box.width_m, 1.8);
  EXPECT_EQ(box.height_m, 1.5);
  EXPECT_FALSE(box.speed_mps);
}

TEST_F(OpenLabel, ANonUnitQuaternionIsNormalised) {
  // The standard allows quaternions "in non-unit form": 3 times the one of yaw -2.0 rad.
  const Labels labels =
      read(one_cuboid(fmt::format("[0, 0, 0, 0, 0, {:.17g}, {:.17g}, 4, 2, 1.5]", 3 * std::sin(-1.0), 3 * std::cos(-1.0))));
  EXPECT_NEAR(labels.boxes.at(0).yaw_rad, -2.0, 1e-15);
}

TEST_F(OpenLabel, AnEulerCuboidsYawIsRz) {
  const LabelledBox box = read(one_cuboid("[1, 2, 3, 0.1, 0.2, 0.3, 4, 2, 1.5]")).boxes.at(0);
  EXPECT_EQ(box.x_m, 1.0);
  EXPECT_EQ(box.y_m, 2.0);
  EXPECT_EQ(box.z_m, 3.0);
  EXPECT_EQ(box.yaw_rad, 0.3);
  EXPECT_EQ(box.length_m, 4.0);
  EXPECT_EQ(box.width_m, 2.0);
  EXPECT_EQ(box.height_m, 1.5);
  // Wrapped into [-pi, pi] like the quaternion's.
  EXPECT_NEAR(read(one_cuboid("[1, 2, 3, 0, 0, 4.0, 4, 2, 1.5]")).boxes.at(0).yaw_rad, 4.0 - kTwoPi, 1e-15);
}

TEST_F(OpenLabel, FramesInNumberOrderThenObjectsInFileOrder) {
  // Frame 10 stands before frame 9 in the file, and frame 9 gives its objects before its time.
  const Labels labels = read(document(
      R"({"7": {"name": "a", "type": "Pedestrian"}, "3": {"name": "b", "type": "Car", "coordinate_system": "odom"}})",
      R"({"10": {"frame_properties": {"timestamp": 2.5}, "objects": {
            "3": {"object_data": {"cuboid": [{"name": "shape", "val": [5, 0, 0, 0, 0, 0, 4, 2, 1.5]}]}},
            "7": {"object_data": {"cuboid": [{"name": "shape", "val": [6, 0, 0, 0, 0, 0, 0.5, 0.5, 1.8]}]}}}},
          "9": {"objects": {
            "7": {"object_data": {"cuboid": [{"name": "shape", "val": [1, 0, 0, 0, 0, 0, 0.5, 0.5, 1.8]}]}},
            "3": {"object_data": {"cuboid": [{"name": "shape", "val": [2, 0, 0, 0, 0, 0, 4, 2, 1.5]}]}}},
            "frame_properties": {"timestamp": 2.4}}})"));
  ASSERT_EQ(labels.boxes.size(), 4u);
  const auto expect = [&](std::size_t i, const char* uid, const char* type, std::int64_t t_ns, double x_m) {
    EXPECT_EQ(labels.boxes[i].uid, uid) << i;
    EXPECT_EQ(labels.boxes[i].type, type) << i;
    EXPECT_EQ(labels.boxes[i].t_ns, t_ns) << i;
    EXPECT_EQ(labels.boxes[i].x_m, x_m) << i;
  };
  expect(0, "7", "Pedestrian", 2'400'000'000, 1.0);
  expect(1, "3", "Car", 2'400'000'000, 2.0);
  expect(2, "3", "Car", 2'500'000'000, 5.0);
  expect(3, "7", "Pedestrian", 2'500'000'000, 6.0);
  // A cuboid naming no coordinate system is in its object's, else in none named.
  EXPECT_EQ(labels.boxes[1].coordinate_system, "odom");
  EXPECT_EQ(labels.boxes[0].coordinate_system, "");
}

TEST_F(OpenLabel, TimestampsToTheNanosecond) {
  // As a number and as a string: from the digits, which a double would round to 1700000000.1234567.
  EXPECT_EQ(time_of("1700000000.123456789"), 1'700'000'000'123'456'789);
  EXPECT_EQ(time_of(R"("1700000000.123456789")"), 1'700'000'000'123'456'789);
  EXPECT_EQ(time_of("1700000000.05"), 1'700'000'000'050'000'000);
  EXPECT_EQ(time_of("1.7e9"), 1'700'000'000'000'000'000);
  EXPECT_EQ(time_of("17E-1"), 1'700'000'000);
  EXPECT_EQ(time_of("0.0000000015"), 2);  // rounded to the nearest ns, halves up
  EXPECT_EQ(time_of("-0.25"), -250'000'000);
  // ISO 8601 with its zone: date -u -d 2023-04-01T12:00:00Z +%s gives 1680350400.
  EXPECT_EQ(time_of(R"("2023-04-01T12:00:00.050Z")"), 1'680'350'400'050'000'000);
  EXPECT_EQ(time_of(R"("2023-04-01 14:00:00.05+02:00")"), 1'680'350'400'050'000'000);
  EXPECT_EQ(time_of(R"("2023-04-01T07:30:00-0430")"), 1'680'350'400'000'000'000);
  EXPECT_EQ(time_of(R"("1970-01-01T00:00:00.000000001Z")"), 1);
}

TEST_F(OpenLabel, SpeedFromANum) {
  const Labels labels = read(document(R"({"0": {"name": "", "type": "Car"}, "1": {"name": "", "type": "Car"}, "2": {"name": "", "type": "Car"}})",
                                      R"({"0": {"frame_properties": {"timestamp": 1}, "objects": {
      "0": {"object_data": {"num": [{"name": "score", "val": 0.9}, {"name": "speed_mps", "val": 13.5}],
                            "cuboid": [{"name": "shape", "val": [0, 0, 0, 0, 0, 0, 4, 2, 1.5]}]}},
      "1": {"object_data": {"cuboid": [{"name": "shape", "val": [0, 0, 0, 0, 0, 0, 4, 2, 1.5],
                                         "attributes": {"num": [{"name": "speed", "val": -2}, {"name": "speed_mps", "type": "max", "val": 50}]}}]}},
      "2": {"object_data": {"cuboid": [{"name": "shape", "val": [0, 0, 0, 0, 0, 0, 4, 2, 1.5]}]}}}}})"));
  ASSERT_EQ(labels.boxes.size(), 3u);
  EXPECT_EQ(labels.boxes[0].speed_mps, 13.5);
  EXPECT_EQ(labels.boxes[1].speed_mps, -2.0);  // "speed" in the cuboid's attributes; a "max" is no speed
  EXPECT_FALSE(labels.boxes[2].speed_mps);
}

TEST_F(OpenLabel, StaticCuboidsHoldInEachFrameListingTheirObject) {
  // Object 0's static cuboid holds in frames 0 and 1, not in frame 2 which lists no object 0; in
  // frame 1 object 1's own cuboid replaces its static one; a null val is no box.
  const Labels labels = read(document(
      R"({"0": {"name": "sign", "type": "Static", "object_data": {"cuboid": [{"name": "shape", "val": [30, 1, 0, 0, 0, 0, 0.5, 0.5, 2]}],
                                                          "num": [{"name": "speed_mps", "val": 0}]}},
          "1": {"name": "car", "type": "Car", "object_data": {"cuboid": [{"name": "shape", "val": [9, 9, 9, 0, 0, 0, 4, 2, 1.5]}]}}})",
      R"({"0": {"frame_properties": {"timestamp": 1}, "objects": {"0": {}}},
          "1": {"frame_properties": {"timestamp": 2}, "objects": {"0": {}, "1": {"object_data": {"cuboid": [
                {"name": "shape", "val": [10, 0, 0, 0, 0, 0, 4, 2, 1.5]}, {"name": "other", "val": null}]}}}},
          "2": {"frame_properties": {"timestamp": 3}, "objects": {}}})"));
  ASSERT_EQ(labels.boxes.size(), 3u);
  EXPECT_EQ(labels.boxes[0].uid, "0");
  EXPECT_EQ(labels.boxes[0].t_ns, 1'000'000'000);
  EXPECT_EQ(labels.boxes[0].x_m, 30.0);
  EXPECT_EQ(labels.boxes[0].speed_mps, 0.0);
  EXPECT_EQ(labels.boxes[1].uid, "0");
  EXPECT_EQ(labels.boxes[1].t_ns, 2'000'000'000);
  EXPECT_EQ(labels.boxes[2].uid, "1");
  EXPECT_EQ(labels.boxes[2].x_m, 10.0);
}

// Issue 51, HIGH 8: static cuboids were copied into every frame that lists their object, so a
// few bytes per listing made a box each: 1,000 cuboids x 10,000 frames gave 3.5 GB from 800 KB.
// The boxes are bounded by the file's bytes (one per kFileBytesPerBox) and per frame, checked
// before the cuboids are copied, naming the listing that passes the bound.
TEST_F(OpenLabel, StaticCuboidsCopiedBeyondTheBytesBehindThemAreRefused) {
  using replay::openlabel::kFileBytesPerBox;
  using replay::openlabel::kMaxBoxesPerFrame;
  const auto cuboids = [](std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n; ++i) out += std::string(i == 0 ? "" : ",") + R"({"val":[0,0,0,0,0,0,1,1,1]})";
    return "[" + out + "]";
  };
  // 100 static cuboids listed by 300 frames: 30,000 boxes from some 20 kB.
  std::string frames;
  for (int f = 0; f < 300; ++f) frames += fmt::format(R"({}"{}":{{"frame_properties":{{"timestamp":{}}},"objects":{{"0":{{}}}}}})", f == 0 ? "" : ",", f, f + 1);
  const std::string bomb = document(R"({"0":{"type":"Car","object_data":{"cuboid":)" + cuboids(100) + "}}}", "{" + frames + "}");
  const std::size_t max_boxes = bomb.size() / kFileBytesPerBox;
  ASSERT_LT(max_boxes, 30'000u);
  const std::string m = refusal(bomb);
  EXPECT_THAT(m, HasSubstr(fmt::format("openlabel.frames.{}.objects.0: {} boxes with this object's 100, where the file's {} bytes allow {} "
                                       "(one per 4 bytes, schemas/limits.md)",
                                       max_boxes / 100, (max_boxes / 100 + 1) * 100, bomb.size(), max_boxes)));
  // The same listed by as few frames as its bytes allow: read.
  std::string few;
  for (int f = 0; f < 3; ++f) few += fmt::format(R"({}"{}":{{"frame_properties":{{"timestamp":{}}},"objects":{{"0":{{}}}}}})", f == 0 ? "" : ",", f, f + 1);
  EXPECT_EQ(read(document(R"({"0":{"type":"Car","object_data":{"cuboid":)" + cuboids(100) + "}}}", "{" + few + "}")).boxes.size(), 300u);
  // Two objects of 5,001 static cuboids each in one frame: more than a frame may hold.
  const std::string crowded = document(R"({"0":{"type":"Car","object_data":{"cuboid":)" + cuboids(5'001) + R"(}},"1":{"type":"Car","object_data":{"cuboid":)" +
                                           cuboids(5'001) + "}}}",
                                       R"({"0":{"frame_properties":{"timestamp":1},"objects":{"0":{},"1":{}}}})");
  EXPECT_THAT(refusal(crowded), HasSubstr(fmt::format("openlabel.frames.0.objects.1: 10002 boxes in the frame with this object's 5001: more than the "
                                                      "limit of {} a frame (schemas/limits.md)",
                                                      kMaxBoxesPerFrame)));
}

TEST_F(OpenLabel, NoFramesNoBoxes) {
  EXPECT_TRUE(read(R"({"openlabel": {"metadata": {"schema_version": "1.0.0"}}})").boxes.empty());
}

TEST_F(OpenLabel, RefusesWhatIsNotOpenLabel) {
  EXPECT_THAT(refusal("this is not JSON"), HasSubstr("not JSON"));
  EXPECT_THAT(refusal(""), HasSubstr("not JSON"));
  EXPECT_THAT(refusal(R"({"vcd": {}})"), HasSubstr("openlabel: missing: not an OpenLABEL file"));
  EXPECT_THAT(refusal(R"({"openlabel": {"objects": {}}})"), HasSubstr("openlabel.metadata.schema_version: missing"));
  // Cut short, by as little as its last brace, or followed by more.
  const std::string whole = one_cuboid("[0, 0, 0, 0, 0, 0, 4, 2, 1.5]");
  EXPECT_THAT(refusal(whole.substr(0, whole.size() - 12)), HasSubstr("not JSON"));
  EXPECT_THAT(refusal(whole.substr(0, whole.size() - 1)), HasSubstr("labels.json: is not valid JSON"));
  EXPECT_THAT(refusal(whole + R"( {"openlabel": {}})"), HasSubstr("labels.json: not JSON: more follows its root object"));
}

TEST_F(OpenLabel, RefusesBadCuboids) {
  const std::string cuboid = "openlabel.frames.0.objects.0.object_data.cuboid[0].val";
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 0, 0, 0, 0, 4, 2]")), HasSubstr(cuboid + ": holds 8 numbers; a cuboid holds 9"));
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 0, 0, 0, 0, 0, 0, 4, 2, 1.5]")), HasSubstr(cuboid + ": holds 11 numbers"));
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 1e999, 0, 0, 0, 4, 2, 1.5]")), HasSubstr(cuboid + "[2]: is not a finite number"));
  EXPECT_THAT(refusal(one_cuboid(R"([0, 0, "x", 0, 0, 0, 4, 2, 1.5])")), HasSubstr(cuboid + "[2]"));
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 0, 0, 0, 0, 4, 0, 1.5]")), HasSubstr(cuboid + "[7]: sy = 0 is no size"));
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 0, 0, 0, 0, 1, 4, 2, -1.5]")), HasSubstr(cuboid + "[9]: sz = -1.5 is no size"));
  EXPECT_THAT(refusal(one_cuboid("[0, 0, 0, 0, 0, 0, 0, 4, 2, 1.5]")), HasSubstr(cuboid + ": the quaternion (qx, qy, qz, qw) is zero"));
  EXPECT_THAT(refusal(document(R"({"0": {"name": "", "type": "Car"}})",
                               R"({"0": {"frame_properties": {"timestamp": 0}, "objects": {"0": {"object_data": {"cuboid": [{"name": "shape"}]}}}}})")),
              HasSubstr(cuboid + ": missing"));
}

TEST_F(OpenLabel, RefusesBadObjectsAndFrames) {
  EXPECT_THAT(refusal(document(R"({"0": {"name": "car0", "type": "Car"}})",
                               R"({"12": {"frame_properties": {"timestamp": 0}, "objects": {"3": {}}}})")),
              HasSubstr("openlabel.frames.12.objects.3: object 3 is not among openlabel.objects"));
  EXPECT_THAT(refusal(document(R"({"0": {"name": "car0"}})", "{}")), HasSubstr("openlabel.objects.0.type: missing"));
  EXPECT_THAT(refusal(document(R"({"0": {"name": "car0", "type": "Car"}})", R"({"first": {}})")),
              HasSubstr("openlabel.frames.first: is no frame number"));
  EXPECT_THAT(refusal(document(R"({"0": {"name": "", "type": "Car"}})",
                               R"({"0": {"frame_properties": {"timestamp": 0}, "objects": {"0": {"object_data": {
                                   "num": [{"name": "speed_mps", "val": "fast"}]}}}}})")),
              HasSubstr("openlabel.frames.0.objects.0.object_data.num[0].val: has the wrong JSON type"));
}

TEST_F(OpenLabel, RefusesAFrameWithBoxesWithoutAUsableTime) {
  const std::string timestamp = "openlabel.frames.0.frame_properties.timestamp";
  const auto at = [](const std::string& time) { return one_cuboid("[0, 0, 0, 0, 0, 0, 4, 2, 1.5]", time); };
  const std::string no_time = document(R"({"0": {"name": "", "type": "Car"}})", R"({"0": {"objects": {"0": {"object_data": {"cuboid": [
      {"name": "shape", "val": [0, 0, 0, 0, 0, 0, 4, 2, 1.5]}]}}}}})");
  EXPECT_THAT(refusal(no_time), HasSubstr(timestamp + ": missing"));
  // The standard's own example has no zone: it names no instant.
  EXPECT_THAT(refusal(at(R"("2020-04-11 12:00:01")")), HasSubstr(timestamp + ": \"2020-04-11 12:00:01\" is no time rcsim reads"));
  EXPECT_THAT(refusal(at(R"("2023-02-29T12:00:00Z")")), HasSubstr(timestamp));
  EXPECT_THAT(refusal(at(R"("yesterday")")), HasSubstr(timestamp));
  EXPECT_THAT(refusal(at("1e30")), HasSubstr(timestamp));  // past 2262
  EXPECT_THAT(refusal(at("true")), HasSubstr(timestamp + ": is neither a number nor a string"));
}

}  // namespace
}  // namespace rcsim::openlabel_test
