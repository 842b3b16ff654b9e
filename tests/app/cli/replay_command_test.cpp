// rcsim scene / replay as a user runs them: the JSON summary, many runs in one database,
// determinism, refusals, and a replay killed midway.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <thread>
#include <tuple>
#include <unistd.h>

#include "scratch_dir.hpp"
#include "app/cli/run_rcsim.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_rcsim;

class ReplayCli : public testing::ScratchDirTest {
 protected:
  ReplayCli() : ScratchDirTest("replay_cli") {}

  fs::path recording(double duration_s, const std::string& name = "rec") {
    const fs::path path = dir_ / name;
    write_recording(path, testing::model_recording(testing::two_cars_scene(duration_s), 2, 0.03, 0.01));
    return path;
  }
};

std::size_t data_rows(const std::string& csv) {
  std::size_t lines = 0;
  for (const char c : csv) lines += c == '\n';
  return lines - 1;
}

TEST_F(ReplayCli, JsonSummaryAccountsForEveryRecordedTarget) {
  const fs::path rec = recording(3.0);
  const auto r = run_rcsim("replay " + rec.string() + " --db " + (dir_ / "r.sqlite").string() + " --json --seed 2", false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = nlohmann::json::parse(r.output);
  for (const char* key : {"run_id", "cycles", "targets_recorded", "targets_simulated", "gospa_mean",
                          "merge_artefacts_recorded", "merge_artefacts_simulated", "latency_recorded_s",
                          "latency_simulated_s"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_EQ(summary["run_id"], 1);
  EXPECT_EQ(summary["cycles"], 76);
  EXPECT_EQ(summary["targets_recorded"].get<std::size_t>(), data_rows(read_file(rec / "targets.csv")));
  EXPECT_GT(summary["targets_simulated"].get<int>(), 0);
}

// A recording whose sensors report raw detections is compared with the model's detections
// (no_tracking) unless --fidelity says otherwise; one that reports tracks, with the tracker.
TEST_F(ReplayCli, ComparesAtTheLevelTheSensorsReport) {
  Recording rec = testing::model_recording(testing::two_cars_scene(1.0), 2);
  const fs::path tracks = dir_ / "tracks", raw = dir_ / "raw";
  write_recording(tracks, rec);
  for (auto& s : rec.sensors) s.reports = ListLevel::detections;
  write_recording(raw, rec);
  const std::string db = (dir_ / "r.sqlite").string();
  for (const auto& [dir, extra] : {std::pair{tracks, ""}, std::pair{raw, ""}, std::pair{raw, " --fidelity full"}}) {
    ASSERT_EQ(run_rcsim("replay " + dir.string() + " --db " + db + extra).exit_code, 0);
  }
  SQLite::Database d(db);
  std::vector<std::string> levels;
  SQLite::Statement q(d, "SELECT json_extract(parameters, '$.fidelity.level') FROM runs ORDER BY run_id");
  while (q.executeStep()) levels.push_back(q.getColumn(0).getString());
  EXPECT_EQ(levels, (std::vector<std::string>{"full", "no_tracking", "full"}));
}

// What the import noticed reaches the user of replay too (stderr), not only of rcsim import.
TEST_F(ReplayCli, PrintsImportWarnings) {
  Recording rec = testing::model_recording(testing::two_cars_scene(2.0), 2, 0.03, 0.01);
  rec.boxes[0].erase(rec.boxes[0].begin() + 10, rec.boxes[0].begin() + 30);  // 0.8 s unannotated
  const fs::path path = dir_ / "gap";
  write_recording(path, rec);
  const auto r = run_rcsim("replay " + path.string() + " --db " + (dir_ / "r.sqlite").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rcsim: warning: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("absent"), std::string::npos) << r.output;
  const auto clean = run_rcsim("replay " + recording(2.0).string() + " --db " + (dir_ / "r.sqlite").string());
  ASSERT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_EQ(clean.output.find("warning"), std::string::npos) << clean.output;
}

TEST_F(ReplayCli, RunsAccumulateAndTheSameSeedRepeatsExactly) {
  const fs::path rec = recording(2.0);
  const std::string db = (dir_ / "r.sqlite").string();
  for (const char* seed : {"4", "4", "5"}) {
    ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db + " --seed " + seed + " --again").exit_code, 0);
  }
  SQLite::Database d(db);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 3);
  const auto targets_of = [&](int run) {
    std::string text;
    replay::for_each_target(d, run, {}, [&](const replay::StoredTarget& t) {
      text += fmt::format("{},{},{},{},{:.6f},{:.6f};", t.cycle, t.sensor, t.simulated ? "simulated" : "recorded", t.idx,
                          t.range_m, t.azimuth_rad);
    });
    return text;
  };
  EXPECT_GT(targets_of(1).size(), 100u);
  EXPECT_EQ(targets_of(1), targets_of(2));
  EXPECT_NE(targets_of(1), targets_of(3));
  EXPECT_EQ(d.execAndGet("PRAGMA application_id").getInt(), 0x52435352);
  EXPECT_EQ(d.execAndGet("PRAGMA user_version").getInt(), replay::kReportSchemaVersion);
}

TEST_F(ReplayCli, AnotherSensorConfigurationIsStoredWithItsRun) {
  const fs::path rec = recording(2.0);
  const std::string db = (dir_ / "r.sqlite").string();
  std::string config = read_file(fs::path(RCSIM_SOURCE_DIR) / "src/sensor/sensors/srr24.json");
  const std::string six_db = "\"detection_threshold_db\": 6.0";
  const auto threshold = config.find(six_db);
  ASSERT_NE(threshold, std::string::npos);
  config.replace(threshold, six_db.size(), "\"detection_threshold_db\": 18.0");
  std::ofstream(dir_ / "srr24_18db.json") << config;
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db).exit_code, 0);
  const auto r = run_rcsim("replay " + rec.string() + " --db " + db + " --sensor " + (dir_ / "srr24_18db.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  SQLite::Database d(db);
  SQLite::Statement q(d, "SELECT count(*) FROM run_sensors WHERE run_id = 2 AND configuration LIKE ? AND type LIKE ?");
  q.bind(1, "%\"detection_threshold_db\": 18.0%");
  q.bind(2, "%srr24_18db.json");
  ASSERT_TRUE(q.executeStep());
  EXPECT_EQ(q.getColumn(0).getInt(), 2);
  const auto simulated = [&](int run) {
    SQLite::Statement t(d, "SELECT targets_simulated FROM summaries WHERE run_id = ?");
    t.bind(1, run);
    t.executeStep();
    return t.getColumn(0).getInt();
  };
  EXPECT_LT(simulated(2), simulated(1));  // a higher threshold detects less
}

// A --sensor that names no file and no built-in profile is the option's fault (issue 48), not the
// recording's sensors[].type, which it replaces; nothing is stored.
TEST_F(ReplayCli, AMissingSensorFileNamesTheOption) {
  const fs::path rec = recording(1.0);
  const fs::path db = dir_ / "r.sqlite";
  for (const std::string& sensor : {(dir_ / "missing.json").string(), std::string("srr42")}) {
    const auto r = run_rcsim("replay " + rec.string() + " --db " + db.string() + " --sensor " + sensor);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--sensor: " + sensor + ": no such built-in profile or rcsim-sensor file"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("sensors[0].type"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(db));
  }
  // A name close to a built-in one is answered with it.
  EXPECT_NE(run_rcsim("replay " + rec.string() + " --db " + db.string() + " --sensor srr42").output.find("\"srr24\""),
            std::string::npos);
}

TEST_F(ReplayCli, SceneWritesALoadableSceneAndImportStillDoesSayingSo) {
  const fs::path rec = recording(2.0);
  const fs::path scene = dir_ / "scene.json";
  ASSERT_EQ(run_rcsim("scene " + rec.string() + " -o " + scene.string()).exit_code, 0);
  const auto r = run_rcsim("simulate " + scene.string() + " --level tracks", false);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_GT(data_rows(r.output), 10u);
  // The old spelling: the same scene, and a note of the new one.
  const fs::path old_spelling = dir_ / "old.json";
  const auto old = run_rcsim("import " + rec.string() + " -o " + old_spelling.string());
  EXPECT_EQ(old.exit_code, 0);
  EXPECT_NE(old.output.find("is now `rcsim scene RECORDING_DIR -o SCENE.json`"), std::string::npos) << old.output;
  EXPECT_EQ(read_file(old_spelling), read_file(scene));
}

TEST_F(ReplayCli, BadRecordingsAreNamedAndNothingIsStored) {
  const fs::path rec = recording(1.0);
  const std::string db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db).exit_code, 0);
  const auto foreign = run_rcsim("replay " + rec.string() + " --db " + (rec / "ego.csv").string());
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_NE(foreign.output.find("ego.csv"), std::string::npos) << foreign.output;
  std::ofstream(rec / "targets.csv", std::ios::app) << "0.04,1,front_left,12.0,0.1\n";  // truncated row
  const auto r = run_rcsim("replay " + rec.string() + " --db " + db);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("targets.csv: line"), std::string::npos) << r.output;
  SQLite::Database d(db);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 1);

  const auto missing = run_rcsim("replay " + (dir_ / "nothing").string() + " --db " + db);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("nothing"), std::string::npos);
}

TEST_F(ReplayCli, ReplayKilledMidwayLeavesEarlierRunsComplete) {
  const fs::path small = recording(1.0, "small");
  const fs::path large = recording(400.0, "large");  // 10,000 cycles: long enough to kill midway
  const std::string db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(run_rcsim("replay " + small.string() + " --db " + db).exit_code, 0);

  // The replay kills itself with SIGKILL after storing 3000 of its 20,000 sensor cycles: in the
  // middle of its transaction, with no chance to clean up (rcsim_killable, RCSIM_TEST_KILL_AFTER_CYCLES).
  const auto complete = run_rcsim("replay " + large.string() + " --db " + db);  // a whole large run first
  ASSERT_EQ(complete.exit_code, 0) << complete.output;
  const std::string command = std::string("RCSIM_TEST_KILL_AFTER_CYCLES=3000 ") + RCSIM_KILLABLE_BINARY + " replay " +
                              large.string() + " --db " + db + " --again > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFSIGNALED(status) || WEXITSTATUS(status) == 128 + SIGKILL) << "status " << status;
  ASSERT_TRUE(fs::exists(db + "-wal"));  // the dead run's uncommitted pages are left behind

  SQLite::Database d(db, SQLite::OPEN_READWRITE);
  EXPECT_EQ(d.execAndGet("PRAGMA integrity_check").getString(), "ok");
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 2);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM summaries").getInt(), 2);
  EXPECT_EQ(d.execAndGet("SELECT count(DISTINCT run_id) FROM target_blocks").getInt(), 2);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM cycle_blocks WHERE run_id = 3").getInt(), 0);
  // And the database takes the next run.
  EXPECT_EQ(run_rcsim("replay " + small.string() + " --db " + db + " --again").exit_code, 0);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM summaries").getInt(), 3);
}

// Issue 53, trap 4: Ctrl-C during a replay exited 130 silently and left an empty database. Now it
// stops at the next cycle boundary (within a second), says where and what became of the report,
// and stores nothing of the run (one transaction): an earlier report keeps its runs unchanged, one
// the replay created is removed. Exit status 130, as a shell reports Ctrl-C.
TEST_F(ReplayCli, AnInterruptedReplayStopsPromptlyAndLeavesTheReportAsItWas) {
  const fs::path small = recording(1.0, "small");
  const fs::path large = recording(6000.0, "large");  // 150,000 cycles: seconds to replay
  const std::string db = (dir_ / "r.sqlite").string(), fresh = (dir_ / "new.sqlite").string();
  ASSERT_EQ(run_rcsim("replay " + small.string() + " --db " + db).exit_code, 0);
  for (const std::string& target : {db, fresh}) {
    const auto start = std::chrono::steady_clock::now();
    // SIGINT every 0.1 s from the start (a background job ignores it until the replay's handler is
    // in place), as the interrupted-fit test sends it.
    const auto r = testing::run_shell_command(fmt::format(
        "{} replay {} --db {} --again & pid=$!; for i in $(seq 1 600); do sleep 0.1; kill -INT $pid 2>/dev/null || break; "
        "done; wait $pid; echo \"rc $?\"",
        RCSIM_BINARY, large.string(), target));
    const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(r.output.find("rc 130\n"), std::string::npos) << r.output;
    EXPECT_LT(elapsed_s, 3.0) << "the replay went on after Ctrl-C: " << r.output;
    const std::string said = "rcsim: interrupted: model_made: the replay stopped at cycle ";
    const std::size_t at = r.output.find(said);
    ASSERT_NE(at, std::string::npos) << r.output;
    EXPECT_LT(std::stoi(r.output.substr(at + said.size())), 150001 / 2) << r.output;
    EXPECT_NE(r.output.find(" of 150001; nothing of it stored"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("stored in"), std::string::npos) << "the replay finished before Ctrl-C: " << r.output;
    if (target == db) {
      EXPECT_NE(r.output.find(db + " holds the runs stored before, unchanged"), std::string::npos) << r.output;
      SQLite::Database d(db, SQLite::OPEN_READONLY);
      EXPECT_EQ(d.execAndGet("PRAGMA integrity_check").getString(), "ok");
      EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 1);
      EXPECT_EQ(d.execAndGet("SELECT count(*) FROM summaries").getInt(), 1);
    } else {
      EXPECT_NE(r.output.find(fresh + ", which this replay created, removed"), std::string::npos) << r.output;
      for (const char* suffix : {"", "-wal", "-shm", "-journal"}) EXPECT_FALSE(fs::exists(fresh + suffix)) << suffix;
    }
  }
}

// Issue 53: a finished report was left in WAL mode, which sqlite3 cannot read on read-only storage
// (it needs a -shm beside the file). The last writer to close it switches it back to a rollback
// journal: no -wal, no -shm, and sqlite3 reads it from a read-only mount (where one can be made).
TEST_F(ReplayCli, AFinishedReportIsReadableOnReadOnlyStorage) {
  const fs::path rec = recording(1.0);
  const fs::path folder = dir_ / "reports";
  fs::create_directories(folder);
  const std::string db = (folder / "r.sqlite").string();
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db).exit_code, 0);
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db + " --again --seed 2").exit_code, 0);
  for (const char* suffix : {"-wal", "-shm", "-journal"}) EXPECT_FALSE(fs::exists(db + suffix)) << suffix;
  {
    std::ifstream file(db, std::ios::binary);
    char header[20] = {};
    file.read(header, sizeof header);
    EXPECT_EQ(header[18], 1) << "the file's write version: 2 is WAL";
    EXPECT_EQ(header[19], 1) << "the file's read version: 2 is WAL";
  }
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("PRAGMA journal_mode").getString(), "delete");
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 2);
  if (std::system("command -v sqlite3 >/dev/null 2>&1 && unshare -rm true >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "sqlite3 or unshare -rm unavailable: not read from a read-only mount";
  }
  const auto r = testing::run_shell_command("unshare -rm sh -c 'mount --bind " + folder.string() + " " + folder.string() +
                                            " && mount -o remount,ro,bind " + folder.string() + " && sqlite3 " + db +
                                            " \"SELECT count(*) FROM runs\"'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "2\n");
}

// --store summary keeps the per-cycle figures, bit for bit those of a full run, and every table per
// run, object and sensor, but no targets, no boxes and no sensor poses; it says so in the run, and
// its report renders, naming the figures that need --store full.
TEST_F(ReplayCli, SummaryStoreKeepsTheFiguresAndNoTargets) {
  const fs::path rec = recording(3.0);
  const std::string db = (dir_ / "r.sqlite").string();
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db + " --seed 3").exit_code, 0);
  ASSERT_EQ(run_rcsim("replay " + rec.string() + " --db " + db + " --seed 3 --store summary").exit_code, 0);
  const auto bad = run_rcsim("replay " + rec.string() + " --db " + db + " --store some");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--store"), std::string::npos) << bad.output;

  SQLite::Database d(db);
  EXPECT_EQ(replay::run_store_level(d, 1), replay::StoreLevel::full);
  EXPECT_EQ(replay::run_store_level(d, 2), replay::StoreLevel::summary);
  EXPECT_EQ(d.execAndGet("SELECT store FROM runs WHERE run_id = 2").getString(), "summary");
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM target_blocks WHERE run_id = 2").getInt(), 0);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM object_state_blocks WHERE run_id = 2").getInt(), 0);
  EXPECT_GT(d.execAndGet("SELECT count(*) FROM target_blocks WHERE run_id = 1").getInt(), 0);
  int targets = 0;
  replay::for_each_target(d, 2, {}, [&](const replay::StoredTarget&) { ++targets; });
  EXPECT_EQ(targets, 0);

  // The cycles of both runs, poses aside, and the run-level tables, identical.
  const auto cycles_of = [&](int run) {
    std::vector<replay::StoredCycle> rows;
    replay::for_each_cycle(d, run, {}, [&](const replay::StoredCycle& c) { rows.push_back(c); });
    return rows;
  };
  const auto full = cycles_of(1), summary = cycles_of(2);
  ASSERT_EQ(full.size(), 2u * 76u);
  ASSERT_EQ(summary.size(), full.size());
  for (std::size_t i = 0; i < full.size(); ++i) {
    const auto &f = full[i], &s = summary[i];
    EXPECT_TRUE(f.X_WS.has_value());
    EXPECT_FALSE(s.X_WS.has_value());
    EXPECT_EQ(std::tuple(f.cycle, f.sensor, f.n_recorded, f.n_simulated, f.n_assigned, f.merge_recorded),
              std::tuple(s.cycle, s.sensor, s.n_recorded, s.n_simulated, s.n_assigned, s.merge_recorded));
    // Bit for bit: EXPECT_EQ on doubles compares exactly.
    EXPECT_EQ(std::tuple(f.t_s, f.gospa_m, f.gospa_localisation_mp, f.gospa_missed_mp, f.gospa_false_mp, f.ospa_m),
              std::tuple(s.t_s, s.gospa_m, s.gospa_localisation_mp, s.gospa_missed_mp, s.gospa_false_mp, s.ospa_m));
    ASSERT_TRUE(f.classes && s.classes);
    EXPECT_EQ(f.classes->gospa_object_m, s.classes->gospa_object_m);
    EXPECT_EQ(f.classes->n_object_recorded, s.classes->n_object_recorded);
  }
  for (const char* table : {"summaries", "latencies", "distribution_distances", "object_figures", "object_ranges",
                            "merge_pairs", "run_sensors", "run_objects"}) {
    // Every column but the run id and the times of the replay.
    const std::string columns = fmt::format(
        "SELECT group_concat(name) FROM pragma_table_info('{}') WHERE name NOT IN ('run_id', 'simulate_cpu_s', "
        "'total_wall_s')",
        table);
    const std::string list = d.execAndGet(columns).getString();
    const auto rows = [&](int run) {
      return d.execAndGet(fmt::format("SELECT count(*) || ':' || coalesce(group_concat(r, ';'), '') FROM (SELECT "
                                      "printf('%s', json_array({})) AS r FROM {} WHERE run_id = {} ORDER BY 1)",
                                      list, table, run))
          .getString();
    };
    EXPECT_EQ(rows(1), rows(2)) << table;
  }

  const fs::path html = dir_ / "r.html";
  const auto report = run_rcsim("report " + db + " -o " + html.string() + " --run 2");
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string page = read_file(html);
  EXPECT_NE(page.find("data-key=\"store\">summary<"), std::string::npos);
  EXPECT_NE(page.find("The bird&#39;s-eye pictures need the targets"), std::string::npos);
  EXPECT_NE(page.find("The residual histograms need the targets"), std::string::npos);
  EXPECT_NE(page.find("Targets per cycle, sensor"), std::string::npos);  // from the cycles: still drawn
  EXPECT_NE(page.find("GOSPA, sensor"), std::string::npos);
  EXPECT_EQ(page.find("Nearest object target range"), std::string::npos);
  EXPECT_EQ(page.find("class=\"birdseye\""), std::string::npos);
}

}  // namespace
}  // namespace rcsim
