// The golden run: fixed seeds over every bundled scene and recording, run as a user runs rcsim,
// hashed, and compared with tests/golden/golden_hashes.txt. Any change of output fails here, so
// a refactor that reorders random draws or moves a rounding is caught; a deliberate change of
// output is a deliberate update of the hashes, said in the commit (scripts/update-golden.sh).
//
// What is hashed (FNV-1a 64, the recording checksum's hash):
//   simulate : `rcsim simulate SCENE --seed 7 --level L --format csv` stdout, L = ideal,
//              detections, tracks;
//   synth    : `rcsim synth SCENE --seed 7` (the signal-level reference): its ego.csv, objects.csv
//              and targets.csv, for the documented examples (docs/examples);
//   replay   : the logical content of the report `rcsim replay REC --seed 7` writes, as its
//              readers see it and independent of how it is stored: the run-level tables rows
//              ordered by primary key, the cycles, targets and annotated boxes through the
//              store's row reader (replay/store/run_rows.hpp); reals printed with 17 significant
//              digits, the targets' reals at the float32 precision they are stored at; the
//              columns that name the machine or the moment (times, directories, version) are
//              left out.
// Beside the hashes, the replay's figures (golden_figures.txt) are compared within stated
// tolerances: another compiler or other flags may round differently and change the hashes (a
// differing hash is then skipped, saying so, where the compiler is not the one the hashes were
// made with), but must not move what a user reads beyond these.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "io/recording.hpp"
#include <nlohmann/json.hpp>

#include "replay/store/run_rows.hpp"
#include "scratch_dir.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::run_rcsim;

constexpr int kGoldenSeed = 7;
const fs::path kSourceDir = RCSIM_SOURCE_DIR;
const fs::path kHashFile = kSourceDir / "tests" / "golden" / "golden_hashes.txt";
const fs::path kFiguresFile = kSourceDir / "tests" / "golden" / "golden_figures.txt";

// The compiler this build was made with, as the hash file names the one its hashes come from.
#ifdef __clang__
const std::string kCompiler = std::string("clang ") + __clang_version__;
#else
const std::string kCompiler = std::string("gcc ") + __VERSION__;
#endif

// A replay's figures as `rcsim replay --json` prints them, and how far another compiler may move
// them: |actual - golden| <= max(absolute, relative * |golden|).
struct FigureTolerance {
  const char* figure;
  double relative, absolute;
};
const std::vector<FigureTolerance> kFigureTolerances{
    {"cycles", 0.0, 0.0},  // the recording's: exact
    {"targets_recorded", 0.0, 0.0},
    {"targets_simulated", 0.03, 2.0},
    {"targets_matched", 0.05, 2.0},
    {"gospa_mean", 0.05, 0.02},
    {"ospa_mean", 0.05, 0.02},
    {"object_cycles_detected_simulated", 0.05, 2.0},
    {"merge_artefacts_simulated", 0.05, 2.0},
    {"residual_range_rms_m", 0.10, 0.01},
};

struct GoldenCase {
  std::string kind;  // simulate | synth | replay
  std::string path;  // relative to the source directory
  std::string level;  // simulate only
  std::string key() const { return kind + " " + path + (level.empty() ? "" : " " + level); }
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.key(); }

std::vector<GoldenCase> golden_cases() {
  std::vector<GoldenCase> cases;
  std::set<std::string> scenes;
  for (const char* dir : {"docs/examples", "recordings_synthetic/scenes", "recordings_synthetic/campaign/scenes"}) {
    for (const auto& e : fs::directory_iterator(kSourceDir / dir)) {
      if (e.path().extension() == ".json") scenes.insert(fs::relative(e.path(), kSourceDir).string());
    }
  }
  for (const auto& scene : scenes) {
    for (const char* level : {"ideal", "detections", "tracks"}) cases.push_back({"simulate", scene, level});
  }
  for (const auto& scene : scenes) {
    if (scene.rfind("docs/examples/", 0) == 0) cases.push_back({"synth", scene, ""});
  }
  std::set<std::string> recordings;
  for (const char* dir : {"recordings_synthetic", "recordings_synthetic/campaign"}) {
    for (const auto& e : fs::directory_iterator(kSourceDir / dir)) {
      if (fs::exists(e.path() / "recording.json")) recordings.insert(fs::relative(e.path(), kSourceDir).string());
    }
  }
  for (const auto& rec : recordings) cases.push_back({"replay", rec, ""});
  return cases;
}

std::map<std::string, std::string> expected_hashes() {
  std::map<std::string, std::string> hashes;
  std::ifstream in(kHashFile);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto space = line.rfind(' ');
    hashes[line.substr(0, space)] = line.substr(space + 1);
  }
  return hashes;
}

std::string real(double value) { return fmt::format("{:.17g}", value); }

// The compiler the hash file's hashes were made with ("# compiler: ..."); empty where it says none.
std::string hashes_compiler() {
  std::ifstream in(kHashFile);
  std::string line;
  const std::string tag = "# compiler: ";
  while (std::getline(in, line)) {
    if (line.rfind(tag, 0) == 0) return line.substr(tag.size());
  }
  return "";
}

// golden_figures.txt: per replay case "replay PATH FIGURE VALUE" lines.
std::map<std::string, std::map<std::string, double>> expected_figures() {
  std::map<std::string, std::map<std::string, double>> figures;
  std::ifstream in(kFiguresFile);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto value_at = line.rfind(' '), figure_at = line.rfind(' ', value_at - 1);
    figures[line.substr(0, figure_at)][line.substr(figure_at + 1, value_at - figure_at - 1)] = std::stod(line.substr(value_at + 1));
  }
  return figures;
}

// Compares a replay's --json figures with the golden ones within their tolerances.
void expect_figures_within_tolerances(const GoldenCase& c, const nlohmann::json& summary) {
  if (const char* out = std::getenv("RCSIM_GOLDEN_FIGURES_OUT")) {
    std::ofstream file(out, std::ios::app);
    for (const auto& t : kFigureTolerances) file << c.key() << ' ' << t.figure << ' ' << real(summary.at(t.figure).get<double>()) << '\n';
  }
  const auto all = expected_figures();
  const auto it = all.find(c.key());
  ASSERT_NE(it, all.end()) << "no golden figures for '" << c.key() << "' in " << kFiguresFile.string();
  for (const auto& t : kFigureTolerances) {
    const auto golden = it->second.find(t.figure);
    ASSERT_NE(golden, it->second.end()) << c.key() << ": " << t.figure;
    const double actual = summary.at(t.figure).get<double>();
    EXPECT_LE(std::abs(actual - golden->second), std::max(t.absolute, t.relative * std::abs(golden->second)))
        << c.key() << ": " << t.figure << " " << actual << " against the golden " << golden->second;
  }
}

std::string hex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

// Columns whose values depend on the machine, the moment or the checkout, not on the figures.
bool is_circumstantial(const std::string& column) {
  static const std::set<std::string> kColumns{"created_utc", "recording_dir", "rcsim_version", "simulate_cpu_s",
                                              "total_wall_s", "parameters"};
  return kColumns.count(column) > 0;
}

// The run-level tables whose rows are hashed as stored, with their deterministic columns.
const std::vector<std::string> kRunTables{"run_sensors", "run_objects", "merge_pairs", "latencies",
                                          "distribution_distances", "summaries", "object_figures", "object_ranges"};
// The columns of `runs` that describe the recording and the replay (not the machine, the moment or
// the storage).
constexpr const char* kRunColumns = "run_id, recording_name, recording_checksum, recording_source, cycle_time_s, cycles, seed, level";

std::string real32(double value) { return real(static_cast<double>(static_cast<float>(value))); }
std::string optional_real(double value) { return std::isnan(value) ? "NULL" : real32(value); }

// The rows of a query as text, one line per row.
std::string dump_rows(SQLite::Database& db, const std::string& select) {
  std::string text;
  SQLite::Statement rows(db, select);
  while (rows.executeStep()) {
    for (int c = 0; c < rows.getColumnCount(); ++c) {
      const auto value = rows.getColumn(c);
      if (c) text += ',';
      if (value.isNull()) text += "NULL";
      else if (value.isInteger()) text += std::to_string(value.getInt64());
      else if (value.isFloat()) text += real(value.getDouble());
      else text += value.getString();
    }
    text += '\n';
  }
  return text;
}

// A table's deterministic columns, rows by primary key.
std::string dump_table(SQLite::Database& db, const std::string& table) {
  std::vector<std::string> columns;
  std::vector<std::pair<int, std::string>> key;
  SQLite::Statement info(db, "PRAGMA table_info(" + table + ")");
  while (info.executeStep()) {
    const std::string name = info.getColumn(1).getString();
    if (const int pk = info.getColumn(5).getInt(); pk > 0) key.emplace_back(pk, name);
    if (!is_circumstantial(name)) columns.push_back(name);
  }
  std::sort(key.begin(), key.end());
  std::string select = "SELECT ";
  for (std::size_t i = 0; i < columns.size(); ++i) select += (i ? ", " : "") + columns[i];
  select += " FROM " + table;
  for (std::size_t i = 0; i < key.size(); ++i) select += (i ? ", " : " ORDER BY ") + key[i].second;
  return "== " + table + "\n" + dump_rows(db, select);
}

// The cycles, targets and boxes of one run, through the store's row reader.
std::string dump_run_rows(SQLite::Database& db, std::int64_t run_id) {
  std::string text = fmt::format("== cycles of run {}\n", run_id);
  replay::for_each_cycle(db, run_id, {}, [&](const replay::StoredCycle& c) {
    text += fmt::format("{},{},{},", c.cycle, c.sensor, real(c.t_s));
    text += c.X_WS ? fmt::format("{},{},{}", real(c.X_WS->x_m), real(c.X_WS->y_m), real(c.X_WS->yaw_rad)) : "NULL";
    text += fmt::format(",{},{},{},{},{},{},{},{},{},{},{}", c.n_recorded, c.n_simulated, c.n_assigned, real(c.gospa_m),
                        real(c.gospa_localisation_mp), real(c.gospa_missed_mp), real(c.gospa_false_mp), real(c.ospa_m),
                        c.merge_recorded, c.merge_simulated, c.merge_matched);
    if (c.classes) {
      const auto& k = *c.classes;
      text += fmt::format(",{},{},{},{},{},{}\n", k.n_object_recorded, k.n_object_simulated, k.n_background_recorded,
                          k.n_background_simulated, real(k.gospa_object_m), real(k.ospa_object_m));
    } else {
      text += ",NULL\n";
    }
  });
  text += fmt::format("== targets of run {}\n", run_id);
  replay::for_each_target(db, run_id, {}, [&](const replay::StoredTarget& t) {
    text += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},", t.cycle, t.sensor, t.simulated ? "simulated" : "recorded",
                        t.idx, t.track_id, real32(t.range_m), real32(t.azimuth_rad), real32(t.range_rate_mps),
                        real32(t.amplitude_db), t.object, t.match_idx, t.merge_artefact ? 1 : 0,
                        t.target_class ? std::string(metrics::target_class_name(*t.target_class)) : "NULL");
    text += t.p_OT_O ? fmt::format("{},{}", real32(t.p_OT_O->x()), real32(t.p_OT_O->y())) : "NULL";
    text += fmt::format(",{},{},{}\n", optional_real(t.rcs_dbsm), optional_real(t.snr_db), optional_real(t.elevation_rad));
  });
  text += fmt::format("== object states of run {}\n", run_id);
  std::vector<replay::StoredObjectState> states;
  replay::for_each_object_state(db, run_id, {}, [&](const replay::StoredObjectState& s) { states.push_back(s); });
  std::sort(states.begin(), states.end(),
            [](const auto& a, const auto& b) { return std::pair(a.cycle, a.object) < std::pair(b.cycle, b.object); });
  for (const auto& s : states) {
    text += fmt::format("{},{},{},{},{}\n", s.cycle, s.object, real(s.X_WO.x_m), real(s.X_WO.y_m), real(s.X_WO.yaw_rad));
  }
  return text;
}

// The report's logical content as text.
std::string dump_report(const fs::path& db_path) {
  SQLite::Database db(db_path.string(), SQLite::OPEN_READONLY);
  std::string text = "== runs\n" + dump_rows(db, std::string("SELECT ") + kRunColumns + " FROM runs ORDER BY run_id");
  for (const auto& table : kRunTables) text += dump_table(db, table);
  SQLite::Statement runs(db, "SELECT run_id FROM runs ORDER BY run_id");
  while (runs.executeStep()) text += dump_run_rows(db, runs.getColumn(0).getInt64());
  return text;
}

class GoldenRun : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenRun, OutputHashIsUnchanged) {
  const GoldenCase& c = GetParam();
  std::string output;
  if (c.kind == "simulate") {
    const auto r = run_rcsim(fmt::format("simulate {} --seed {} --level {} --format csv",
                                         (kSourceDir / c.path).string(), kGoldenSeed, c.level), false);
    ASSERT_EQ(r.exit_code, 0) << c.key();
    output = r.output;
  } else if (c.kind == "synth") {
    const fs::path dir = testing::fresh_scratch_dir("golden");
    const auto r = run_rcsim(fmt::format("synth {} -o {} --seed {}", (kSourceDir / c.path).string(),
                                         (dir / "rec").string(), kGoldenSeed), false);
    ASSERT_EQ(r.exit_code, 0) << c.key();
    for (const char* file : {"ego.csv", "objects.csv", "targets.csv"}) output += testing::read_file(dir / "rec" / file);
    fs::remove_all(dir);
  } else {
    const fs::path dir = testing::fresh_scratch_dir("golden");
    const fs::path db = dir / "report.sqlite";
    const auto r = run_rcsim(fmt::format("replay {} --db {} --seed {} --json", (kSourceDir / c.path).string(), db.string(),
                                         kGoldenSeed), false);
    ASSERT_EQ(r.exit_code, 0) << c.key();
    expect_figures_within_tolerances(c, nlohmann::json::parse(r.output));
    output = dump_report(db);
    fs::remove_all(dir);
  }
  ASSERT_FALSE(output.empty()) << c.key();
  const std::string actual = hex(fnv1a64(output));
  // scripts/update-golden.sh collects these lines into the hash file.
  if (const char* out = std::getenv("RCSIM_GOLDEN_OUT")) {
    std::ofstream(out, std::ios::app) << "# compiler: " << kCompiler << '\n' << c.key() << ' ' << actual << '\n';
  }
  const auto expected = expected_hashes();
  const auto it = expected.find(c.key());
  ASSERT_NE(it, expected.end()) << "no golden hash for '" << c.key() << "' in " << kHashFile.string()
                                << "; the line would be: " << c.key() << ' ' << actual;
  // Another compiler may round differently: a hash that differs there is said, not failed (the
  // figures above are its check). Today clang's ASan build gives gcc's hashes bit for bit.
  if (const std::string made_with = hashes_compiler(); made_with != kCompiler && it->second != actual) {
    GTEST_SKIP() << c.key() << ": the hashes were made with " << made_with << ", this build with " << kCompiler
                 << " gives another: only the figures are compared (within their tolerances)";
  }
  EXPECT_EQ(it->second, actual) << c.key() << ": the output changed. If that is deliberate, update "
                                << kHashFile.string() << " (scripts/update-golden.sh) and say why in the commit.";
}

// Every line of the hash file names a case that still exists: a scene or recording removed or
// renamed is removed from the file too.
TEST(GoldenHashes, EveryLineNamesABundledCase) {
  std::set<std::string> keys;
  for (const auto& c : golden_cases()) keys.insert(c.key());
  const auto expected = expected_hashes();
  ASSERT_FALSE(expected.empty()) << kHashFile.string();
  for (const auto& [key, hash] : expected) {
    EXPECT_TRUE(keys.count(key)) << key;
    EXPECT_EQ(hash.size(), 16u) << key;
  }
}

std::string case_name(const ::testing::TestParamInfo<GoldenCase>& info) {
  std::string name = info.param.kind + "_" + info.param.path + (info.param.level.empty() ? "" : "_" + info.param.level);
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Bundled, GoldenRun, ::testing::ValuesIn(golden_cases()), case_name);

}  // namespace
}  // namespace rcsim
