// The report database (replay/store/report_store.hpp): a run is one transaction, so a run that
// fails midway leaves the earlier runs as they were; a database of another program is refused;
// older versions are migrated, a version 3 run's rows into the v4 blocks bit for bit (the targets'
// reals at float32), and the targets per range bin (v6) of the runs stored before are not known;
// a run's bins add up to its per-object targets.
#include "replay/store/report_store.hpp"

#include <SQLiteCpp/VariadicBind.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_migration.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/report_schema.hpp"
#include "replay/store/run_rows.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {

namespace {

// An empty report database as version 1, 2 or 3 of rcsim made it.
void write_old_schema(SQLite::Database& db, int version) {
  db.exec(kReportSchemaSql);
  if (version >= 2) db.exec(kBenchSchemaSql);
  if (version >= 3) db.exec(kRealDriveSchemaSql);
  db.exec(fmt::format("PRAGMA application_id = {}", kReportApplicationId));
  db.exec(fmt::format("PRAGMA user_version = {}", version));
}

// A report database as version 1 to 5 of rcsim wrote it, with one run of one cycle and target
// stored (from version 3 with its real-drive columns and one object's figures, overall and in one
// range bin, without the targets per bin of version 6; from version 4 in blocks, converted as
// version 4 converted them).
void write_old_database(const std::string& path, int version) {
  SQLite::Database db(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  write_old_schema(db, std::min(version, 3));
  db.exec("INSERT INTO runs VALUES (1, 'old', '/x', '0000000000000000', '{}', 0.04, 1, 0, 'tracks', '{}', '0.0.1', "
          "'2026-01-01T00:00:00Z')");
  db.exec("INSERT INTO cycles (run_id, cycle, sensor, t_s, sensor_x_m, sensor_y_m, sensor_yaw_rad, n_recorded, "
          "n_simulated, n_assigned, gospa_m, gospa_localisation_mp, gospa_missed_mp, gospa_false_mp, ospa_m, "
          "merge_recorded, merge_simulated, merge_matched) VALUES (1, 0, 0, 0.0, 3.7, 0, 0, 1, 0, 0, 1.414, 0, 2, 0, 2, 0, 0, 0)");
  db.exec("INSERT INTO targets (run_id, cycle, sensor, origin, idx, track_id, range_m, azimuth_rad, range_rate_mps, "
          "amplitude_db, x_s_m, y_s_m, object, match_idx, merge_artefact) "
          "VALUES (1, 0, 0, 'recorded', 0, NULL, 10, 0, -1, 20, 10, 0, NULL, NULL, 0)");
  if (version >= 3) {
    db.exec("UPDATE cycles SET n_object_recorded = 0, n_object_simulated = 0, n_background_recorded = 1, "
            "n_background_simulated = 0, gospa_object_m = 0, ospa_object_m = 0");
    db.exec("UPDATE targets SET target_class = 'background', rcs_dbsm = 7.5");
    db.exec("INSERT INTO object_figures VALUES (1, 0, 0, 1, 0, 0, 0, 0)");
    db.exec("INSERT INTO object_ranges VALUES (1, 0, 0, 20.0, 30.0, 1, 0, 0)");
  }
  if (version >= 4) {
    db.exec(kBlockSchemaSql);
    convert_row_tables_to_blocks(db);
    db.exec(kDropRowTablesSql);
  }
  if (version >= 5) db.exec(kCampaignSchemaSql);
  db.exec(fmt::format("PRAGMA user_version = {}", version));
}

// The logical rows of a run (run_rows.hpp), every real with 17 digits.
std::string rows_of_run(SQLite::Database& db, std::int64_t run_id) {
  std::string text;
  for_each_cycle(db, run_id, {}, [&](const StoredCycle& c) {
    text += fmt::format("c {} {} {:.17g} {:.17g} {:.17g} {:.17g} {} {} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {} {} {}",
                        c.cycle, c.sensor, c.t_s, c.X_WS->x_m, c.X_WS->y_m, c.X_WS->yaw_rad, c.n_recorded, c.n_simulated,
                        c.n_assigned, c.gospa_m, c.gospa_localisation_mp, c.gospa_missed_mp, c.gospa_false_mp, c.ospa_m,
                        c.merge_recorded, c.merge_simulated, c.merge_matched);
    if (c.classes) {
      text += fmt::format(" {} {} {} {} {:.17g} {:.17g}", c.classes->n_object_recorded, c.classes->n_object_simulated,
                          c.classes->n_background_recorded, c.classes->n_background_simulated,
                          c.classes->gospa_object_m, c.classes->ospa_object_m);
    }
    text += '\n';
  });
  for_each_target(db, run_id, {}, [&](const StoredTarget& t) {
    text += fmt::format("t {} {} {} {} {} {:.17g} {:.17g} {:.17g} {:.17g} {} {} {} {} {:.17g} {:.17g} {:.17g}", t.cycle,
                        t.sensor, t.simulated, t.idx, t.track_id, t.range_m, t.azimuth_rad, t.range_rate_mps,
                        t.amplitude_db, t.object, t.match_idx, t.merge_artefact,
                        t.target_class ? static_cast<int>(*t.target_class) : -1, t.rcs_dbsm, t.snr_db, t.elevation_rad);
    if (t.p_OT_O) text += fmt::format(" {:.17g} {:.17g}", t.p_OT_O->x(), t.p_OT_O->y());
    text += '\n';
  });
  for_each_object_state(db, run_id, {}, [&](const StoredObjectState& o) {
    text += fmt::format("o {} {} {:.17g} {:.17g} {:.17g}\n", o.cycle, o.object, o.X_WO.x_m, o.X_WO.y_m, o.X_WO.yaw_rad);
  });
  return text;
}

// Version 3's rows of every run of `from`, written into `to` (made by write_old_schema) as
// version 3 stored them.
void write_as_version_3(SQLite::Database& from, SQLite::Database& to) {
  SQLite::Transaction transaction(to);
  SQLite::Statement runs(from, "SELECT run_id FROM runs ORDER BY run_id");
  SQLite::Statement cycle(to, "INSERT INTO cycles VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  SQLite::Statement target(to, "INSERT INTO targets VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  SQLite::Statement state(to, "INSERT INTO object_states VALUES (?, ?, ?, ?, ?, ?)");
  const auto bind_or_null = [](SQLite::Statement& s, int index, double value, bool present) {
    if (present) s.bind(index, value); else s.bind(index);
  };
  const auto bind_index = [](SQLite::Statement& s, int index, int value) {
    if (value >= 0) s.bind(index, value); else s.bind(index);
  };
  while (runs.executeStep()) {
    const std::int64_t run_id = runs.getColumn(0).getInt64();
    for_each_cycle(from, run_id, {}, [&](const StoredCycle& c) {
      SQLite::bind(cycle, run_id, c.cycle, c.sensor, c.t_s, c.X_WS->x_m, c.X_WS->y_m, c.X_WS->yaw_rad, c.n_recorded,
                   c.n_simulated, c.n_assigned, c.gospa_m, c.gospa_localisation_mp, c.gospa_missed_mp, c.gospa_false_mp,
                   c.ospa_m, c.merge_recorded, c.merge_simulated, c.merge_matched, c.classes->n_object_recorded,
                   c.classes->n_object_simulated, c.classes->n_background_recorded, c.classes->n_background_simulated,
                   c.classes->gospa_object_m, c.classes->ospa_object_m);
      cycle.exec();
      cycle.reset();
    });
    for_each_target(from, run_id, {}, [&](const StoredTarget& t) {
      const Vec2 p_ST_S = t.p_ST_S();
      SQLite::bind(target, run_id, t.cycle, t.sensor, t.simulated ? "simulated" : "recorded", t.idx);
      bind_index(target, 6, t.track_id);
      target.bind(7, t.range_m);
      target.bind(8, t.azimuth_rad);
      target.bind(9, t.range_rate_mps);
      target.bind(10, t.amplitude_db);
      target.bind(11, p_ST_S.x());
      target.bind(12, p_ST_S.y());
      bind_index(target, 13, t.object);
      bind_index(target, 14, t.match_idx);
      target.bind(15, t.merge_artefact ? 1 : 0);
      target.bind(16, std::string(metrics::target_class_name(*t.target_class)));
      bind_or_null(target, 17, t.p_OT_O ? t.p_OT_O->x() : 0.0, t.p_OT_O.has_value());
      bind_or_null(target, 18, t.p_OT_O ? t.p_OT_O->y() : 0.0, t.p_OT_O.has_value());
      bind_or_null(target, 19, t.rcs_dbsm, !std::isnan(t.rcs_dbsm));
      bind_or_null(target, 20, t.snr_db, !std::isnan(t.snr_db));
      bind_or_null(target, 21, t.elevation_rad, !std::isnan(t.elevation_rad));
      target.exec();
      target.reset();
    });
    for_each_object_state(from, run_id, {}, [&](const StoredObjectState& o) {
      SQLite::bind(state, run_id, o.cycle, o.object, o.X_WO.x_m, o.X_WO.y_m, o.X_WO.yaw_rad);
      state.exec();
      state.reset();
    });
  }
  transaction.commit();
}

// Each table's columns as (name, type, not null), in order.
std::string table_layout(SQLite::Database& db) {
  std::string text;
  SQLite::Statement tables(db, "SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  while (tables.executeStep()) {
    const std::string table = tables.getColumn(0).getString();
    SQLite::Statement info(db, "PRAGMA table_info(" + table + ")");
    text += fmt::format("{}:", table);
    while (info.executeStep()) {
      text += fmt::format(" {} {}{},", info.getColumn(1).getString(), info.getColumn(2).getString(),
                          info.getColumn(3).getInt() ? " NOT NULL" : "");
    }
    text += '\n';
  }
  return text;
}

class ReportStore : public testing::ScratchDirTest {
 protected:
  ReportStore() : ScratchDirTest("report_store") {}

  Recording write_and_read(const Recording& rec, const std::string& name) { return testing::write_and_read(rec, dir_ / name); }
};

TEST_F(ReportStore, FailedRunLeavesEarlierRunsIntact) {
  const Scene scene = testing::two_cars_scene(1.0);
  const Recording rec = write_and_read(testing::model_recording(scene, 1), "a");
  const auto path = (dir_ / "r.sqlite").string();
  ReplayOptions options;
  options.import.effects = {};
  {
    const auto db = open_report_database(path, true);
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
  }
  // A sink that fails midway, like a replay that meets a full disk.
  struct Failing final : ReplaySink {
    explicit Failing(SQLite::Database& db) : inner(db) {}
    void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions& o) override {
      inner.begin_run(r, i, s, o);
    }
    void add_cycle(const CycleComparison& c) override {
      if (++cycles == 10) throw std::runtime_error("disk full");
      inner.add_cycle(c);
    }
    void end_run(const ReplaySummary& s) override { inner.end_run(s); }
    ReportWriter inner;
    int cycles = 0;
  };
  {
    const auto db = open_report_database(path, true);
    Failing failing(*db);
    EXPECT_THROW(replay_recording(rec, options, failing), std::runtime_error);
  }
  const auto db = open_report_database(path, false);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(DISTINCT run_id) FROM cycle_blocks").getInt(), 1);
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM summaries").getInt(), 1);
  EXPECT_EQ(db->execAndGet("PRAGMA integrity_check").getString(), "ok");
}

// Versions 1 to 5 are migrated in place to the current one: the same tables and columns, in the
// same order, as a database made new; the runs kept, their new columns NULL and their store full,
// their rows in blocks, their targets per range bin not known (NULL, never 0); a new run then
// stores, with its targets per range bin.
TEST_F(ReportStore, OlderVersionsMigrateToTheLayoutOfANewDatabase) {
  const auto fresh = open_report_database((dir_ / "new.sqlite").string(), true);
  for (const int version : {1, 2, 3, 4, 5}) {
    const std::string path = (dir_ / ("v" + std::to_string(version) + ".sqlite")).string();
    write_old_database(path, version);
    const auto db = open_report_database(path, false);
    EXPECT_EQ(db->execAndGet("PRAGMA user_version").getInt(), kReportSchemaVersion);
    EXPECT_EQ(table_layout(*db), table_layout(*fresh)) << "from version " << version;
    EXPECT_EQ(run_store_level(*db, 1), StoreLevel::full);
    std::vector<StoredTarget> targets;
    for_each_target(*db, 1, {}, [&](const StoredTarget& t) { targets.push_back(t); });
    ASSERT_EQ(targets.size(), 1u);
    EXPECT_EQ(targets[0].range_m, 10.0);
    EXPECT_EQ(targets[0].amplitude_db, 20.0);
    std::vector<StoredCycle> cycles;
    for_each_cycle(*db, 1, {}, [&](const StoredCycle& c) { cycles.push_back(c); });
    ASSERT_EQ(cycles.size(), 1u);
    EXPECT_EQ(cycles[0].gospa_m, 1.414);
    EXPECT_EQ(cycles[0].gospa_missed_mp, 2.0);
    EXPECT_EQ(cycles[0].X_WS->x_m, 3.7);
    if (version < 3) {
      EXPECT_FALSE(targets[0].target_class.has_value());
      EXPECT_FALSE(cycles[0].classes.has_value());
    } else {
      EXPECT_EQ(targets[0].target_class, metrics::TargetClass::stationary_background);
      EXPECT_EQ(targets[0].rcs_dbsm, 7.5);
      ASSERT_TRUE(cycles[0].classes.has_value());
      EXPECT_EQ(cycles[0].classes->n_background_recorded, 1);
      // The bin stored before v6 keeps its cycles; its targets are not known.
      EXPECT_EQ(db->execAndGet("SELECT count(*) FROM object_ranges WHERE run_id = 1 AND targets_recorded IS NULL "
                               "AND targets_simulated IS NULL AND cycles_in_view = 1")
                    .getInt(),
                1);
      const report::RunData old_run = report::load_run(*db, 1);
      ASSERT_EQ(old_run.object_ranges.size(), 1u);
      EXPECT_EQ(old_run.object_ranges[0].cycles_in_view, 1);
      EXPECT_FALSE(old_run.object_ranges[0].targets_recorded.has_value());
      EXPECT_FALSE(old_run.object_ranges[0].targets_simulated.has_value());
    }

    const Recording rec = write_and_read(testing::model_recording(testing::two_cars_scene(1.0), 1),
                                         "rec" + std::to_string(version));
    ReplayOptions options;
    options.import.effects = {};
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
    EXPECT_EQ(db->execAndGet("SELECT count(*) FROM runs").getInt(), 2);
    int unclassed = 0, stored = 0;
    for_each_target(*db, 2, {}, [&](const StoredTarget& t) { ++stored, unclassed += !t.target_class.has_value(); });
    EXPECT_GT(stored, 0);
    EXPECT_EQ(unclassed, 0);
    EXPECT_GT(db->execAndGet("SELECT count(*) FROM object_figures WHERE run_id = 2").getInt(), 0);
    EXPECT_EQ(db->execAndGet("SELECT count(*) FROM object_ranges WHERE run_id = 2 AND targets_recorded IS NULL").getInt(),
              0);
    EXPECT_EQ(db->execAndGet("PRAGMA integrity_check").getString(), "ok");
  }
}

// A stored run's range bins add up, per sensor and object, to its object_figures row: cycles in
// view, cycles detected and targets, recorded and simulated; and read back as stored.
TEST_F(ReportStore, TheTargetsPerRangeBinAddUpToThoseOfTheObject) {
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReplayOptions options;
  options.import.effects = {};
  options.object_range_bin_m = 5.0;
  const Recording rec = write_and_read(testing::model_recording(testing::two_cars_scene(6.0), 3), "rec");
  ReportWriter writer(*db);
  replay_recording(rec, options, writer);
  EXPECT_GT(db->execAndGet("SELECT count(*) FROM object_figures WHERE targets_recorded > 0").getInt(), 0);
  EXPECT_GT(db->execAndGet("SELECT count(*) FROM object_ranges").getInt(),
            db->execAndGet("SELECT count(*) FROM object_figures").getInt())
      << "the cars cross bins";
  EXPECT_EQ(db->execAndGet("SELECT count(*) FROM object_figures f JOIN (SELECT run_id, sensor, object, "
                           "sum(cycles_in_view) AS v, sum(cycles_detected_recorded) AS dr, "
                           "sum(cycles_detected_simulated) AS ds, sum(targets_recorded) AS tr, "
                           "sum(targets_simulated) AS ts FROM object_ranges GROUP BY run_id, sensor, object) r "
                           "USING (run_id, sensor, object) WHERE f.cycles_in_view = r.v AND "
                           "f.cycles_detected_recorded = r.dr AND f.cycles_detected_simulated = r.ds AND "
                           "f.targets_recorded = r.tr AND f.targets_simulated = r.ts")
                .getInt(),
            db->execAndGet("SELECT count(*) FROM object_figures").getInt());
  const report::RunData run = report::load_run(*db, 1);
  std::int64_t recorded = 0, simulated = 0;
  for (const report::ObjectRangeBin& b : run.object_ranges) {
    ASSERT_TRUE(b.targets_recorded && b.targets_simulated);
    recorded += *b.targets_recorded;
    simulated += *b.targets_simulated;
  }
  std::int64_t object_recorded = 0, object_simulated = 0;
  for (const report::ObjectFigures& f : run.object_figures) {
    object_recorded += f.targets_recorded;
    object_simulated += f.targets_simulated;
  }
  EXPECT_EQ(recorded, object_recorded);
  EXPECT_EQ(simulated, object_simulated);
  EXPECT_GT(recorded, 0);
}

// A version 3 database of real runs (written here as version 3 wrote them, from the rows of a
// new one) reads back after its migration exactly as the new database does: every cycle's figures
// and pose, every box bit for bit, every target at float32.
TEST_F(ReportStore, AVersion3DatabaseReadsBackAsANewOne) {
  const std::string new_path = (dir_ / "new.sqlite").string(), old_path = (dir_ / "v3.sqlite").string();
  const auto fresh = open_report_database(new_path, true);
  ReplayOptions options;
  options.import.effects = {};
  for (int seed = 1; seed <= 2; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    const Recording rec = write_and_read(testing::model_recording(testing::two_cars_scene(6.0), 3), "rec" + std::to_string(seed));
    ReportWriter writer(*fresh);
    replay_recording(rec, options, writer);
  }
  {
    SQLite::Database old(old_path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    write_old_schema(old, 3);
    old.exec("ATTACH DATABASE '" + new_path + "' AS fresh");
    old.exec("INSERT INTO runs SELECT run_id, recording_name, recording_dir, recording_checksum, recording_source, "
             "cycle_time_s, cycles, seed, level, parameters, rcsim_version, created_utc FROM fresh.runs");
    for (const char* table : {"run_sensors", "run_objects", "merge_pairs", "latencies", "distribution_distances",
                              "summaries", "object_figures"}) {
      old.exec(fmt::format("INSERT INTO {0} SELECT * FROM fresh.{0}", table));
    }
    old.exec("INSERT INTO object_ranges SELECT run_id, sensor, object, range_from_m, range_to_m, cycles_in_view, "
             "cycles_detected_recorded, cycles_detected_simulated FROM fresh.object_ranges");
    old.exec("DETACH DATABASE fresh");
    write_as_version_3(*fresh, old);
  }
  const auto migrated = open_report_database(old_path, false);
  EXPECT_EQ(migrated->execAndGet("PRAGMA user_version").getInt(), kReportSchemaVersion);
  EXPECT_EQ(table_layout(*migrated), table_layout(*fresh));
  for (const std::int64_t run_id : {1, 2}) {
    const std::string rows = rows_of_run(*fresh, run_id);
    EXPECT_GT(rows.size(), 10'000u);
    EXPECT_EQ(rows_of_run(*migrated, run_id), rows) << "run " << run_id;
  }
  EXPECT_EQ(migrated->execAndGet("PRAGMA integrity_check").getString(), "ok");
}

// A version 3 database whose targets have no cycle cannot be migrated: refused, naming the file,
// and left as it was.
TEST_F(ReportStore, RefusesAVersion3DatabaseItCannotConvert) {
  const std::string path = (dir_ / "orphans.sqlite").string();
  write_old_database(path, 3);
  { SQLite::Database(path, SQLite::OPEN_READWRITE).exec("UPDATE targets SET cycle = 5"); }
  try {
    open_report_database(path, false);
    ADD_FAILURE() << "a database with targets of no cycle was migrated";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("orphans.sqlite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cycle 5"), std::string::npos) << e.what();
  }
  EXPECT_EQ(SQLite::Database(path).execAndGet("PRAGMA user_version").getInt(), 3);
}

// A database newer than this rcsim is refused, naming the file, and left as it was.
TEST_F(ReportStore, RefusesANewerVersion) {
  const std::string path = (dir_ / "v9.sqlite").string();
  write_old_database(path, 2);
  { SQLite::Database(path, SQLite::OPEN_READWRITE).exec("PRAGMA user_version = 9"); }
  try {
    open_report_database(path, false);
    ADD_FAILURE() << "a version 9 database was opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("v9.sqlite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("version 9"), std::string::npos) << e.what();
  }
  EXPECT_EQ(SQLite::Database(path).execAndGet("PRAGMA user_version").getInt(), 9);
}

TEST_F(ReportStore, RefusesAForeignDatabase) {
  const auto path = (dir_ / "other.sqlite").string();
  {
    SQLite::Database other(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    other.exec("CREATE TABLE t (x INTEGER)");
  }
  EXPECT_THROW(open_report_database(path, true), InputError);
  std::ofstream(dir_ / "junk.sqlite") << "this is not a database, just text that is long enough to matter......";
  EXPECT_THROW(open_report_database((dir_ / "junk.sqlite").string(), true), InputError);
}

}  // namespace
}  // namespace rcsim::replay
