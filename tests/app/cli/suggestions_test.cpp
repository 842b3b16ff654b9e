// What a user mistyped, named with what they probably meant (app/cli/suggestions.cpp): on a small
// command tree built here, parsed as CLI11 parses rcsim's, with unknown arguments allowed through.
#include "app/cli/suggestions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace rcsim::suggestions_test {

// "rcsim" with `replay --seed N --db FILE` and `campaign plan --shards N`; every command lets unknown
// arguments through, so that they are left for unknown_argument_message to name.
struct CommandTree {
  CLI::App root{"test", "rcsim"};
  int seed = 0;
  int shards = 0;
  std::string db;
  CommandTree() {
    root.allow_extras();
    CLI::App* replay = root.add_subcommand("replay", "replay");
    replay->allow_extras();
    replay->add_option("--seed", seed);
    replay->add_option("--db", db);
    CLI::App* campaign = root.add_subcommand("campaign", "campaign");
    campaign->allow_extras();
    CLI::App* plan = campaign->add_subcommand("plan", "plan");
    plan->allow_extras();
    plan->add_option("--shards", shards);
  }
  std::optional<std::string> message_for(std::vector<std::string> args) {
    std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
    root.parse(args);
    return cli::unknown_argument_message(root);
  }
};

TEST(Suggestions, AMistypedOptionIsNamedWithTheNearestOptionOfItsCommand) {
  CommandTree tree;
  EXPECT_EQ(tree.message_for({"replay", "--sed", "1"}),
            "rcsim replay: unknown option '--sed'; did you mean '--seed'? (rcsim replay --help)");
  CommandTree with_value;  // --sed=1: the name alone is named
  EXPECT_EQ(with_value.message_for({"replay", "--sed=1"}),
            "rcsim replay: unknown option '--sed'; did you mean '--seed'? (rcsim replay --help)");
}

TEST(Suggestions, AnOptionNothingResemblesListsWhereTheOptionsAre) {
  CommandTree tree;
  EXPECT_EQ(tree.message_for({"replay", "--zzzzzzzz"}),
            "rcsim replay: unknown option '--zzzzzzzz' (rcsim replay --help lists the options)");
}

TEST(Suggestions, AMistypedCommandIsNamedBeforeItsOptionsAtAnyDepth) {
  CommandTree tree;
  // "rcsim replya --seed 1": the command is what went wrong, not its options.
  EXPECT_EQ(tree.message_for({"replya", "--seed", "1"}),
            "rcsim: unknown command 'replya'; did you mean 'replay'? (rcsim --help)");
  CommandTree nested;
  EXPECT_EQ(nested.message_for({"campaign", "plna"}),
            "rcsim campaign: unknown command 'plna'; did you mean 'plan'? (rcsim campaign --help)");
  CommandTree far;
  EXPECT_EQ(far.message_for({"campaign", "qqqqqqq"}),
            "rcsim campaign: unknown command 'qqqqqqq' (commands: plan; rcsim campaign --help)");
}

TEST(Suggestions, AWordWhereACommandTakesNoneIsUnexpectedAndAFullParseHasNoMessage) {
  CommandTree tree;
  EXPECT_EQ(tree.message_for({"campaign", "plan", "extra"}),
            "rcsim campaign plan: unexpected argument 'extra' (rcsim campaign plan --help)");
  CommandTree clean;
  EXPECT_EQ(clean.message_for({"replay", "--seed", "3", "--db", "x.sqlite"}), std::nullopt);
  EXPECT_EQ(clean.seed, 3);
}

}  // namespace rcsim::suggestions_test
