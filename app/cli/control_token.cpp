#include "cli/control_token.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <iostream>

#include "common/input_error.hpp"
#include "common/safe_text.hpp"
#include "common/text_file.hpp"
#include "stream/wire_format.hpp"

namespace rcsim::cli {

std::optional<std::string> control_token_file_warning(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return std::nullopt;  // read_text_file names what is wrong
  const bool others_read = (status.st_mode & S_IROTH) != 0, others_write = (status.st_mode & (S_IWOTH | S_IWGRP)) != 0;
  if (!others_read && !others_write) return std::nullopt;
  return fmt::format("rcsim: warning: {}: the control token file (mode {:04o}) can be {} by other users of this machine, "
                     "who could then steer the stream; `chmod 600 {}` keeps it yours",
                     escape_control_characters(path), status.st_mode & 07777,
                     others_read && others_write ? "read and changed" : others_read ? "read" : "changed",
                     escape_control_characters(path));
}

std::string read_control_token(const std::string& path) {
  const std::string text = read_text_file(path, 4096);
  if (const auto warning = control_token_file_warning(path)) std::cerr << *warning << '\n';
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
