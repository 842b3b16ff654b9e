#pragma once
// The samples of one quantity over a run, for its distribution distances
// (distribution_distance.hpp), in memory bounded whatever the run's length:
// - up to kExactCapacity samples they are kept as they are (float), and the distances are exact;
// - beyond, they are folded into a histogram of fixed bins of `bin_width` (per quantity, a
//   stated resolution), and the distances are computed between the bin centres. Moving every
//   sample to its bin centre moves it by at most half a bin, so the Wasserstein-1 distance is off
//   by at most one bin width (half for each side); the Kolmogorov–Smirnov statistic, evaluated at
//   the bin edges, is off by at most the largest share of either sample in one bin. Both bounds
//   are returned with the distance (docs/metrics.md).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "metrics/distribution_distance.hpp"

namespace rcsim::metrics {

class SampleSummary {
 public:
  static constexpr std::size_t kExactCapacity = std::size_t{1} << 18;  // 1 MiB of floats
  // Bins beyond this many are refused (the value range of a quantity is bounded by the inputs'
  // limits, schemas/recording.md); their samples are counted in the nearest end bin.
  static constexpr std::size_t kMaxBins = std::size_t{1} << 22;

  explicit SampleSummary(double bin_width) : bin_width_(bin_width) {}
  void add(float value);
  std::size_t size() const { return count_; }
  bool exact() const { return !binned_; }

  // The bins' memory once folded; the exact samples' otherwise (for the memory figures).
  std::size_t memory_bytes() const;

  friend DistributionDistance distribution_distance(const SampleSummary& recorded, const SampleSummary& simulated);

 private:
  void fold();  // the exact samples into bins
  void add_to_bin(double value, std::uint64_t count);
  double bin_width_;
  std::size_t count_ = 0;
  bool binned_ = false;
  std::vector<float> exact_;
  std::int64_t first_key_ = 0;        // key of bins_[0]: the bin of value v is round(v / width)
  std::vector<std::uint64_t> bins_;
};

// Exact when both are exact (then bit-identical to distribution_distance on the samples);
// otherwise between the bin centres, with the bounds set (DistributionDistance::*_bound).
DistributionDistance distribution_distance(const SampleSummary& recorded, const SampleSummary& simulated);

}  // namespace rcsim::metrics
