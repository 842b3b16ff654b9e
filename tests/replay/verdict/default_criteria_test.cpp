// The default tolerances (replay/verdict/default_criteria.hpp, docs/verdicts.md): the documented
// blocks are the built-in ones, each criterion judges the runs of its kind only, and a
// track-level run's verdict computed by hand from its stored figures.
#include "replay/verdict/default_criteria.hpp"

#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::verdict {
namespace {

// The ```json blocks of docs/verdicts.md, in order.
std::vector<nlohmann::json> documented_blocks() {
  std::ifstream in(std::filesystem::path(RCSIM_SOURCE_DIR) / "docs" / "verdicts.md");
  std::vector<nlohmann::json> blocks;
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line == "```json") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      blocks.push_back(nlohmann::json::parse(block));
    } else if (inside) {
      block += line + '\n';
    }
  }
  return blocks;
}

TEST(DefaultCriteria, TheDocumentedBlocksAreTheBuiltInOnes) {
  const auto blocks = documented_blocks();
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0], nlohmann::json::parse(default_criteria_document(ListLevel::tracks)));
  EXPECT_EQ(blocks[1], nlohmann::json::parse(default_criteria_document(ListLevel::detections)));
}

TEST(DefaultCriteria, TaggedByKindTracksFirstHeadlineFigureFirst) {
  const auto& criteria = default_criteria();
  ASSERT_FALSE(criteria.empty());
  EXPECT_EQ(criteria.front().figure, "gospa_mean_m");
  EXPECT_EQ(criteria.front().kind, ListLevel::tracks);
  const auto first_detection = std::find_if(criteria.begin(), criteria.end(),
                                            [](const Criterion& c) { return c.kind == ListLevel::detections; });
  ASSERT_NE(first_detection, criteria.end());
  EXPECT_EQ(first_detection->figure, "gospa_object_mean_m");  // not all-target GOSPA: the background is a density
  for (const Criterion& c : criteria) {
    EXPECT_TRUE(c.kind.has_value()) << c.figure;
    EXPECT_EQ(c.scope, Scope::recording) << c.figure;
  }
}

TEST(ListLevel, FromTheLevelAndForOldRunsFromTheFidelity) {
  EXPECT_EQ(compared_level("tracks", "full"), ListLevel::tracks);
  EXPECT_EQ(compared_level("detections", "full"), ListLevel::detections);
  EXPECT_EQ(compared_level("mixed", "full"), ListLevel::detections);
  EXPECT_EQ(compared_level("tracks", "no_tracking"), ListLevel::detections);  // stored before runs.level was written
}

class DefaultVerdict : public rcsim::testing::ScratchDirTest {
 protected:
  DefaultVerdict() : ScratchDirTest("default_verdict") {}
};

TEST_F(DefaultVerdict, ATrackRunIsJudgedByTheTrackTolerancesAlone) {
  const auto db = open_report_database((dir_ / "report.sqlite").string(), true);
  {
    ReportWriter writer(*db, StoreLevel::summary);
    ReplayOptions options;
    options.seed = 1;
    replay_recording_dir(std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "two_in_one_cell", options,
                         writer);
  }
  EXPECT_EQ(db->execAndGet("SELECT level FROM runs").getString(), "tracks");
  const Verdicts v = judge(*db, default_criteria());
  ASSERT_EQ(v.runs.size(), 1u);
  const std::vector<FigureVerdict> figures = figure_verdicts(v, v.runs[0]);
  ASSERT_EQ(figures.size(), 5u);  // the five track figures, none of the six detection ones
  EXPECT_EQ(figures[0].figure, "gospa_mean_m");
  EXPECT_EQ(figures[0].tolerance(), "<= 1");
  EXPECT_EQ(figures[1].tolerance(), "0.8 .. 1.25");
  // By hand from the stored summary: 132 simulated / 139 recorded targets.
  const auto counts = read_run_figures(*db, {"target_count_ratio", "gospa_mean_m"});
  ASSERT_TRUE(counts[0].values[0].has_value());
  EXPECT_DOUBLE_EQ(*figures[1].value, *counts[0].values[0]);
  EXPECT_EQ(figures[1].passed, *counts[0].values[0] >= 0.8 && *counts[0].values[0] <= 1.25);
  EXPECT_EQ(figures[0].passed, *counts[0].values[1] <= 1.0);
  bool all = true;
  for (const auto& f : figures) all = all && f.passed;
  EXPECT_EQ(v.runs[0].passed, all);
}

}  // namespace
}  // namespace rcsim::replay::verdict
