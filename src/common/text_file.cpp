#include "common/text_file.hpp"

#include <fstream>
#include <sstream>

#include "common/input_error.hpp"

namespace rcsim {

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rcsim
