#pragma once
// Fuzz entry point of the importers of real datasets (`rcsim import --from aimotive`,
// docs/importers.md, docs/fuzzing.md). The input is a bundle (fuzz_support.hpp) laid over a tiny
// hand-made sequence in the dataset's own layout (tests/fuzz/base/aimotive.txt: made-up numbers,
// no real data), written as a sequence directory and imported. What the importer accepts it
// writes as a recording, which rcsim must then read back (`rcsim import` then `rcsim replay`).
#include <fmt/format.h>

#include "fuzz/fuzz_support.hpp"
#include "io/recording.hpp"
#include "replay/import/aimotive_importer.hpp"

namespace rcsim::fuzz {

// Sections: sensor/calibration/calibration.json; an ego log given with --ego-log (empty: none);
// then per keyframe k: dynamic/box/3d_body/frame_k.json, sensor/radar/B_LRR_C/B_LRR_C_k.json,
// sensor/radar/F_LRR_C/F_LRR_C_k.json. The keyframes are those of the base or of the input,
// whichever has more; a keyframe beyond the base's takes the base's files of keyframe k mod 5
// where the input has none (same timestamp: refused, unless the input gives its own).
inline std::filesystem::path write_aimotive_sequence(Input data, replay::DatasetImportOptions& options) {
  static const std::string base_text = read_source_file("tests/fuzz/base/aimotive.txt");
  static const std::vector<std::string_view> base = split_sections(base_text);
  constexpr std::size_t kFixed = 2, kPerKeyframe = 3, kMaxKeyframes = 64;
  const std::vector<std::string_view> input = split_sections(as_text(data));
  const std::size_t base_keyframes = (base.size() - kFixed) / kPerKeyframe;
  const std::size_t input_keyframes = input.size() > kFixed ? (input.size() - kFixed + kPerKeyframe - 1) / kPerKeyframe : 0;
  const std::size_t keyframes = std::min(std::max(base_keyframes, input_keyframes), kMaxKeyframes);
  const auto section = [&](std::size_t i) {
    if (i < input.size() && !input[i].empty()) return input[i];
    if (i < kFixed) return base[i];
    const std::size_t k = (i - kFixed) / kPerKeyframe % base_keyframes;
    return base[kFixed + k * kPerKeyframe + (i - kFixed) % kPerKeyframe];
  };

  const std::filesystem::path dir = fresh_dir("aimotive");
  const std::filesystem::path sequence = dir / "raw" / "fuzz_sequence";
  std::filesystem::create_directories(sequence / "sensor" / "calibration");
  std::filesystem::create_directories(sequence / "dynamic" / "box" / "3d_body");
  std::filesystem::create_directories(sequence / "sensor" / "radar" / "B_LRR_C");
  std::filesystem::create_directories(sequence / "sensor" / "radar" / "F_LRR_C");
  write_file(sequence / "sensor" / "calibration" / "calibration.json", section(0));
  if (const std::string_view ego_log = section(1); !ego_log.empty()) {
    options.ego_log = dir / "ego_log.csv";
    write_file(options.ego_log, ego_log);
  }
  for (std::size_t k = 0; k < keyframes; ++k) {
    const std::string number = fmt::format("{:07}", 1000 + k);
    const std::size_t at = kFixed + k * kPerKeyframe;
    write_file(sequence / "dynamic" / "box" / "3d_body" / ("frame_" + number + ".json"), section(at));
    write_file(sequence / "sensor" / "radar" / "B_LRR_C" / ("B_LRR_C_" + number + ".json"), section(at + 1));
    write_file(sequence / "sensor" / "radar" / "F_LRR_C" / ("F_LRR_C_" + number + ".json"), section(at + 2));
  }
  return dir;
}

// `rcsim import --from aimotive DIR/raw -o DIR/recording`, then the recording read back.
inline Recording import_aimotive_and_read_back(const std::filesystem::path& dir, const replay::DatasetImportOptions& options) {
  const replay::DatasetRecording imported = replay::find_dataset_importer("aimotive").import(dir / "raw", options);
  const std::filesystem::path out = dir / "recording";
  write_recording(out, imported.recording, imported.extra_files);
  try {
    return read_recording(out);
  } catch (const InputError& e) {
    throw Finding(std::string("rcsim import --from aimotive wrote a recording rcsim cannot read: ") + e.what());
  }
}

inline void fuzz_aimotive(Input data) {
  replay::DatasetImportOptions options;
  const std::filesystem::path dir = write_aimotive_sequence(data, options);
  refusals_are_fine([&] { (void)import_aimotive_and_read_back(dir, options); });
}

}  // namespace rcsim::fuzz
