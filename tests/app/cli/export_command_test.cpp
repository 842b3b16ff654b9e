// rcsim export (issue 31, "queryable reports"): a run's rows decoded from the compact blocks,
// checked against the figures the report stores for the same run.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_rcsim;

class ExportCli : public testing::ScratchDirTest {
 protected:
  ExportCli() : ScratchDirTest("export_cli") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    const std::string rec = (testing::kBundledRecordings / "two_in_one_cell").string();
    ASSERT_EQ(run_rcsim(fmt::format("replay {} --db {} --seed 1", rec, db())).exit_code, 0);
    ASSERT_EQ(run_rcsim(fmt::format("replay {} --db {} --seed 1 --store summary", rec, db())).exit_code, 0);
  }
  std::string db() const { return (dir_ / "r.sqlite").string(); }
};

// The lines of a text, without the last empty one.
std::vector<std::string> export_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST_F(ExportCli, CyclesAsCsvAddUpToTheStoredGospaMean) {
  const auto r = run_rcsim(fmt::format("export {} --run 1 --table cycles", db()), false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto lines = export_lines(r.output);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0].rfind("run_id,cycle,sensor,t_s,sensor_x_m,sensor_y_m,sensor_yaw_rad,n_recorded,n_simulated,"
                           "n_assigned,gospa_m,",
                           0),
            0u)
      << lines[0];
  ASSERT_EQ(lines.size(), 1u + 126u * 2u);  // a row per cycle and sensor
  // The mean of the gospa_m column is the run's stored GOSPA mean.
  double sum = 0.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream row(lines[i]);
    std::string field;
    for (int c = 0; c <= 10; ++c) std::getline(row, field, ',');
    sum += std::stod(field);
  }
  SQLite::Database d(db());
  const double stored = d.execAndGet("SELECT gospa_mean FROM summaries WHERE run_id = 1").getDouble();
  EXPECT_NEAR(sum / 252.0, stored, 1e-12);
}

TEST_F(ExportCli, TargetsAsJsonLinesAreEveryRecordedAndSimulatedTarget) {
  const fs::path out = dir_ / "targets.jsonl";
  const auto r = run_rcsim(fmt::format("export {} --run 1 --table targets --format jsonl -o {}", db(), out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto lines = export_lines(read_file(out));
  EXPECT_EQ(lines.size(), 139u + 132u);  // recorded + simulated targets of the run
  long long recorded = 0, artefacts = 0;
  for (const std::string& line : lines) {
    const auto row = nlohmann::json::parse(line);
    recorded += row["origin"] == "recorded";
    artefacts += row["merge_artefact"].get<int>();
    EXPECT_TRUE(row["target_class"].is_string());
  }
  EXPECT_EQ(recorded, 139);
  EXPECT_EQ(artefacts, 85 + 114);  // the merge artefacts the replay printed
  const auto objects = run_rcsim(fmt::format("export {} --run 1 --table objects", db()), false);
  ASSERT_EQ(objects.exit_code, 0);
  EXPECT_EQ(export_lines(objects.output)[0], "run_id,cycle,object,x_m,y_m,yaw_rad");
}

TEST_F(ExportCli, RefusalsNameTheRunAndLeaveNoFile) {
  const fs::path out = dir_ / "x.csv";
  const auto unknown = run_rcsim(fmt::format("export {} --run 7 --table cycles -o {}", db(), out.string()));
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find(db()), std::string::npos) << unknown.output;
  const auto summary = run_rcsim(fmt::format("export {} --run 2 --table targets -o {}", db(), out.string()));
  EXPECT_EQ(summary.exit_code, 2) << summary.output;
  EXPECT_NE(summary.output.find("--store summary"), std::string::npos) << summary.output;
  EXPECT_FALSE(fs::exists(out));
  const auto table = run_rcsim(fmt::format("export {} --run 1 --table cycle", db()));
  EXPECT_EQ(table.exit_code, 2) << table.output;
  fs::create_symlink(dir_ / "elsewhere.csv", dir_ / "link.csv");
  EXPECT_EQ(run_rcsim(fmt::format("export {} --run 1 --table cycles -o {}", db(), (dir_ / "link.csv").string())).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "elsewhere.csv"));
}


// --format mcap: the whole run in one file, said in one line; refused without -o (a binary file on
// a terminal), for an unknown run, and over a link, leaving no file.
TEST_F(ExportCli, McapIsOneFileWrittenAtomicallyAndRefusedWithoutAName) {
  const fs::path out = dir_ / "run1.mcap";
  const auto written = run_rcsim(fmt::format("export {} --run 1 --format mcap -o {}", db(), out.string()));
  ASSERT_EQ(written.exit_code, 0) << written.output;
  EXPECT_NE(written.output.find("rcsim export: run 1 as MCAP, 126 cycles of 2 sensor(s), "), std::string::npos) << written.output;
  const std::string bytes = testing::read_file(out);
  EXPECT_EQ(bytes.substr(0, 5), "\x89MCAP");
  EXPECT_EQ(bytes.substr(bytes.size() - 8, 5), "\x89MCAP");
  const auto no_name = run_rcsim(fmt::format("export {} --run 1 --format mcap", db()));
  EXPECT_EQ(no_name.exit_code, 2);
  EXPECT_NE(no_name.output.find("--format mcap writes a binary file: name it with -o FILE.mcap"), std::string::npos) << no_name.output;
  const auto unknown = run_rcsim(fmt::format("export {} --run 9 --format mcap -o {}", db(), (dir_ / "x.mcap").string()));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "x.mcap"));
  const auto no_table = run_rcsim(fmt::format("export {} --run 1", db()));
  EXPECT_EQ(no_table.exit_code, 2);
  EXPECT_NE(no_table.output.find("--table: is required for --format csv"), std::string::npos) << no_table.output;
}

// Issue 51: a non-UTF-8 object id threw the JSON library's type_error.316 (exit 1); it is refused
// by the object's position, exit 2, leaving no file.
TEST_F(ExportCli, ANonUtf8ObjectIdIsRefusedByItsPosition) {
  {
    SQLite::Database db(this->db(), SQLite::OPEN_READWRITE);
    db.exec("UPDATE run_objects SET object_id = CAST(x'6361ff72' AS TEXT) WHERE run_id = 1 AND object = 0");
  }
  const fs::path out = dir_ / "bad.mcap";
  const auto r = run_rcsim(fmt::format("export {} --run 1 --format mcap -o {}", db(), out.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run 1: object 0's id is not UTF-8 text (invalid UTF-8 at byte 2)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("json.exception"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Issue 51: a file tagged as a report (application_id RCSR, the current version) without its
// tables gave SQLite's bare "no such table", exit 1: now named with its file, exit 2.
TEST_F(ExportCli, AFileTaggedAsAReportWithoutItsTablesIsRefusedByName) {
  const std::string tagged = (dir_ / "tagged.sqlite").string();
  int application_id = 0, version = 0;
  {
    SQLite::Database db(this->db(), SQLite::OPEN_READONLY);
    application_id = db.execAndGet("PRAGMA application_id").getInt();
    version = db.execAndGet("PRAGMA user_version").getInt();
  }
  {
    SQLite::Database db(tagged, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db.exec(fmt::format("PRAGMA application_id = {}", application_id));
    db.exec(fmt::format("PRAGMA user_version = {}", version));
    db.exec("CREATE TABLE t(x)");
  }
  for (const std::string& command : {fmt::format("export {} --run 1 --table cycles", tagged), fmt::format("report {} -o {}", tagged, (dir_ / "report.html").string())}) {
    const auto r = run_rcsim(command);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.output;
    EXPECT_NE(r.output.find(tagged + ": tagged as an rcsim report"), std::string::npos) << command << ": " << r.output;
    EXPECT_NE(r.output.find("has no table runs"), std::string::npos) << command << ": " << r.output;
  }
}

// Issue 51: export, a read, switched the report to WAL (and back as it closed): the file is now
// left byte for byte as it was, and no -wal file appears beside it.
TEST_F(ExportCli, ExportingLeavesTheReportAsItWas) {
  const std::string before = testing::read_file(db());
  for (const std::string& args : {std::string("--table targets -o ") + (dir_ / "t.csv").string(),
                                  std::string("--format mcap -o ") + (dir_ / "t.mcap").string()}) {
    ASSERT_EQ(run_rcsim(fmt::format("export {} --run 1 {}", db(), args)).exit_code, 0) << args;
    EXPECT_TRUE(testing::read_file(db()) == before) << args << ": the report changed";
    EXPECT_FALSE(fs::exists(db() + "-wal")) << args;
  }
}

}  // namespace
}  // namespace rcsim
