#pragma once
// Built-in data files compiled into the executable (see cmake/embed_files.cmake).
#include <string_view>
#include <vector>

namespace rcsim {

struct EmbeddedFile {
  std::string_view name;
  std::string_view text;
};

const std::vector<EmbeddedFile>& embedded_object_models();
const std::vector<EmbeddedFile>& embedded_sensor_configs();

}  // namespace rcsim
