// The version 3 -> 4 conversion of a report's row tables into blocks (replay/store/
// report_migration.cpp), on a version 3 database written here row by row with the schema's own
// steps: every cycle's figures and pose bit for bit, the targets' reals at float32, their classes
// by name (a class without its offset dropped), NULL optional columns as NaN, the boxes by cycle,
// each run's GOSPA parameters (the defaults where its parameters are no JSON); and the refusal of
// targets whose cycle has no row.
#include "replay/store/report_migration.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "replay/store/report_schema.hpp"
#include "replay/store/run_rows.hpp"


namespace rcsim::report_migration_test {

using namespace replay;

// A version 3 database in memory with the runs given as (run_id, parameters).
void write_version_3(SQLite::Database& db, const std::vector<std::pair<int, std::string>>& runs) {
  db.exec(kReportSchemaSql);
  db.exec(kBenchSchemaSql);
  db.exec(kRealDriveSchemaSql);
  SQLite::Statement insert(db, "INSERT INTO runs VALUES (?, 'r', '/r', '0000000000000000', '{}', 0.05, 2, 0, "
                               "'detections', ?, '0.0.1', '2026-01-01T00:00:00Z')");
  for (const auto& [run_id, parameters] : runs) {
    insert.bind(1, run_id);
    insert.bind(2, parameters);
    insert.exec();
    insert.reset();
  }
}

// Blocks in place of the rows, as opening an older database converts them.
void convert(SQLite::Database& db) {
  db.exec(kBlockSchemaSql);
  convert_row_tables_to_blocks(db);
  db.exec(kDropRowTablesSql);
}

const char* const kCycle = "INSERT INTO cycles VALUES ";
const char* const kTarget = "INSERT INTO targets VALUES ";

// The reals a target keeps: float32.
double f32(double value) { return static_cast<double>(static_cast<float>(value)); }

TEST(ReportMigration, RowsIntoBlocksAsVersion4ReadsThem) {
  SQLite::Database db(":memory:", SQLite::OPEN_READWRITE);
  write_version_3(db, {{1, R"({"gospa": {"cutoff_m": 5, "order_p": 1}})"}, {2, "not json"}});
  // Run 1: two cycles of two sensors; the second sensor's first cycle stored before v3 figures.
  db.exec(std::string(kCycle) +
          "(1, 0, 0, 0.0, 3.7, 0.7, 0.1, 1, 1, 1, 0.1, 0.2, 0.3, 0.4, 1.0 / 3, 0, 0, 0, 1, 0, 0, 1, 0.5, 0.6), "
          "(1, 0, 1, 0.0, 3.7, -0.7, -0.1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL), "
          "(1, 1, 0, 0.05, 3.75, 0.7, 0.1, 0, 0, 0, 2.5, 0, 0, 2.5, 2.5, 0, 0, 0, 0, 0, 0, 0, 0, 0), "
          "(1, 1, 1, 0.05, 3.75, -0.7, -0.1, 3, 0, 0, 2.5, 0, 2.5, 0, 2.5, 1, 0, 0, 2, 0, 0, 0, 2.5, 2.5), "
          "(2, 0, 0, 0.0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
  db.exec(std::string(kTarget) +
          "(1, 0, 0, 'recorded', 0, 3, 10.1, 0.1, -1.5, 20.3, 0, 0, 0, 0, 0, 'object', 0.5, -0.25, 7.5, NULL, NULL), "
          "(1, 0, 0, 'simulated', 0, NULL, 10.2, 0.12, -1.4, 19.0, 0, 0, NULL, 0, 1, 'background', NULL, NULL, NULL, "
          "12.0, 0.02), "
          "(1, 1, 1, 'recorded', 0, NULL, 30.0, -0.2, 0, 5, 0, 0, 1, NULL, 0, 'object', NULL, NULL, NULL, NULL, NULL), "
          "(1, 1, 1, 'recorded', 1, NULL, 31.0, -0.3, 0, 5, 0, 0, NULL, NULL, 0, 'other', NULL, NULL, NULL, NULL, NULL), "
          "(1, 1, 1, 'recorded', 2, NULL, 32.0, -0.3, 0, 5, 0, 0, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
  db.exec("INSERT INTO run_objects VALUES (1, 0, 'a', 'passenger_car', 4.5, 1.8, 10), "
          "(1, 1, 'b', 'passenger_car', 4.5, 1.8, 10)");
  db.exec("INSERT INTO object_states VALUES (1, 0, 0, 1, 2, 0.1), (1, 0, 1, 5, 6, 0.2), (1, 1, 0, 1.5, 2.5, 0.15)");
  convert(db);

  std::vector<StoredCycle> cycles;
  for_each_cycle(db, 1, {}, [&](const StoredCycle& c) { cycles.push_back(c); });
  ASSERT_EQ(cycles.size(), 4u);
  const StoredCycle& first = cycles[0];
  EXPECT_EQ(first.cycle, 0);
  EXPECT_EQ(first.sensor, 0);
  EXPECT_EQ(first.X_WS->x_m, 3.7);
  EXPECT_EQ(first.X_WS->y_m, 0.7);
  EXPECT_EQ(first.X_WS->yaw_rad, 0.1);
  EXPECT_EQ(first.gospa_m, 0.1);
  EXPECT_EQ(first.gospa_false_mp, 0.4);
  EXPECT_EQ(first.ospa_m, 1.0 / 3) << "bit for bit";
  ASSERT_TRUE(first.classes.has_value());
  EXPECT_EQ(first.classes->n_background_simulated, 1);
  EXPECT_EQ(first.classes->ospa_object_m, 0.6);
  EXPECT_FALSE(cycles[1].classes.has_value()) << "no v3 figures: none";
  EXPECT_EQ(cycles[3].cycle, 1);
  EXPECT_EQ(cycles[3].sensor, 1);
  EXPECT_EQ(cycles[3].t_s, 0.05);
  EXPECT_EQ(cycles[3].n_recorded, 3);
  EXPECT_EQ(cycles[3].merge_recorded, 1);

  std::vector<StoredTarget> targets;
  for_each_target(db, 1, {}, [&](const StoredTarget& t) { targets.push_back(t); });
  ASSERT_EQ(targets.size(), 5u);
  const StoredTarget& object = targets[0];
  EXPECT_FALSE(object.simulated);
  EXPECT_EQ(object.track_id, 3);
  EXPECT_EQ(object.range_m, f32(10.1));
  EXPECT_EQ(object.azimuth_rad, f32(0.1));
  EXPECT_EQ(object.amplitude_db, f32(20.3));
  EXPECT_EQ(object.object, 0);
  EXPECT_EQ(object.match_idx, 0);
  EXPECT_EQ(object.target_class, metrics::TargetClass::object);
  ASSERT_TRUE(object.p_OT_O.has_value());
  EXPECT_EQ(object.p_OT_O->x(), 0.5);
  EXPECT_EQ(object.p_OT_O->y(), -0.25);
  EXPECT_EQ(object.rcs_dbsm, 7.5);
  EXPECT_TRUE(std::isnan(object.snr_db));
  const StoredTarget& background = targets[1];
  EXPECT_TRUE(background.simulated);
  EXPECT_EQ(background.track_id, -1);
  EXPECT_TRUE(background.merge_artefact);
  EXPECT_EQ(background.target_class, metrics::TargetClass::stationary_background);
  EXPECT_TRUE(std::isnan(background.rcs_dbsm));
  EXPECT_EQ(background.elevation_rad, f32(0.02));
  // An object target without its offset keeps its object but not its class.
  EXPECT_EQ(targets[2].object, 1);
  EXPECT_FALSE(targets[2].target_class.has_value());
  EXPECT_FALSE(targets[2].p_OT_O.has_value());
  EXPECT_EQ(targets[3].target_class, metrics::TargetClass::other);
  EXPECT_FALSE(targets[4].target_class.has_value());
  EXPECT_EQ(targets[4].idx, 2);

  std::vector<StoredObjectState> boxes;
  for_each_object_state(db, 1, {}, [&](const StoredObjectState& o) { boxes.push_back(o); });
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[1].cycle, 0);
  EXPECT_EQ(boxes[1].object, 1);
  EXPECT_EQ(boxes[1].X_WO.x_m, 5.0);
  EXPECT_EQ(boxes[2].cycle, 1);
  EXPECT_EQ(boxes[2].X_WO.yaw_rad, 0.15);

  // Each run's GOSPA parameters, c^p / 2 and p: 5 / 2 and 1; the defaults c = 2, p = 2 for run 2.
  EXPECT_EQ(db.execAndGet("SELECT group_concat(DISTINCT half_cutoff_p || ' ' || order_p) FROM cycle_blocks "
                          "WHERE run_id = 1")
                .getString(),
            "2.5 1.0");
  EXPECT_EQ(db.execAndGet("SELECT half_cutoff_p || ' ' || order_p FROM cycle_blocks WHERE run_id = 2").getString(),
            "2.0 2.0");
  EXPECT_EQ(run_store_level(db, 1), StoreLevel::full);
  int run_2_targets = 0;
  for_each_target(db, 2, {}, [&](const StoredTarget&) { ++run_2_targets; });
  EXPECT_EQ(run_2_targets, 0);
}

TEST(ReportMigration, TargetsOfACycleWithoutARowAreRefused) {
  SQLite::Database db(":memory:", SQLite::OPEN_READWRITE);
  write_version_3(db, {{1, "{}"}});
  // Cycles 0 and 1 of sensor 0; a target of sensor 1 in cycle 0, which has no row.
  db.exec(std::string(kCycle) +
          "(1, 0, 0, 0.0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL), "
          "(1, 1, 0, 0.05, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
  db.exec(std::string(kTarget) +
          "(1, 0, 1, 'recorded', 0, NULL, 10, 0, 0, 0, 10, 0, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
  db.exec(kBlockSchemaSql);
  try {
    convert_row_tables_to_blocks(db);
    ADD_FAILURE() << "a target of no cycle was converted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "run 1: targets of cycle 0, sensor 1 have no row in the table cycles");
  }
}

}  // namespace rcsim::report_migration_test
