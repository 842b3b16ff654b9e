#pragma once
// --fidelity NAME, shared by rcsim simulate, replay and stream (docs/fidelity.md).
#include <CLI/CLI.hpp>
#include <string>

#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "replay/run/replay_run.hpp"
#include "sim/fidelity.hpp"

namespace rcsim::cli {

inline void add_fidelity_option(CLI::App& cmd, std::string& name) {
  cmd.add_option("--fidelity", name, std::string("fidelity level: ") + std::string(kFidelityNames) + " (docs/fidelity.md)")
      ->capture_default_str();
}

// The level a recording is compared at unless --fidelity says otherwise (replay_run.hpp).
using replay::default_fidelity_for;

// An unknown name is an input error (exit 2).
inline Fidelity fidelity_from_arg(const std::string& name) {
  const auto fidelity = parse_fidelity(name);
  if (!fidelity) {
    throw InputError("--fidelity", name, std::string("unknown fidelity level; one of ") + std::string(kFidelityNames));
  }
  return *fidelity;
}

}  // namespace rcsim::cli
