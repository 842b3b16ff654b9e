// What makes two runs the same run (replay/store/run_identity.hpp): the key, FNV-1a 64 over the
// fields with a separator, by hand; the identity planned from a recording's header is the one its
// replay stores, and another seed or store level another; the labels that tell runs apart, read
// from the stored parameters and sensors; the recording directories in run order.
#include "replay/store/run_identity.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "io/recording_stream.hpp"
#include "model/model_library.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::run_identity_test {

using replay::RunIdentity;
using replay::RunLabel;

// FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3), written out here.
std::uint64_t fnv1a_by_hand(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

TEST(RunIdentity, TheKeyIsFnv1aOverTheFieldsWithASeparator) {
  EXPECT_EQ(fnv1a_by_hand("a"), 0xaf63dc4c8601ec8cULL);  // the published test vector
  RunIdentity id;
  id.recording_checksum = "00000000000000aa";
  id.seed = 7;
  id.store = "full";
  id.sensor_types = "srr24\nsrr24\n";
  id.parameters = R"({"x":1})";
  const std::string fields = std::string("00000000000000aa") + '\0' + "7" + '\0' + "full" + '\0' + "srr24\nsrr24\n" +
                             '\0' + R"({"x":1})";
  EXPECT_EQ(id.key(), fmt::format("{:016x}", fnv1a_by_hand(fields)));
  EXPECT_EQ(id.key().size(), 16u);
  // A character moved from one field to the next is another identity: the separator tells them apart.
  RunIdentity moved = id;
  moved.store = "ful";
  moved.sensor_types = "lsrr24\nsrr24\n";
  EXPECT_NE(moved.key(), id.key());
  RunIdentity other_seed = id;
  other_seed.seed = 8;
  EXPECT_NE(other_seed.key(), id.key());
  EXPECT_NE(other_seed, id);
  EXPECT_EQ(RunIdentity(id).key(), id.key());
}

TEST(RunIdentity, TheLabelsText) {
  RunLabel label;
  label.sensors = "srr24 x2";
  label.fidelity = "no_tracking";
  label.effects = "no clutter";
  label.seed = 4;
  EXPECT_EQ(label.text(), "srr24 x2, fidelity no_tracking, no clutter, no calibration, seed 4");
  label.calibration = "cal/a";
  EXPECT_EQ(label.text(), "srr24 x2, fidelity no_tracking, no clutter, calibration cal/a, seed 4");
  label.calibration_checksum = "0123456789abcdef";  // its first 8 digits
  EXPECT_EQ(label.text(), "srr24 x2, fidelity no_tracking, no clutter, calibration cal/a #01234567, seed 4");
}

class RunIdentityStored : public testing::ScratchDirTest {
 protected:
  RunIdentityStored() : ScratchDirTest("run_identity") {}

  // Replays the bundled recording `name` into the database with this seed and store level.
  void replay_into(replay::ReportDatabase& db, const char* name, std::uint64_t seed, replay::StoreLevel store) {
    replay::ReplayOptions options;
    options.seed = seed;
    replay::ReportWriter writer(db, store);
    replay::replay_recording_dir(testing::kBundledRecordings / name, options, writer);
  }
};

TEST_F(RunIdentityStored, ThePlannedIdentityIsTheStoredOne) {
  const auto db = replay::open_report_database((dir_ / "r.sqlite").string(), true);
  replay_into(*db, "front_approach", 3, replay::StoreLevel::summary);
  const auto stored = replay::stored_run_identities(*db);
  ASSERT_EQ(stored.size(), 1u);
  const RunIdentity& id = stored.at(1);
  const std::filesystem::path dir = testing::kBundledRecordings / "front_approach";
  EXPECT_EQ(id.recording_checksum, fmt::format("{:016x}", recording_checksum(dir)));
  EXPECT_EQ(id.seed, 3);
  EXPECT_EQ(id.store, "summary");
  EXPECT_EQ(id.sensor_types, db->execAndGet("SELECT group_concat(type, char(10)) || char(10) FROM "
                                            "(SELECT type FROM run_sensors WHERE run_id = 1 ORDER BY sensor)")
                                 .getString());
  EXPECT_EQ(id.parameters, db->execAndGet("SELECT parameters FROM runs WHERE run_id = 1").getString());

  const Recording header = read_recording_header(dir);
  replay::ReplayOptions options;
  options.seed = 3;
  const auto planned = [&](const replay::ReplayOptions& o, replay::StoreLevel store) {
    return replay::planned_run_identity(recording_checksum(dir), replay::import_header(header, 0.0, testing::library(), o.import),
                                        o, store);
  };
  EXPECT_EQ(planned(options, replay::StoreLevel::summary), id);
  EXPECT_NE(planned(options, replay::StoreLevel::full), id);
  options.seed = 4;
  EXPECT_NE(planned(options, replay::StoreLevel::summary), id);
  // The rcsim version is not part of it.
  db->exec("UPDATE runs SET rcsim_version = '9.9.9'");
  EXPECT_EQ(replay::stored_run_identities(*db).at(1), id);
}

TEST_F(RunIdentityStored, LabelsFromTheStoredParametersAndSensors) {
  const auto db = replay::open_report_database((dir_ / "r.sqlite").string(), true);
  replay_into(*db, "front_approach", 1, replay::StoreLevel::summary);
  replay_into(*db, "two_in_one_cell", 2, replay::StoreLevel::summary);
  const std::string type = db->execAndGet("SELECT type FROM run_sensors WHERE run_id = 1 AND sensor = 0").getString();
  const int sensors = db->execAndGet("SELECT count(*) FROM run_sensors WHERE run_id = 1").getInt();
  auto labels = replay::read_run_labels(*db);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels.at(1).sensors, sensors == 1 ? type : fmt::format("{} x{}", type, sensors));
  EXPECT_EQ(labels.at(1).fidelity, "full");
  EXPECT_EQ(labels.at(1).effects, "no effects") << "the synthetic recording.json switches every effect off";
  EXPECT_EQ(labels.at(2).seed, 2);
  EXPECT_EQ(labels.at(1).level, db->execAndGet("SELECT level FROM runs WHERE run_id = 1").getString());

  // Effects switched off, a calibration, another fidelity; sensors of two types; parameters that
  // are no JSON read as the defaults.
  db->exec(R"(UPDATE runs SET parameters = '{"fidelity": {"level": "points_only"}, "import": {"calibration": "cal/x", )"
           R"("calibration_checksum": "fedcba9876543210", "effects": {"clutter": false, "multibounce": true, )"
           R"("occlusion": false}}}' WHERE run_id = 1)");
  db->exec("INSERT INTO run_sensors SELECT run_id, 7, 'x', 'other_radar', x_m, y_m, yaw_rad, azimuth_half_rad, "
           "max_range_m, configuration FROM run_sensors WHERE run_id = 1 AND sensor = 0");
  db->exec("UPDATE runs SET parameters = 'not json' WHERE run_id = 2");
  labels = replay::read_run_labels(*db);
  const RunLabel& one = labels.at(1);
  EXPECT_EQ(one.fidelity, "points_only");
  EXPECT_EQ(one.effects, "no clutter, no occlusion");
  EXPECT_EQ(one.calibration, "cal/x");
  EXPECT_EQ(one.calibration_checksum, "fedcba9876543210");
  EXPECT_EQ(one.sensors.substr(one.sensors.size() - 13), ", other_radar") << one.sensors;
  EXPECT_EQ(labels.at(2).fidelity, "full");
  EXPECT_EQ(labels.at(2).effects, "all effects");
  EXPECT_EQ(labels.at(2).calibration, "");
  db->exec(R"(UPDATE runs SET parameters = '{"import": {"effects": {"clutter": false, "multibounce": false, )"
           R"("occlusion": false}}}' WHERE run_id = 2)");
  const auto only = replay::read_run_labels(*db, 2);
  ASSERT_EQ(only.size(), 1u);
  EXPECT_EQ(only.at(2).effects, "no effects");
  EXPECT_TRUE(replay::read_run_labels(*db, 5).empty());
}

TEST_F(RunIdentityStored, RecordingDirectoriesInRunOrderAndNoneWithoutARunsTable) {
  const auto db = replay::open_report_database((dir_ / "r.sqlite").string(), true);
  EXPECT_TRUE(replay::stored_recording_dirs(*db).empty());
  replay_into(*db, "two_in_one_cell", 1, replay::StoreLevel::summary);
  replay_into(*db, "front_approach", 1, replay::StoreLevel::summary);
  const auto dirs = replay::stored_recording_dirs(*db);
  ASSERT_EQ(dirs.size(), 2u);
  EXPECT_EQ(std::filesystem::path(dirs[0]).filename(), "two_in_one_cell");
  EXPECT_EQ(std::filesystem::path(dirs[1]).filename(), "front_approach");
  // A shard's report created but its schema not yet written.
  SQLite::Database bare((dir_ / "bare.sqlite").string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  EXPECT_TRUE(replay::stored_recording_dirs(bare).empty());
}

}  // namespace rcsim::run_identity_test
