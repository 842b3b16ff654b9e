#pragma once
// A recording written row by row (schemas/recording.md), for importers that stream a log of any
// length through bounded memory; write_recording (io/recording.hpp) writes a whole Recording
// through it. The directory is made complete or not at all: the files grow in a temporary sibling
// directory (`.NAME.tmp.PID`) through 1 MiB buffers, and finish() renames it into place (an
// earlier recording of that name replaced only then); a writer destroyed unfinished removes it.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/recording.hpp"

namespace rcsim {

// Which of targets.csv's optional columns the rows give: every row, or none (the reader refuses
// empty fields).
struct TargetColumns {
  bool id = false, rcs_dbsm = false, snr_db = false, elevation_rad = false;
};

class RecordingWriter {
 public:
  // `sensor_ids` name the targets' and cycles' sensors by index; cycles.csv is written where
  // `own_clocks` (version 4). Refuses (InputError) a directory that is not a recording's or whose
  // parent cannot be made.
  RecordingWriter(const std::filesystem::path& dir, std::vector<std::string> sensor_ids, TargetColumns columns, bool own_clocks);
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;
  ~RecordingWriter();

  // Rows in the files' order: ego rows and boxes in time order (boxes of one time in the
  // recording's object order), targets and cycles by cycle.
  void ego(const EgoSample& e);
  void box(const std::string& object_id, const AnnotatedBox& b);
  void target(const RecordedTarget& t);  // std::invalid_argument where a column's value is missing
  void cycle(const SensorCycle& c);

  // recording.json from `header` (its rows are not read: the ones written are the recording's),
  // `extra_files` beside it, then the directory into place.
  void finish(const Recording& header, const std::map<std::string, std::string>& extra_files = {});

 private:
  struct Files;
  std::filesystem::path target_, parent_, name_, temp_;
  std::vector<std::string> sensor_ids_;
  TargetColumns columns_;
  std::unique_ptr<Files> files_;
  std::size_t cycles_ = 0;
  bool finished_ = false;
};

// The optional columns a recording's targets give (every target, or the column is not written).
TargetColumns target_columns(const Recording& rec);

}  // namespace rcsim
