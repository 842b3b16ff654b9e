#pragma once
// The page `rcsim profile derive --report FILE.html` writes (docs/profile-derive.md): every value
// of the derived profile with its source and evidence, then the figures it was read from (SNR
// against range and azimuth with the fitted law and pattern, the pair-distance histograms with
// the cells, the noise against SNR margin, the cycle steps). Self-contained HTML, every text
// escaped.
#include <ostream>
#include <string>

#include "replay/profile/profile_derivation.hpp"

namespace rcsim::replay {

void write_profile_report(std::ostream& out, const profile::ProfileDerivation& derivation, const std::string& profile_file);

}  // namespace rcsim::replay
