#pragma once
// The object model database (paper IV-2): built-in models plus model files, loaded and
// validated once, then read-only.
#include <map>
#include <string>
#include <string_view>

#include "common/json_reader.hpp"
#include "model/object_model.hpp"

namespace rcsim {

// Reads one `rcsim-object-model` document (schemas/object-model.md).
ObjectModel parse_object_model(const JsonField& root);
ObjectModel load_object_model_file(const std::string& path);

class ModelLibrary {
 public:
  // The built-in models (src/model/models/*.json, embedded at build time).
  static ModelLibrary builtin();

  void add(ObjectModel model);
  bool contains(std::string_view name) const { return models_.find(std::string(name)) != models_.end(); }
  const ObjectModel& at(std::string_view name) const;
  const std::map<std::string, ObjectModel>& models() const { return models_; }

 private:
  std::map<std::string, ObjectModel> models_;
};

}  // namespace rcsim
