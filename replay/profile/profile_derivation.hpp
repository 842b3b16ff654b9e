#pragma once
// `rcsim profile derive` (docs/profile-derive.md): a sensor profile read off real recordings, as
// the paper's parameters are "derived by inspection of real radar data" (II-C, III-B). Every value
// the data can show is measured and comes with its evidence; the rest is the base profile's,
// marked so.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "replay/profile/derivation_figures.hpp"
#include "replay/profile/derived_value.hpp"

namespace rcsim::replay::profile {

struct DeriveOptions {
  // The base profile: a built-in name or an rcsim-sensor file; empty: the recordings' own type.
  std::string base;
  std::string name;  // the derived profile's name
  std::uint64_t seed = 0;
};

struct ProfileDerivation {
  nlohmann::ordered_json profile;  // a valid rcsim-sensor document
  std::vector<DerivedValue> values;  // in the profile's order of derivation; base values hold the base's
  std::vector<DerivationFigure> figures;  // what they were read from (--report)
  std::string base;                  // what the base was
  long long detections = 0, sensor_cycles = 0;
};

// InputError naming the recording and what is missing for recordings a profile cannot come from
// (tracks only, one cycle, too few detections, all at one place) or an unknown base.
ProfileDerivation derive_profile(const std::vector<const Recording*>& recordings, const DeriveOptions& options);

}  // namespace rcsim::replay::profile
