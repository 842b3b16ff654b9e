#pragma once
// A whole file as text, or an InputError naming it.
#include <filesystem>
#include <string>

namespace rcsim {

std::string read_text_file(const std::filesystem::path& path);

}  // namespace rcsim
