// `rcsim stream` (and its peer `rcsim listen`) refusing what a user typed wrong: exit status 2
// and the option named, whichever layer found it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::stream_command_test {

namespace fs = std::filesystem;
using rcsim::testing::CommandResult;

const std::string kUsageScene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/front_approach.json";

using rcsim::testing::output_has;
CommandResult run_usage(const std::string& args) { return rcsim::testing::run_rcsim_with_timeout(args); }

class StreamCliUsage : public rcsim::testing::ScratchDirTest {
 protected:
  StreamCliUsage() : ScratchDirTest("stream_cli_usage") {}
};

// README's exit statuses: what the user typed wrong is 2, whichever layer finds it (the stream's
// and listener's own checks threw errors that ended with 1).
TEST_F(StreamCliUsage, StreamAndListenRefuseBadArgumentsWithStatusTwo) {
  const std::string stream = "stream " + kUsageScene + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {stream + "--to 127.0.0.1:5000 --speed fast", "--speed 'fast'"},
      {stream + "--to 127.0.0.1:5000 --messages simulated,lies", "--messages: message type 'lies'"},
      {stream, "nothing to stream to"},
      {stream + "--to 127.0.0.1", "'127.0.0.1': no port"},
      {stream + "--to 127.0.0.1:0", "port 0 is not a destination"},
      {stream + "--to 127.0.0.1:5000 --from-cycle 101", "--from-cycle: cycle 101 is not in 0..100"},
      {stream + "--to 239.1.2.3:5000 --multicast-interface lo", "--multicast-interface: 'lo' is not an IPv4 address"},
      {"listen --sensors 0,x", "--sensors: 0,x: expected sensor indices 0..31"},
      {"listen --messages lies", "--messages: message type 'lies'"},
      {"listen --group 10.1.2.3", "--group: 10.1.2.3: not a multicast group"},
      {"listen --bind 300.1.1.1", "--bind: 300.1.1.1: not an IP address"},
      {"listen --group 239.1.2.3 --interface eth0", "--interface: eth0: not an IP address"},
      {"listen --subscribe 127.0.0.1:x", "--subscribe: '127.0.0.1:x'"},
  };
  for (const auto& [args, message] : cases) {
    const bool listen = args.rfind("listen ", 0) == 0;  // and the capture it would write
    const auto r = run_usage(args + (listen ? " -o " + (dir_ / "out.csv").string() : std::string()));
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_TRUE(output_has(r, message)) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out.csv"));
}

}  // namespace rcsim::stream_command_test
