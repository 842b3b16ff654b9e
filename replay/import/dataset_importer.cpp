#include "replay/import/dataset_importer.hpp"

#include "common/input_error.hpp"
#include "replay/import/aimotive_importer.hpp"

namespace rcsim::replay {

const std::vector<DatasetImporter>& dataset_importers() {
  static const std::vector<DatasetImporter> importers{
      {"aimotive", "aiMotive Multimodal Dataset sequence (radar detections, 3D boxes, calibration)", import_aimotive},
  };
  return importers;
}

const DatasetImporter& find_dataset_importer(std::string_view name) {
  std::string known;
  for (const DatasetImporter& importer : dataset_importers()) {
    if (importer.name == name) return importer;
    known += (known.empty() ? "" : ", ") + std::string(importer.name);
  }
  throw InputError("--from", "", "unknown dataset '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace rcsim::replay
