#pragma once
// --seed N, one option for every command that draws random numbers: one type (a whole number in
// 0..2^63-1, which the report database stores as it is) and one default.
#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdint>
#include <limits>
#include <string>

namespace rcsim::cli {

inline constexpr std::uint64_t kDefaultSeed = 0;
inline constexpr std::uint64_t kMaxSeed = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());

// Refuses "-1", "1.5", "1e3", "0x10" and seeds beyond kMaxSeed in one short line.
inline std::string seed_text_error(const std::string& text) {
  std::uint64_t seed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed);
  const bool whole = !text.empty() && error == std::errc() && end == text.data() + text.size();
  if (whole && seed <= kMaxSeed) return {};
  return "must be a whole number in 0.." + std::to_string(kMaxSeed) + ", got '" + text + "'";
}

inline CLI::Option* add_seed_option(CLI::App& cmd, std::uint64_t& seed, const std::string& what) {
  seed = kDefaultSeed;
  return cmd.add_option("--seed", seed, what)
      ->type_name("UINT")
      ->check(CLI::Validator([](std::string& text) { return seed_text_error(text); }, ""))
      ->capture_default_str();
}

}  // namespace rcsim::cli
