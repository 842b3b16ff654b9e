#pragma once
// The random generator passed explicitly to every stage that draws (STYLE.md: Drake's
// RandomGenerator). xoshiro256** seeded through SplitMix64; normal variates by Marsaglia's polar
// method (two per round, the second kept), written here so that the draws are identical on every
// standard library.
#include <cmath>
#include <cstdint>

namespace rcsim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0, std::uint64_t stream = 0) {
    std::uint64_t x = seed ^ (0x9E3779B97F4A7C15ULL * (stream + 1));
    for (auto& word : state_) word = splitmix64(x);
  }

  std::uint64_t next_u64() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1).
  double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

  // Standard normal variate.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform01() - 1.0;
      v = 2.0 * uniform01() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * scale;
    has_spare_ = true;
    return u * scale;
  }

  // Exponential variate with the given mean.
  double exponential(double mean) { return -mean * std::log(1.0 - uniform01()); }

  // Poisson variate by Knuth's multiplication method (fine for small means).
  int poisson(double mean) {
    // Knuth's product of uniforms holds while exp(-mean) is far from underflow; a larger mean is a
    // sum of Poisson draws of at most kPoissonChunk each (exact: Poisson means add).
    if (mean > kPoissonChunk) {
      const double chunks = std::ceil(mean / kPoissonChunk);
      int count = 0;
      for (double k = 0; k < chunks; ++k) count += poisson(mean / chunks);
      return count;
    }
    const double limit = std::exp(-mean);
    int count = 0;
    double product = uniform01();
    while (product > limit && count < 4 * static_cast<int>(kPoissonChunk)) {
      ++count;
      product *= uniform01();
    }
    return count;
  }

 private:
  static constexpr double kPoissonChunk = 500.0;
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static std::uint64_t splitmix64(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace rcsim
