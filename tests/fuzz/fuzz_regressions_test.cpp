// Every input a fuzz harness crashed on (tests/fuzz/regressions/HARNESS/*), replayed through the
// harness's own entry point (tests/fuzz/*_targets.hpp) in the ordinary build, and so under ASan
// and UBSan in scripts/test.sh's sanitizer build; and the harnesses' base inputs, which must be
// valid (a base the readers refuse would leave the fuzzers testing refusals only). docs/fuzzing.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "fuzz/aimotive_targets.hpp"
#include "fuzz/astyx_targets.hpp"
#include "fuzz/recording_targets.hpp"
#include "fuzz/mcap_targets.hpp"
#include "fuzz/openlabel_targets.hpp"
#include "fuzz/store_targets.hpp"
#include "fuzz/udp_targets.hpp"
#include "fuzz/world_targets.hpp"
#include "replay/import/dataset_importer.hpp"

namespace rcsim::fuzz {
namespace {

namespace fs = std::filesystem;

const std::map<std::string, void (*)(Input)>& entry_points() {
  static const std::map<std::string, void (*)(Input)> entries{
      {"scene", fuzz_scene},         {"object_model", fuzz_object_model}, {"sensor_config", fuzz_sensor_config},
      {"recording", fuzz_recording}, {"calibration", fuzz_calibration},   {"aimotive", fuzz_aimotive},
      {"astyx", fuzz_astyx},         {"mcap", fuzz_mcap},                 {"openlabel", fuzz_openlabel},
      {"udp_datagram", fuzz_udp_datagrams}, {"udp_control", fuzz_udp_control},
      {"report_database", fuzz_report_database}, {"campaign_manifest", fuzz_campaign_manifest}};
  return entries;
}

// Inputs whose fault is known and not fixed yet: the test is skipped, saying why (the input stays
// checked in so that the fix turns it on). Key: "HARNESS/FILE".
const std::map<std::string, std::string>& known_unfixed() {
  static const std::map<std::string, std::string> known{};
  return known;
}

const fs::path kRegressions = fs::path(RCSIM_SOURCE_DIR) / "tests" / "fuzz" / "regressions";

struct RegressionInput {
  std::string harness, file;
};
void PrintTo(const RegressionInput& input, std::ostream* out) { *out << input.harness << "/" << input.file; }

std::vector<RegressionInput> regression_inputs() {
  std::vector<RegressionInput> inputs;
  if (!fs::is_directory(kRegressions)) return inputs;
  for (const auto& harness : fs::directory_iterator(kRegressions)) {
    if (!harness.is_directory()) continue;
    for (const auto& file : fs::directory_iterator(harness.path())) {
      if (file.is_regular_file()) inputs.push_back({harness.path().filename().string(), file.path().filename().string()});
    }
  }
  std::sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) { return a.harness + a.file < b.harness + b.file; });
  return inputs;
}

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzRegression : public ::testing::TestWithParam<RegressionInput> {};

TEST_P(FuzzRegression, RefusedOrAcceptedWithoutCrash) {
  const RegressionInput& input = GetParam();
  const auto entry = entry_points().find(input.harness);
  ASSERT_NE(entry, entry_points().end()) << "tests/fuzz/regressions/" << input.harness << ": no such harness";
  if (const auto known = known_unfixed().find(input.harness + "/" + input.file); known != known_unfixed().end()) {
    GTEST_SKIP() << input.harness << "/" << input.file << ": " << known->second;
  }
  const std::vector<std::uint8_t> bytes = read_bytes(kRegressions / input.harness / input.file);
  EXPECT_NO_THROW(entry->second(bytes)) << input.harness << "/" << input.file;
}

std::string test_name(const ::testing::TestParamInfo<RegressionInput>& info) {
  std::string name = info.param.harness + "_" + info.param.file;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegression, ::testing::ValuesIn(regression_inputs()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FuzzRegression);

TEST(FuzzRegressions, EveryKnownUnfixedInputIsCheckedIn) {
  for (const auto& [key, reason] : known_unfixed()) EXPECT_TRUE(fs::is_regular_file(kRegressions / key)) << key;
}

// ---- the bases are valid, so that the fuzzers start from inputs rcsim accepts ----

TEST(FuzzBases, TheBaseRecordingIsReadAndReplayed) {
  const std::string text = read_source_file("tests/fuzz/base/recording.txt");
  const auto sections = split_sections(text);
  ASSERT_EQ(sections.size(), 4u);
  const fs::path dir = fresh_dir("base_recording");
  write_recording_sections(dir, sections);
  const Recording recording = read_recording(dir);
  EXPECT_EQ(recording.cycle_count(), 12);
  EXPECT_GT(recording.targets.size(), 10u);
  replay::DiscardingSink sink;
  EXPECT_EQ(replay::replay_recording_dir(dir, {}, sink).cycles, 12);
  EXPECT_NO_THROW(fuzz_recording({}));
}

TEST(FuzzBases, TheBaseCalibrationLoads) {
  const std::string text = read_source_file("tests/fuzz/base/calibration.txt");
  const auto sections = split_sections(text);
  ASSERT_EQ(sections.size(), 3u);
  const fs::path dir = fresh_dir("base_calibration");
  const char* files[] = {"calibration.json", "sensor_srr24.json", "model_passenger_car.json"};
  for (std::size_t i = 0; i < 3; ++i) write_file(dir / files[i], sections[i]);
  const auto calibration = replay::load_calibration(dir.string());
  EXPECT_EQ(calibration->sensors.size(), 1u);
  EXPECT_EQ(calibration->models.size(), 1u);
}

TEST(FuzzBases, TheBaseAimotiveSequenceImports) {
  const std::string text = read_source_file("tests/fuzz/base/aimotive.txt");
  EXPECT_EQ(split_sections(text).size(), 2u + 3u * 5u);
  replay::DatasetImportOptions options;
  const fs::path dir = write_aimotive_sequence({}, options);
  EXPECT_TRUE(options.ego_log.empty());
  const Recording recording = import_aimotive_and_read_back(dir, options);
  EXPECT_EQ(recording.cycle_count(), 5);
  EXPECT_EQ(recording.sensors.size(), 2u);
  EXPECT_EQ(recording.objects.size(), 2u);  // the pedestrian has no model: left out
  EXPECT_GT(recording.targets.size(), 50u);
  // With an ego log on the importer's clock (a seed in tests/fuzz/corpus/aimotive/).
  const std::string with_log = read_source_file("tests/fuzz/corpus/aimotive/ego_log");
  const fs::path dir2 = write_aimotive_sequence({reinterpret_cast<const std::uint8_t*>(with_log.data()), with_log.size()}, options);
  EXPECT_FALSE(options.ego_log.empty());
  EXPECT_EQ(import_aimotive_and_read_back(dir2, options).cycle_count(), 5);
}

TEST(FuzzBases, TheSmallScenesRunWithBuiltInFiles) {
  // The scenes the model and sensor harnesses put a fuzzed file into, with a built-in one.
  const ModelLibrary library = ModelLibrary::builtin();
  const struct {
    const char* scene;
    const char* file;
    const char* builtin;
    bool model;
  } cases[] = {{"model_scene.json", "model.json", "passenger_car", true},
               {"model_polyline_scene.json", "model.json", "guard_rail", true},
               {"sensor_scene.json", "sensor.json", "srr24", false}};
  for (const auto& c : cases) {
    const fs::path dir = fresh_dir("base_scene");
    const auto& files = c.model ? embedded_object_models() : embedded_sensor_configs();
    const auto found = std::find_if(files.begin(), files.end(), [&](const EmbeddedFile& f) { return f.name == c.builtin; });
    ASSERT_NE(found, files.end()) << c.builtin;
    write_file(dir / c.file, found->text);
    const std::string text = read_source_file(fs::path("tests/fuzz/base") / c.scene);
    const nlohmann::json json = parse_json_text(text, c.scene);
    const Scene scene = parse_scene(JsonField(json, c.scene, ""), library, dir.string());
    EXPECT_GE(scene.objects.size(), 2u) << c.scene;
    EXPECT_NO_THROW(simulate_a_few_cycles(scene)) << c.scene;
    const std::vector<std::uint8_t> bytes(found->text.begin(), found->text.end());
    EXPECT_NO_THROW((c.model ? fuzz_object_model : fuzz_sensor_config)(bytes)) << c.builtin;
  }
}

TEST(FuzzBases, TheEncodedDatagramSeedsDecodeAndSurviveTheHarness) {
  for (const auto& [name, bytes] : udp_datagram_seeds()) {
    udp::ListenerState listener;
    for (const auto& [source, datagram] : udp::split_datagrams(bytes)) listener.process(datagram, source);
    EXPECT_EQ(listener.malformed, 0u) << name;
    const bool targets = name.find("target") != std::string::npos, truth = name.find("ground_truth") != std::string::npos;
    EXPECT_EQ(!listener.output.empty(), targets) << name;
    EXPECT_EQ(!listener.truth_output.empty(), truth) << name;
  }
  for (const auto& [name, bytes] : udp_control_seeds()) {
    stream::ControlRequest request;
    EXPECT_EQ(stream::decode_control_request(bytes, request), stream::DecodeError::none) << name;
    EXPECT_NO_THROW(fuzz_udp_control(bytes)) << name;
  }
}

TEST(FuzzBases, TheReportDatabaseSeedsRenderAndMerge) {
  const auto seeds = report_database_seeds();
  ASSERT_EQ(seeds.size(), 2u);
  for (const auto& [name, bytes] : seeds) {
    const fs::path dir = fresh_dir("report_seed_check");
    write_file(dir / "report.sqlite", {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
    EXPECT_NO_THROW((void)replay::write_html_report_file((dir / "report.sqlite").string(), (dir / "r.html").string(), {}))
        << name;
    const replay::MergeResult merged = replay::merge_reports({(dir / "report.sqlite").string()}, (dir / "m.sqlite").string());
    EXPECT_EQ(merged.added(), 1) << name;
  }
}

TEST(FuzzBases, TheCampaignManifestSeedsPlan) {
  for (const auto& entry : fs::directory_iterator(fs::path(RCSIM_SOURCE_DIR) / "tests/fuzz/corpus/campaign_manifest")) {
    const std::string text = read_source_file(entry.path());
    std::string script;
    EXPECT_NO_THROW(script = plan_campaign_manifest(text)) << entry.path();
    EXPECT_NE(script.find("#SBATCH --array=0-1"), std::string::npos) << script;
  }
}

// The seed log imports: 10 radar cycles at 20 Hz, 3 returns each, the ego at 10 Hz, one car; the
// seed with another schema on the radar's topic is refused naming it.
TEST(FuzzBases, TheMcapSeedsImportOrAreRefusedByName) {
  const auto seeds = mcap_seeds();
  ASSERT_EQ(seeds.size(), 4u);
  const fs::path dir = fresh_dir("mcap_seed");
  write_file(dir / "mapping.json", kMcapMapping);
  replay::DatasetImportOptions options;
  options.mapping = dir / "mapping.json";
  write_file(dir / "drive.mcap", {reinterpret_cast<const char*>(seeds[0].second.data()), seeds[0].second.size()});
  const Recording rec = replay::import_mcap(dir / "drive.mcap", options).recording;
  EXPECT_EQ(rec.cycle_count(), 10);
  EXPECT_EQ(rec.targets.size(), 30u);
  EXPECT_EQ(rec.ego.size(), 5u);
  ASSERT_EQ(rec.objects.size(), 1u);
  EXPECT_NEAR(rec.sensors[0].cycle_time_s, 0.05, 1e-9);
  // No speed_mps in the seed: the parked car's speed from its positions, 0 everywhere.
  ASSERT_EQ(rec.boxes[0].size(), 5u);
  for (const AnnotatedBox& b : rec.boxes[0]) EXPECT_NEAR(b.speed_mps, 0.0, 1e-12);
  write_file(dir / "wrong.mcap", {reinterpret_cast<const char*>(seeds[1].second.data()), seeds[1].second.size()});
  try {
    replay::import_mcap(dir / "wrong.mcap", options);
    ADD_FAILURE() << "another schema on the radar's topic was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("schema 'sensor_msgs/msg/Imu'"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(fuzz_mcap(Input(seeds[0].second.data(), seeds[0].second.size())));
  // The point-cloud seed: the same 30 returns; the middle point of the first cycle 16.3 m ahead.
  write_file(dir / "cloud.mcap", {reinterpret_cast<const char*>(seeds[2].second.data()), seeds[2].second.size()});
  const Recording clouds = replay::import_mcap(dir / "cloud.mcap", options).recording;
  EXPECT_EQ(clouds.targets.size(), 30u);
  EXPECT_NEAR(clouds.targets[1].range_m, 20.0 - 3.7, 1e-5);
  EXPECT_NEAR(clouds.targets[1].azimuth_rad, 0.0, 1e-7);
  // The PointCloud2 seed: the same points, hand-laid CDR.
  write_file(dir / "cloud2.mcap", {reinterpret_cast<const char*>(seeds[3].second.data()), seeds[3].second.size()});
  const Recording clouds2 = replay::import_mcap(dir / "cloud2.mcap", options).recording;
  ASSERT_EQ(clouds2.targets.size(), 30u);
  for (std::size_t i = 0; i < 30; ++i) EXPECT_EQ(clouds2.targets[i].range_m, clouds.targets[i].range_m) << i;
}

// The OpenLABEL seed reads: car1 in frames 0 and 1 (its val null in frame 2), the truck's static
// cuboid in frames 0 and 2; each timestamp form to the nanosecond.
TEST(FuzzBases, TheOpenLabelSeedReads) {
  const auto seeds = openlabel_seeds();
  ASSERT_EQ(seeds.size(), 1u);
  const fs::path dir = fresh_dir("openlabel_seed");
  write_file(dir / "labels.json", {reinterpret_cast<const char*>(seeds[0].second.data()), seeds[0].second.size()});
  const replay::openlabel::Labels labels = replay::openlabel::read_openlabel(dir / "labels.json");
  ASSERT_EQ(labels.boxes.size(), 4u);
  EXPECT_EQ(labels.boxes[0].uid, "car1");
  EXPECT_EQ(labels.boxes[0].t_ns, 1'700'000'000'050'000'000LL);
  EXPECT_EQ(labels.boxes[0].speed_mps, 13.9);
  EXPECT_EQ(labels.boxes[1].uid, "truck");
  EXPECT_EQ(labels.boxes[1].coordinate_system, "base_link");
  EXPECT_EQ(labels.boxes[1].speed_mps, 20.5);
  EXPECT_EQ(labels.boxes[2].t_ns, 1'700'000'000'150'000'001LL);
  EXPECT_NEAR(labels.boxes[2].yaw_rad, 0.5, 1e-12);  // the Euler cuboid's rz
  EXPECT_EQ(labels.boxes[3].uid, "truck");
  EXPECT_EQ(labels.boxes[3].t_ns, 1'700'000'000'250'000'000LL);  // 2023-11-14T22:13:20.250Z
  EXPECT_NO_THROW(fuzz_openlabel(Input(seeds[0].second.data(), seeds[0].second.size())));
}

TEST(FuzzSupport, SectionsSplitOnTheSeparatorLine) {
  EXPECT_EQ(split_sections("a").size(), 1u);
  const auto s = split_sections("a\n=====\n\n=====\nc");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0], "a");
  EXPECT_EQ(s[1], "");
  EXPECT_EQ(s[2], "c");
  EXPECT_TRUE(is_library_message("vector::_M_range_check: __n (which is 3) >= this->size() (which is 3)"));
  EXPECT_TRUE(is_library_message("stod"));
  EXPECT_FALSE(is_library_message("unknown sensor type \"a::b\""));
}

}  // namespace
}  // namespace rcsim::fuzz
