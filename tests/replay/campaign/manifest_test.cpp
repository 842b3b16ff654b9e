// A campaign manifest (replay/campaign/manifest.hpp): recordings found relative to the manifest,
// sorted and each once; the replay member field by field and its defaults; every refusal naming
// the file and the field.
#include "replay/campaign/manifest.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "replay/campaign/manifest_fixtures.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay::campaign::manifest_test {

namespace fs = std::filesystem;

class CampaignManifestTest : public rcsim::testing::ManifestFileTest {
 protected:
  CampaignManifestTest() : ManifestFileTest("campaign_manifest") {}
  // The replay member `text` parsed against dir_, or its refusal.
  std::string replay_error_of(const std::string& text) {
    const nlohmann::json json = nlohmann::json::parse(text);
    try {
      parse_campaign_replay(JsonField(json, "m.json", "replay"), dir_);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  // A directory that counts as a recording: it holds recording.json (read_manifest reads no further).
  void make_recording_dir(const fs::path& dir) {
    fs::create_directories(dir);
    std::ofstream(dir / "recording.json") << "{}";
  }
};

// Moved from tests/replay/campaign/plan_test.cpp (PlanTest): it tests read_manifest alone.
TEST_F(CampaignManifestTest, BadManifestsNameTheFileAndField) {
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "no_such_*").string() + R"("])").find("recordings[0]: "),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "no_such_*").string() + R"("])").find("matches no recording"),
            std::string::npos);
  // Under a directory that does not exist; a relative pattern says what it is relative to.
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "no_such_dir" / "*").string() + R"("])").find("a directory in it is missing"),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": ["no_such_*"])").find("relative to the manifest's directory " + dir_.string()),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [")" + testing::kBundledRecordings.string() + R"("])").find("not a recording directory"),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "front_approach").string() + R"("], "replay": {"sead": 1})").find("sead"), std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "front_approach").string() +
                     R"("], "replay": {"fidelity": "best"})")
                .find("unknown fidelity level 'best'"),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [")" + (testing::kBundledRecordings / "front_approach").string() +
                     R"("], "slurm": {"extra": ["qos=x"]})")
                .find("slurm.extra[0]"),
            std::string::npos);
  EXPECT_NE(error_of(R"("recordings": [])").find("names no recording"), std::string::npos);
  EXPECT_NE(error_of(R"("recordings": ["x"])").find("campaign.json"), std::string::npos);
}

TEST_F(CampaignManifestTest, RecordingsAreFoundRelativeToTheManifestSortedAndEachOnce) {
  make_recording_dir(dir_ / "recs" / "b");
  make_recording_dir(dir_ / "recs" / "a");
  fs::create_directories(dir_ / "recs" / "c_empty");  // matched by the glob, but no recording: left out
  fs::create_directories(dir_ / "sub");
  const fs::path path = dir_ / "sub" / "campaign.json";
  // b by the glob, by a relative path with a detour and by its absolute path; a by the glob: each once, a first.
  std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "dedup", "recordings": ["../recs/*", "../recs/a/../b", ")"
                      << (dir_ / "recs" / "b").string() << R"("], "slurm": {"partition": "cpu", "memory": "4G"}})";
  const CampaignManifest m = read_manifest(path);
  EXPECT_EQ(m.file, path);
  EXPECT_EQ(m.name, "dedup");
  ASSERT_EQ(m.recordings.size(), 2u);
  EXPECT_EQ(m.recordings[0], dir_ / "recs" / "a");
  EXPECT_EQ(m.recordings[1], dir_ / "recs" / "b");
  EXPECT_TRUE(m.criteria.empty());
  EXPECT_EQ(m.slurm.partition, "cpu");
  EXPECT_EQ(m.slurm.memory, "4G");
  EXPECT_EQ(m.slurm.account, "");
  EXPECT_TRUE(m.slurm.extra.empty());
  EXPECT_EQ(m.document.at("name"), "dedup");
  // Without a replay member: the defaults, and each recording's fidelity from what its sensors report.
  EXPECT_FALSE(m.replay.fidelity.has_value());
  EXPECT_EQ(m.replay.store, StoreLevel::summary);
  Recording detections;
  detections.sensors.push_back({"s", "srr24", 0.0, 0.0, 0.0, ListLevel::detections});
  Recording tracks = detections;
  tracks.sensors[0].reports = ListLevel::tracks;
  EXPECT_EQ(m.replay.options_for(detections).fidelity, Fidelity::no_tracking);
  EXPECT_EQ(m.replay.options_for(tracks).fidelity, Fidelity::full);
}

TEST_F(CampaignManifestTest, TheReplayMemberFieldByField) {
  fs::create_directories(dir_ / "cal");
  const nlohmann::json json = nlohmann::json::parse(R"({"seed": 9007199254740992, "fidelity": "points_only", "store": "full",
      "calibration": "cal/../cal", "sensor": "sensors/mine.json", "effects": {"clutter": true}, "gospa_cutoff_m": 5,
      "gospa_order": 1, "gate_m": 2.5, "stationary_gate_mps": 0.25, "smooth_half_window_s": 0, "max_gap_s": 1.5})");
  const CampaignReplay r = parse_campaign_replay(JsonField(json, "m.json", "replay"), dir_);
  EXPECT_EQ(r.options.seed, 9007199254740992u);  // 2^53, the largest seed JSON holds exactly
  ASSERT_TRUE(r.fidelity.has_value());
  EXPECT_EQ(*r.fidelity, Fidelity::points_only);
  EXPECT_EQ(r.store, StoreLevel::full);
  EXPECT_EQ(r.options.import.calibration_dir, (dir_ / "cal").string());  // absolute, normalised
  EXPECT_EQ(r.options.import.sensor_type_override, (dir_ / "sensors" / "mine.json").string());
  // The effects as given, the rest off, and no longer the recording's own.
  EXPECT_TRUE(r.options.import.effects.clutter);
  EXPECT_FALSE(r.options.import.effects.multibounce);
  EXPECT_FALSE(r.options.import.effects.occlusion);
  EXPECT_FALSE(r.options.import.effects_from_recording);
  EXPECT_DOUBLE_EQ(r.options.gospa.cutoff_m, 5.0);
  EXPECT_DOUBLE_EQ(r.options.gospa.order_p, 1.0);
  EXPECT_DOUBLE_EQ(r.options.association_gate_m, 2.5);
  EXPECT_DOUBLE_EQ(r.options.stationary_gate_mps, 0.25);
  EXPECT_DOUBLE_EQ(r.options.import.smoothing_half_window_s, 0.0);
  EXPECT_DOUBLE_EQ(r.options.import.max_gap_s, 1.5);
  // A given fidelity holds whatever the recording reports.
  Recording detections;
  detections.sensors.push_back({"s", "srr24", 0.0, 0.0, 0.0, ListLevel::detections});
  EXPECT_EQ(r.options_for(detections).fidelity, Fidelity::points_only);
  // A sensor without '/' or ".json" is a built-in name, kept as it is.
  const nlohmann::json builtin = nlohmann::json::parse(R"({"sensor": "srr24"})");
  EXPECT_EQ(parse_campaign_replay(JsonField(builtin, "m.json", "replay"), dir_).options.import.sensor_type_override, "srr24");
}

TEST_F(CampaignManifestTest, TheReplayMembersRefusalsNameTheField) {
  EXPECT_EQ(replay_error_of(R"({"seed": 1.5})"), "m.json: replay.seed: expected a whole number");
  EXPECT_EQ(replay_error_of(R"({"store": "none"})"), "m.json: replay.store: 'none' is neither full nor summary");
  EXPECT_EQ(replay_error_of(R"({"gospa_order": 0.5})"), "m.json: replay.gospa_order: expected at least 1");
  EXPECT_EQ(replay_error_of(R"({"gate_m": 0})"), "m.json: replay.gate_m: expected a positive number");
  EXPECT_EQ(replay_error_of(R"({"calibration": "nowhere"})"),
            "m.json: replay.calibration: no such directory: " + (dir_ / "nowhere").string());
  EXPECT_NE(replay_error_of(R"({"fidelity": "best"})").find("one of full | no_monopulse | points_only | no_tracking"),
            std::string::npos);
  EXPECT_NE(replay_error_of(R"({"effects": {"glare": true}})").find("m.json: replay.effects"), std::string::npos);
  EXPECT_NE(replay_error_of(R"({"seed": -1})").find("m.json: replay.seed"), std::string::npos);
}

}  // namespace rcsim::replay::campaign::manifest_test
