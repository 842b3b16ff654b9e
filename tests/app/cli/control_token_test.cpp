// The control token read from a file (app/cli/control_token.cpp): the first line, without its line
// end, 16 to 64 printable ASCII characters without spaces; anything else refused naming the file.
#include "app/cli/control_token.hpp"

#include <gtest/gtest.h>

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

}  // namespace rcsim::control_token_test
