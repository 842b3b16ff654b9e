#pragma once
// A recording made by the reflection-center model itself: the scene simulated and each sensor's
// list written down as if the sensor had reported it (tracks, or the detections of a sensor that
// reports detections, with the radar's cross-section estimate beside an SNR on the radar
// equation), with the true boxes as annotation (optionally with annotation noise). Used where a
// known answer is needed: harness tests (the model replayed against itself with the same seed must
// agree), `profile derive` given back the profile that made the data, and the replay benchmark's
// hour-long recording.
#include <cstdint>
#include <limits>

#include "io/recording.hpp"
#include "scene/scene.hpp"

namespace rcsim::replay {

struct AnnotationNoise {
  double position_sigma_m = 0.0;
  double yaw_sigma_rad = 0.0;
  // Objects are annotated only while their centre is this close to the ego vehicle (a labelling
  // tool annotates what is in sight).
  double max_range_m = std::numeric_limits<double>::infinity();
};

Recording model_recording(const Scene& scene, const std::string& name, std::uint64_t seed,
                          const AnnotationNoise& noise = {});

}  // namespace rcsim::replay
