// The control token read from a file (app/cli/control_token.cpp): the first line, without its line
// end, 16 to 64 printable ASCII characters without spaces; anything else refused naming the file.
#include "app/cli/control_token.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "scratch_dir.hpp"

namespace rcsim::control_token_test {

class ControlToken : public rcsim::testing::ScratchDirTest {
 protected:
  ControlToken() : ScratchDirTest("control_token") {}
  std::string file_with(const std::string& text) {
    const auto path = dir_ / "token";
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  // The message of the error reading `text` as a token file, empty if it was accepted.
  std::string refusal(const std::string& text) {
    try {
      cli::read_control_token(file_with(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(ControlToken, TheFirstLineWithoutItsLineEndIsTheToken) {
  EXPECT_EQ(cli::read_control_token(file_with("0123456789abcdef\n")), "0123456789abcdef");  // 16: the shortest
  EXPECT_EQ(cli::read_control_token(file_with("0123456789abcdefXY\r\nsecond line ignored\n")), "0123456789abcdefXY");
  const std::string longest(64, 'k');
  EXPECT_EQ(cli::read_control_token(file_with(longest)), longest);  // no line end at all
}

TEST_F(ControlToken, ATokenOfTheWrongLengthOrWithSpacesIsRefusedNamingTheFile) {
  for (const std::string& text : {std::string("0123456789abcde\n"), std::string(65, 'k'),
                                  std::string("0123456789 abcdef\n"), std::string("0123456789abcdef\t\n"),
                                  std::string("\n0123456789abcdef\n"), std::string("")}) {
    const std::string message = refusal(text);
    EXPECT_NE(message.find((dir_ / "token").string()), std::string::npos) << "accepted: '" << text << "'";
    EXPECT_NE(message.find("16 to 64 printable ASCII characters"), std::string::npos) << message;
  }
}

TEST_F(ControlToken, AMissingFileIsRefusedNamingIt) {
  const auto missing = (dir_ / "no_such_token").string();
  try {
    cli::read_control_token(missing);
    FAIL() << "a missing token file was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

// Issue 51: a world-readable token file was taken without a word. It is still taken (a choice),
// with a warning naming the file, its mode and the chmod that keeps it private.
TEST_F(ControlToken, ATokenFileOthersMayReadOrChangeIsTakenWithAWarning) {
  namespace fs = std::filesystem;
  const std::string path = file_with("0123456789abcdef\n");
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
  const auto warning = cli::control_token_file_warning(path);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find(path + ": the control token file (mode 0604) can be read by other users"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("chmod 600 " + path), std::string::npos) << *warning;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(cli::read_control_token(path), "0123456789abcdef");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), *warning + "\n");
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_write);
  EXPECT_NE(cli::control_token_file_warning(path).value_or("").find("can be changed by other users"), std::string::npos);
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_FALSE(cli::control_token_file_warning(path).has_value());
}

}  // namespace rcsim::control_token_test
