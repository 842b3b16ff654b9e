// What a user mistyped and what they meant (common/closest_name.hpp): the edit distance with
// transpositions by hand, the typo budget that grows with the name, the unique extension.
#include "common/closest_name.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rcsim::closest_name_test {

TEST(ClosestName, TypingDistanceCountsASwapAsOneEditByHand) {
  EXPECT_EQ(typing_distance("replay", "replay"), 0u);
  EXPECT_EQ(typing_distance("replya", "replay"), 1u);  // "ya" <-> "ay": one transposition
  EXPECT_EQ(typing_distance("", "abc"), 3u);            // three insertions
  EXPECT_EQ(typing_distance("kitten", "sitting"), 3u);  // k->s, e->i, +g
  // Optimal string alignment, not full Damerau: "ca" -> "abc" cannot edit inside the swapped pair,
  // so it is 3 (delete c, keep a, insert b, c), not 2.
  EXPECT_EQ(typing_distance("ca", "abc"), 3u);
  EXPECT_EQ(typing_distance("abc", "ca"), 3u);  // symmetric
}

TEST(ClosestName, TheTypoBudgetGrowsWithTheNameAndIgnoresDashes) {
  const std::vector<std::string> commands = {"simulate", "replay", "calibrate", "campaign", "report"};
  EXPECT_EQ(closest_name("replya", commands), "replay");
  // 7 letters: 7 / 3 = 2 typos allowed; "smulte" (6 letters: 2) is 2 from "simulate".
  EXPECT_EQ(closest_name("simulte", commands), "simulate");
  EXPECT_EQ(closest_name("smulte", commands), "simulate");
  // 4 letters: one typo only; "rplx" is more than 1 from every name and begins none.
  EXPECT_EQ(closest_name("rplx", commands), std::nullopt);
  // Leading dashes are ignored on both sides; the name is returned as known.
  const std::vector<std::string> options = {"--db", "-o", "--seed", "--level"};
  EXPECT_EQ(closest_name("--sed", options), "--seed");
  EXPECT_EQ(closest_name("-levle", options), "--level");
  // One or two letters: only other dashes or a swap, never any other short name.
  EXPECT_EQ(closest_name("--o", options), "-o");
  EXPECT_EQ(closest_name("--bd", options), "--db");
  EXPECT_EQ(closest_name("--dx", options), std::nullopt);  // 1 from "db", but not its letters
  EXPECT_EQ(closest_name("-x", options), std::nullopt);
  EXPECT_EQ(closest_name("anything", {}), std::nullopt);
}

TEST(ClosestName, AnAbbreviationNamesTheOnlyNameItBegins) {
  const std::vector<std::string> commands = {"calibrate", "campaign", "replay", "report"};
  EXPECT_EQ(closest_name("cal", commands), "calibrate");  // 6 from it, but the only one it begins
  EXPECT_EQ(closest_name("camp", commands), "campaign");
  EXPECT_EQ(closest_name("rep", commands), std::nullopt);  // begins both replay and report
  EXPECT_EQ(closest_name("ca", commands), std::nullopt);   // two letters abbreviate nothing
  // A near name wins over an extension: "repor" is 1 from "report" (and begins it).
  EXPECT_EQ(closest_name("repor", commands), "report");
}

TEST(ClosestName, JoinNamesSeparatesWithCommas) {
  EXPECT_EQ(join_names({}), "");
  EXPECT_EQ(join_names({"srr24"}), "srr24");
  EXPECT_EQ(join_names({"a", "b", "c"}), "a, b, c");
}

}  // namespace rcsim::closest_name_test
