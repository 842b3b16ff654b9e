#pragma once
// Fuzz entry points of what `rcsim replay` and `rcsim --calibration` read (docs/fuzzing.md): a
// recording directory (recording.json and its three CSVs) and a calibration directory. The input
// is a bundle (fuzz_support.hpp) laid over a small valid base in tests/fuzz/base/, written into a
// scratch directory and read through the same functions the command line uses.
#include "fuzz/fuzz_support.hpp"
#include "io/recording.hpp"
#include "replay/import/calibration.hpp"
#include "replay/run/replay_run.hpp"

namespace rcsim::fuzz {

// Sections: recording.json, ego.csv, objects.csv, targets.csv (base: tests/fuzz/base/recording.txt,
// the first 12 cycles of recordings_synthetic/two_in_one_cell). A recording read_recording
// accepts is replayed (read again as a stream, smoothed, simulated, compared) when it has at most
// kMaxReplayedCycles cycles, as `rcsim replay` would.
inline void fuzz_recording(Input data) {
  constexpr int kMaxReplayedCycles = 100;
  static const std::string base_text = read_source_file("tests/fuzz/base/recording.txt");
  static const std::vector<std::string_view> base = split_sections(base_text);
  const std::vector<std::string_view> input = split_sections(as_text(data));
  const std::filesystem::path dir = fresh_dir("recording");
  write_recording_sections(dir, {section_or_base(input, base, 0), section_or_base(input, base, 1), section_or_base(input, base, 2),
                                 section_or_base(input, base, 3)});
  refusals_are_fine([&] {
    const Recording recording = read_recording(dir);
    if (recording.cycle_count() > kMaxReplayedCycles) return;
    replay::ReplayOptions options;
    options.seed = 1;
    replay::DiscardingSink sink;
    (void)replay::replay_recording_dir(dir, options, sink);
  });
}

// Sections: calibration.json, sensor_srr24.json, model_passenger_car.json (base:
// tests/fuzz/base/calibration.txt, recordings_synthetic/campaign/calibration).
inline void fuzz_calibration(Input data) {
  static const std::string base_text = read_source_file("tests/fuzz/base/calibration.txt");
  static const std::vector<std::string_view> base = split_sections(base_text);
  static constexpr const char* kFiles[] = {"calibration.json", "sensor_srr24.json", "model_passenger_car.json"};
  const std::vector<std::string_view> input = split_sections(as_text(data));
  const std::filesystem::path dir = fresh_dir("calibration");
  for (std::size_t i = 0; i < std::size(kFiles); ++i) write_file(dir / kFiles[i], section_or_base(input, base, i));
  refusals_are_fine([&] {
    const auto calibration = replay::load_calibration(dir.string());
    for (const auto& [name, config] : calibration->sensors) (void)replay::calibrated_sensor(calibration.get(), config);
    for (const auto& [name, model] : calibration->models) (void)replay::calibrated_model(calibration.get(), model);
  });
}

}  // namespace rcsim::fuzz
