#pragma once
// Fuzz entry point of the Astyx importer (`rcsim import --from astyx`, docs/importers.md,
// docs/fuzzing.md). The input is a bundle (fuzz_support.hpp) laid over a tiny hand-made dataset
// in the dataset's own layout (tests/fuzz/base/astyx.txt: three made-up frames, a stationary
// world seen from an ego at 4 and 6.5 m/s, a car, a truck, a person and a towed object; no real
// data), written as a dataset directory and imported. What the importer accepts it writes as a
// recording, which rcsim must then read back (`rcsim import` then `rcsim replay`).
#include <fmt/format.h>

#include "fuzz/fuzz_support.hpp"
#include "io/recording.hpp"
#include "replay/import/astyx_importer.hpp"

namespace rcsim::fuzz {

// Sections: the --frames list (empty: all); dataset.json; then per frame k: radar_6455/00000k.txt,
// groundtruth_obj3d/00000k.json, calibration/00000k.json, canbus/00000k.json. The frames are
// those of the base or of the input, whichever has more (at most 16); a frame beyond the base's
// takes the base's files of frame k mod 3 where the input has none.
inline std::filesystem::path write_astyx_dataset(Input data, replay::DatasetImportOptions& options) {
  static const std::string base_text = read_source_file("tests/fuzz/base/astyx.txt");
  static const std::vector<std::string_view> base = split_sections(base_text);
  constexpr std::size_t kFixed = 2, kPerFrame = 4, kMaxFrames = 16;
  const std::vector<std::string_view> input = split_sections(as_text(data));
  const std::size_t base_frames = (base.size() - kFixed) / kPerFrame;
  const std::size_t input_frames = input.size() > kFixed ? (input.size() - kFixed + kPerFrame - 1) / kPerFrame : 0;
  const std::size_t frames = std::min(std::max(base_frames, input_frames), kMaxFrames);
  const auto section = [&](std::size_t i) {
    if (i < input.size() && !input[i].empty()) return input[i];
    if (i < kFixed) return base[i];
    const std::size_t k = (i - kFixed) / kPerFrame % base_frames;
    return base[kFixed + k * kPerFrame + (i - kFixed) % kPerFrame];
  };

  const std::filesystem::path dir = fresh_dir("astyx");
  const std::filesystem::path dataset = dir / "raw" / "dataset_astyx_fuzz";
  for (const char* folder : {"radar_6455", "groundtruth_obj3d", "calibration", "canbus"}) {
    std::filesystem::create_directories(dataset / folder);
  }
  // The list as the command line passes it: one argument, no line breaks.
  const std::string_view frames_list = section(0);
  options.frames = std::string(frames_list.substr(0, std::min(frames_list.find('\n'), std::size_t{64})));
  write_file(dataset / "dataset.json", section(1));
  for (std::size_t k = 0; k < frames; ++k) {
    const std::string number = fmt::format("{:06}", k);
    const std::size_t at = kFixed + k * kPerFrame;
    write_file(dataset / "radar_6455" / (number + ".txt"), section(at));
    write_file(dataset / "groundtruth_obj3d" / (number + ".json"), section(at + 1));
    write_file(dataset / "calibration" / (number + ".json"), section(at + 2));
    write_file(dataset / "canbus" / (number + ".json"), section(at + 3));
  }
  return dir;
}

// `rcsim import --from astyx DIR/raw/dataset_astyx_fuzz -o DIR/recording`, then the recording read back.
inline Recording import_astyx_and_read_back(const std::filesystem::path& dir, const replay::DatasetImportOptions& options) {
  const replay::DatasetRecording imported =
      replay::find_dataset_importer("astyx").import(dir / "raw" / "dataset_astyx_fuzz", options);
  const std::filesystem::path out = dir / "recording";
  write_recording(out, imported.recording, imported.extra_files);
  try {
    return read_recording(out);
  } catch (const InputError& e) {
    throw Finding(std::string("rcsim import --from astyx wrote a recording rcsim cannot read: ") + e.what());
  }
}

inline void fuzz_astyx(Input data) {
  replay::DatasetImportOptions options;
  const std::filesystem::path dir = write_astyx_dataset(data, options);
  refusals_are_fine([&] { (void)import_astyx_and_read_back(dir, options); });
}

}  // namespace rcsim::fuzz
