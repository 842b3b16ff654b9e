#include "sim/fidelity.hpp"

#include <array>
#include <utility>

namespace rcsim {
namespace {
constexpr std::array<std::pair<std::string_view, Fidelity>, 4> kLevels{{{"full", Fidelity::full},
                                                                        {"no_monopulse", Fidelity::no_monopulse},
                                                                        {"points_only", Fidelity::points_only},
                                                                        {"no_tracking", Fidelity::no_tracking}}};
}  // namespace

std::optional<Fidelity> parse_fidelity(std::string_view name) {
  for (const auto& [n, f] : kLevels) {
    if (n == name) return f;
  }
  return std::nullopt;
}

std::string_view fidelity_name(Fidelity fidelity) {
  for (const auto& [n, f] : kLevels) {
    if (f == fidelity) return n;
  }
  return "full";
}

}  // namespace rcsim
