#pragma once
// Importers of real datasets (`rcsim import --from DATASET RAW_DIR -o RECORDING_DIR`): each turns
// one dataset's own layout into an rcsim recording (schemas/recording.md). One file per dataset
// behind this interface; docs/importers.md says how to add one for your own logs.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "io/recording.hpp"

namespace rcsim::replay {

struct DatasetRecording {
  Recording recording;
  std::map<std::string, std::string> extra_files;  // written beside it (sensor configurations)
  std::vector<std::string> warnings;               // what a person should know (skipped objects, ...)
};

// What the user adds to a dataset's own files.
struct DatasetImportOptions {
  // An ego log in ego.csv's columns on the importer's clock (docs/importers.md); empty: the
  // importer uses the dataset's own ego log or, where it has none, estimates the ego motion.
  std::filesystem::path ego_log;
  // --frames: which frames of a dataset of single frames to import, by their number in the
  // dataset ("0-199", "0,4", "0-9,20"; parse_frame_list); empty: all. Only importers of such
  // datasets take it (astyx); the others refuse it.
  std::string frames = {};
  // --mapping: which topic of a log is which radar, the ego, the boxes (--from mcap,
  // schemas/mcap-mapping.md); the others refuse it.
  std::filesystem::path mapping = {};
  // --skip-edges: leave out, and count, scans beyond the ego log and scans or ego poses stamped as
  // the one before (--from mcap), where a real log's edges would otherwise be refused.
  bool skip_edges = false;
};

// One item of a --frames list: a frame number (first == last) or a range first-last.
struct FrameRange {
  long long first = 0, last = 0;
};

// A --frames list, as written: comma-separated whole numbers >= 0 and ranges A-B (A <= B), e.g.
// "0-199", "0,4", "0-9,20"; an InputError naming --frames otherwise (empty items, signs, spaces,
// a range backwards, a number beyond 10^9). Whether the frames exist is the importer's to check,
// item by item, so that a range is never expanded beyond the dataset.
std::vector<FrameRange> parse_frame_list(std::string_view list);

// What an importer that writes its recording straight to disk (a log of any length) wrote.
struct ImportSummary {
  std::string name;
  std::size_t cycles = 0, sensors = 0, objects = 0, targets = 0;
  std::vector<std::string> warnings;  // what a person should know (left out scans, an unfinished log)
};

struct DatasetImporter {
  std::string_view name;         // the value of --from
  std::string_view description;  // one line for --help and docs
  DatasetRecording (*import)(const std::filesystem::path& raw_dir, const DatasetImportOptions& options);
  // The recording written straight into a directory in bounded memory, where the importer can;
  // nullptr: write import()'s recording.
  ImportSummary (*import_to)(const std::filesystem::path& raw_dir, const DatasetImportOptions& options,
                                 const std::filesystem::path& dir) = nullptr;
};

// Every importer, by name.
const std::vector<DatasetImporter>& dataset_importers();
// The importer of that name; an InputError listing the known ones otherwise.
const DatasetImporter& find_dataset_importer(std::string_view name);

}  // namespace rcsim::replay
