#include "cli/control_token.hpp"

#include <fmt/format.h>

#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::cli {

std::string read_control_token(const std::string& path) {
  const std::string text = read_text_file(path, 4096);
  std::string token = text.substr(0, text.find('\n'));
  if (!token.empty() && token.back() == '\r') token.pop_back();
  if (!stream::is_control_token(token)) {
    throw InputError(path, "line 1",
                     fmt::format("a control token is {} to {} printable ASCII characters without spaces (e.g. from "
                                 "`head -c 24 /dev/urandom | base64`)",
                                 stream::kMinControlTokenBytes, stream::kMaxControlTokenBytes));
  }
  return token;
}

}  // namespace rcsim::cli
