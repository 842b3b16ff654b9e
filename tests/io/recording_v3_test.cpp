// Recording format version 3 (schemas/recording.md): the timeline, whether the ego motion is
// known, a sensor's amplitude unit and range-rate interval, an object's attributes. A round trip
// keeps them; recordings that use none of them are still written as version 1 or 2, byte for
// byte as before; every refusal names the field.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "app/cli/run_rcsim.hpp"
#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;

const fs::path kSyntheticRecordings = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic";

class RecordingV3 : public testing::ScratchDirTest {
 protected:
  RecordingV3() : ScratchDirTest("rec_v3") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    rec_.name = "tiny_v3";
    rec_.cycle_time_s = 1.0;
    rec_.sensors = {{"radar", "srr24", 0.0, 0.0, 0.0}};
    rec_.objects = {{"f000000_00", "passenger_car", 4.5, 1.8}, {"f000001_00", "truck_trailer", 12.0, 2.5}};
    rec_.boxes = {{{0.0, 20.0, 1.0, 0.5, 0.0, 0}}, {{1.0, 30.0, -2.0, -1.0, 0.0, 0}}};
    for (int k = 0; k < 2; ++k) {
      rec_.ego.push_back({1.0 * k, 0.0, 0.0, 0.0, 0.0, 0.0});
      rec_.targets.push_back({1.0 * k, k, 0, -1, 15.0 + k, 0.1, -2.0, 52.5});
    }
    rec_.sensors[0].reports = ListLevel::detections;
  }

  // rec_ with every version 3 field away from its default.
  Recording v3() const {
    Recording r = rec_;
    r.timeline = Timeline::snapshots;
    r.ego_motion_known = false;
    r.sensors[0].amplitude_unit = AmplitudeUnit::relative_db;
    r.sensors[0].range_rate_interval_mps = RangeRateInterval{-5.2374, 5.1562};
    r.objects[0].attributes = {{"dataset_class", "Car"}, {"occlusion", 1}, {"height_m", 1.45}};
    return r;
  }

  // `text` with `from` replaced by `to` (first occurrence).
  static std::string edited(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " not in\n" << text;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  }

  // The reader's message for recording.json replaced by `text` (empty if accepted).
  std::string refusal(const fs::path& dir, const std::string& text) {
    std::ofstream(dir / "recording.json", std::ios::trunc) << text;
    try {
      read_recording(dir);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  void expect_refused(const fs::path& dir, const std::string& text, const std::vector<std::string>& expected) {
    const std::string message = refusal(dir, text);
    ASSERT_FALSE(message.empty()) << "accepted:\n" << text;
    EXPECT_NE(message.find("recording.json"), std::string::npos) << message;
    for (const std::string& part : expected) EXPECT_NE(message.find(part), std::string::npos) << message;
  }

  Recording rec_;
};

TEST_F(RecordingV3, RoundTripKeepsEveryVersion3FieldAndIsByteStable) {
  write_recording(dir_ / "a", v3());
  const std::string header = testing::read_file(dir_ / "a" / "recording.json");
  EXPECT_NE(header.find("\"version\": 3"), std::string::npos) << header;
  EXPECT_NE(header.find("\"timeline\": \"snapshots\""), std::string::npos) << header;
  EXPECT_NE(header.find("\"ego_motion_known\": false"), std::string::npos) << header;
  const Recording back = read_recording(dir_ / "a");
  EXPECT_EQ(back.timeline, Timeline::snapshots);
  EXPECT_FALSE(back.ego_motion_known);
  EXPECT_EQ(back.sensors[0].amplitude_unit, AmplitudeUnit::relative_db);
  ASSERT_TRUE(back.sensors[0].range_rate_interval_mps.has_value());
  EXPECT_DOUBLE_EQ(back.sensors[0].range_rate_interval_mps->min_mps, -5.2374);
  EXPECT_DOUBLE_EQ(back.sensors[0].range_rate_interval_mps->max_mps, 5.1562);
  EXPECT_EQ(back.sensors[0].reports, ListLevel::detections);
  EXPECT_EQ(back.objects[0].attributes.at("dataset_class"), "Car");
  EXPECT_EQ(back.objects[0].attributes.at("occlusion"), 1);
  EXPECT_TRUE(back.objects[1].attributes.empty());
  EXPECT_EQ(back.cycle_count(), 2);
  write_recording(dir_ / "b", back);
  for (const char* file : {"recording.json", "ego.csv", "objects.csv", "targets.csv"}) {
    EXPECT_EQ(testing::read_file(dir_ / "a" / file), testing::read_file(dir_ / "b" / file)) << file;
  }
}

TEST_F(RecordingV3, EachVersion3FieldAloneMakesVersion3AndDefaultsMakeNone) {
  const auto version_of = [&](const Recording& r, const std::string& name) {
    write_recording(dir_ / name, r);
    const std::string header = testing::read_file(dir_ / name / "recording.json");
    std::smatch m;
    EXPECT_TRUE(std::regex_search(header, m, std::regex("\"version\": (\\d)"))) << header;
    return std::stoi(m[1]);
  };
  Recording r = rec_;
  EXPECT_EQ(version_of(r, "v2"), 2);
  r.sensors[0].reports = ListLevel::tracks;
  for (auto& t : r.targets) t.id = 1;
  EXPECT_EQ(version_of(r, "v1"), 1);
  Recording a = r;
  a.timeline = Timeline::snapshots;
  EXPECT_EQ(version_of(a, "timeline"), 3);
  Recording b = r;
  b.ego_motion_known = false;
  EXPECT_EQ(version_of(b, "ego"), 3);
  Recording c = r;
  c.sensors[0].amplitude_unit = AmplitudeUnit::relative_db;
  EXPECT_EQ(version_of(c, "unit"), 3);
  Recording d = r;
  d.sensors[0].range_rate_interval_mps = RangeRateInterval{-1.0, 1.0};
  EXPECT_EQ(version_of(d, "interval"), 3);
  Recording e = r;
  e.objects[1].attributes = {{"frame", 7}};
  EXPECT_EQ(version_of(e, "attributes"), 3);
  // A version 3 file with the defaults written out reads back to a recording written as version 1.
  const Recording back = read_recording(dir_ / "timeline");
  EXPECT_EQ(back.timeline, Timeline::snapshots);
  EXPECT_TRUE(back.ego_motion_known);
  EXPECT_EQ(back.sensors[0].reports, ListLevel::tracks);
  EXPECT_EQ(back.sensors[0].amplitude_unit, AmplitudeUnit::snr_db);
  EXPECT_FALSE(back.sensors[0].range_rate_interval_mps.has_value());
}

// Every bundled recording (version 1) rewritten byte for byte, and a version 2 one too.
TEST_F(RecordingV3, VersionOneAndTwoRecordingsAreRewrittenByteForByte) {
  int rewritten = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kSyntheticRecordings)) {
    if (entry.path().filename() != "recording.json") continue;
    const fs::path dir = entry.path().parent_path();
    const Recording rec = read_recording(dir);
    const fs::path copy = dir_ / fmt::format("copy_{}", rewritten++);
    write_recording(copy, rec);
    for (const char* file : {"recording.json", "ego.csv", "objects.csv", "targets.csv"}) {
      EXPECT_EQ(testing::read_file(dir / file), testing::read_file(copy / file)) << dir << "/" << file;
    }
    EXPECT_EQ(read_recording(copy).checksum, rec.checksum) << dir;
  }
  EXPECT_GE(rewritten, 10);
  write_recording(dir_ / "v2", rec_);
  const std::string v2 = testing::read_file(dir_ / "v2" / "recording.json");
  EXPECT_NE(v2.find("\"version\": 2"), std::string::npos);
  for (const char* field : {"timeline", "ego_motion_known", "amplitude_unit", "range_rate_interval_mps", "attributes"}) {
    EXPECT_EQ(v2.find(field), std::string::npos) << field;
  }
  write_recording(dir_ / "v2b", read_recording(dir_ / "v2"));
  EXPECT_EQ(testing::read_file(dir_ / "v2b" / "recording.json"), v2);
}

TEST_F(RecordingV3, Version3FieldsInVersion1Or2AreRefusedNamingTheField) {
  write_recording(dir_ / "r", v3());
  const fs::path dir = dir_ / "r";
  const std::string v3_text = testing::read_file(dir / "recording.json");
  // Each field alone in a version 2 file: remove the others by writing a version 2 header and
  // adding the one field back.
  write_recording(dir_ / "two", rec_);
  const fs::path two = dir_ / "two";
  const std::string v2_text = testing::read_file(two / "recording.json");
  const auto v2_with = [&](const std::string& from, const std::string& to) { return edited(v2_text, from, to); };
  expect_refused(two, v2_with("\"cycle_time_s\": 1.0,", "\"cycle_time_s\": 1.0, \"timeline\": \"snapshots\","),
                 {"timeline", "version 3 field", "version 2"});
  expect_refused(two, v2_with("\"cycle_time_s\": 1.0,", "\"cycle_time_s\": 1.0, \"ego_motion_known\": true,"),
                 {"ego_motion_known", "version 3 field"});
  expect_refused(two, v2_with("\"reports\": \"detections\"", "\"reports\": \"detections\", \"amplitude_unit\": \"snr_db\""),
                 {"sensors[0].amplitude_unit", "version 3 field"});
  expect_refused(two,
                 v2_with("\"reports\": \"detections\"", "\"reports\": \"detections\", \"range_rate_interval_mps\": [-1, 1]"),
                 {"sensors[0].range_rate_interval_mps", "version 3 field"});
  expect_refused(two, v2_with("\"width_m\": 1.8", "\"width_m\": 1.8, \"attributes\": {}"),
                 {"objects[0].attributes", "version 3 field"});
  // The version 3 file itself declared version 1: the first v3 field named; reports too.
  std::string as_v1 = v3_text;
  as_v1.replace(as_v1.find("\"version\": 3"), 12, "\"version\": 1");
  expect_refused(dir, as_v1, {"timeline", "version 3 field", "version 1"});
  std::string v5 = v3_text;
  v5.replace(v5.find("\"version\": 3"), 12, "\"version\": 6");
  expect_refused(dir, v5, {"version", "versions 1 to 5"});
}

TEST_F(RecordingV3, BadVersion3ValuesAreRefusedNamingTheField) {
  write_recording(dir_ / "r", v3());
  const fs::path dir = dir_ / "r";
  const std::string text = testing::read_file(dir / "recording.json");
  const auto with = [&](const std::string& from, const std::string& to) { return edited(text, from, to); };
  expect_refused(dir, with("\"snapshots\"", "\"frames\""), {"timeline", "\"drive\" or \"snapshots\"", "frames"});
  expect_refused(dir, with("\"ego_motion_known\": false", "\"ego_motion_known\": \"no\""), {"ego_motion_known", "true or false"});
  expect_refused(dir, with("\"relative_db\"", "\"dB\""), {"sensors[0].amplitude_unit", "\"snr_db\" or \"relative_db\""});
  const std::string& header = text;
  const std::regex interval(R"("range_rate_interval_mps": \[[^\]]*\])");
  ASSERT_TRUE(std::regex_search(header, interval)) << header;
  for (const auto& [bad, why] : std::vector<std::pair<std::string, std::string>>{
           {"[1.0, 5.0]", "min < 0 < max"},
           {"[-5.0, -1.0]", "min < 0 < max"},
           {"[5.0, -5.0]", "min < 0 < max"},
           {"[-1500, 1500]", "wider than the limit of 2000 m/s"},
           {"[-1.0]", "[min, max]"},
           {"[-1.0, 1.0, 2.0]", "[min, max]"},
           {"[\"-1\", 1.0]", "[min, max]"},
           {"-1.0", "must be an array"}}) {
    expect_refused(dir, std::regex_replace(header, interval, "\"range_rate_interval_mps\": " + bad),
                   {"sensors[0].range_rate_interval_mps", why});
  }
  const std::string attributes_key = "\"attributes\": {";
  const std::string& attributes = text;
  const auto begin = attributes.find(attributes_key);
  const auto end = attributes.find('}', begin);
  const std::string original = attributes.substr(begin, end - begin + 1);
  for (const auto& [bad, expected] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {R"("attributes": {"a": {"b": 1}})", {"objects[0].attributes.a", "do not nest"}},
           {R"("attributes": {"a": [1, 2]})", {"objects[0].attributes.a", "do not nest"}},
           {R"("attributes": {"a": true})", {"objects[0].attributes.a", "string or a number"}},
           {R"("attributes": {"a": null})", {"objects[0].attributes.a", "string or a number"}},
           {R"("attributes": {"": 1})", {"objects[0].attributes", "1 to 256 bytes"}},
           {R"("attributes": {"a": "x\ny"})", {"objects[0].attributes.a", "newline"}},
           {R"("attributes": {"a": ")" + std::string(257, 'x') + "\"}", {"objects[0].attributes.a", "257 bytes"}},
           {R"("attributes": [1])", {"objects[0].attributes", "object of strings and numbers"}},
           {R"("attributes": "Car")", {"objects[0].attributes", "object of strings and numbers"}}}) {
    expect_refused(dir, with(original, bad), expected);
  }
  std::string many = "\"attributes\": {";
  for (int i = 0; i < 33; ++i) many += fmt::format("{}\"k{}\": {}", i == 0 ? "" : ", ", i, i);
  expect_refused(dir, with(original, many + "}"), {"objects[0].attributes", "33 members exceed the limit of 32"});
  // At the limits: accepted.
  std::string limit = "\"attributes\": {\"s\": \"" + std::string(256, 'x') + "\"";
  for (int i = 0; i < 31; ++i) limit += fmt::format(", \"k{}\": {}", i, i);
  EXPECT_EQ(refusal(dir, with(original, limit + "}")), "");
}

TEST_F(RecordingV3, TheWriterRefusesWhatTheReaderWouldAndWritesNothing) {
  Recording nested = v3();
  nested.objects[0].attributes["deep"] = {{"x", 1}};
  EXPECT_THROW(write_recording(dir_ / "nested", nested), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "nested"));
  Recording interval = v3();
  interval.sensors[0].range_rate_interval_mps = RangeRateInterval{2.0, 1.0};
  EXPECT_THROW(write_recording(dir_ / "interval", interval), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "interval"));
}

// Snapshots keep every check of a drive: a target's time is its cycle's.
TEST_F(RecordingV3, SnapshotsStillNeedEachTargetAtItsCyclesTime) {
  write_recording(dir_ / "r", v3());
  std::ofstream(dir_ / "r" / "targets.csv", std::ios::trunc)
      << "t_s,cycle,sensor,range_m,azimuth_rad,range_rate_mps,amplitude_db\n0.500000,0,radar,10,0,0,50\n";
  try {
    read_recording(dir_ / "r");
    FAIL() << "accepted a target between cycles";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("differs from cycle 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsim
