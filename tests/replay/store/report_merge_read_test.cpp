// What `rcsim merge` reads before it writes (replay/store/report_merge_read.hpp): the first field
// in which two campaign manifests differ, named as a person can act on it.
#include "replay/store/report_merge_read.hpp"

#include <gtest/gtest.h>

namespace rcsim::replay::merge_read {
namespace {

TEST(ReportMergeRead, TheFirstFieldInWhichTwoManifestsDifferIsNamed) {
  const std::string kept = R"({"name": "drives", "recordings": ["a", "b"], "replay": {"seed": 0, "store": "summary"}})";
  // Equal as JSON: members in another order, other spacing.
  EXPECT_EQ(first_manifest_difference(R"({"replay": {"store": "summary", "seed": 0}, "recordings": ["a","b"],
                                          "name": "drives"})",
                                      kept),
            "");
  EXPECT_EQ(first_manifest_difference(R"({"name": "drives", "recordings": ["a"], "replay": {"seed": 1}})", kept),
            R"(field "recordings": ["a"] against ["a","b"])")
      << "the first in the kept manifest's order";
  EXPECT_EQ(first_manifest_difference(R"({"name": "drives", "recordings": ["a", "b"]})", kept),
            R"(field "replay": missing against {"seed":0,"store":"summary"})");
  EXPECT_EQ(first_manifest_difference(
                R"({"name": "drives", "recordings": ["a", "b"], "replay": {"seed": 0, "store": "summary"}, "x": 1})", kept),
            R"(field "x": 1 against missing)");
  EXPECT_EQ(first_manifest_difference("not json", kept),
            "the texts differ, and one is not JSON (or nests deeper than rcsim reads)");
  // A stored manifest nested 100,000 deep crashed the merge (SIGSEGV) while this message was made.
  const std::string deep = std::string(100'000, '[') + std::string(100'000, ']');
  EXPECT_EQ(first_manifest_difference(deep, kept), "the texts differ, and one is not JSON (or nests deeper than rcsim reads)");
  // A long value is cut.
  const std::string many = R"({"name": "drives", "recordings": [)" + std::string(R"("drive_0001", )") + std::string(R"("drive_0002", "drive_0003", "drive_0004", "drive_0005", "drive_0006"]})");
  const std::string difference = first_manifest_difference(many, kept);
  EXPECT_EQ(difference.rfind(R"(field "recordings": ["drive_0001","drive_0002",)", 0), 0u) << difference;
  EXPECT_LT(difference.size(), 100u) << difference;
}

}  // namespace
}  // namespace rcsim::replay::merge_read
