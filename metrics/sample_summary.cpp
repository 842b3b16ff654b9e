#include "metrics/sample_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rcsim::metrics {

namespace {

// One side as bins: (first key, counts), a sample's bin key k has its centre at k * width.
struct Bins {
  std::int64_t first_key = 0;
  std::vector<std::uint64_t> counts;
  std::uint64_t total = 0;
};

}  // namespace

void SampleSummary::add(float value) {
  ++count_;
  if (!binned_) {
    exact_.push_back(value);
    if (exact_.size() > kExactCapacity) fold();
    return;
  }
  add_to_bin(value, 1);
}

void SampleSummary::fold() {
  binned_ = true;
  for (const float v : exact_) add_to_bin(v, 1);
  std::vector<float>().swap(exact_);  // its memory too
}

void SampleSummary::add_to_bin(double value, std::uint64_t count) {
  const double k = std::round(value / bin_width_);
  const double limit = static_cast<double>(std::numeric_limits<std::int32_t>::max());
  const auto key = static_cast<std::int64_t>(std::clamp(std::isfinite(k) ? k : 0.0, -limit, limit));
  if (bins_.empty()) {
    first_key_ = key;
    bins_.assign(1, 0);
  }
  if (key < first_key_) {
    const auto grow = static_cast<std::size_t>(first_key_ - key);
    if (bins_.size() + grow > kMaxBins) {
      bins_.front() += count;
      return;
    }
    bins_.insert(bins_.begin(), grow, 0);
    first_key_ = key;
  } else if (key >= first_key_ + static_cast<std::int64_t>(bins_.size())) {
    const auto size = static_cast<std::size_t>(key - first_key_) + 1;
    if (size > kMaxBins) {
      bins_.back() += count;
      return;
    }
    bins_.resize(size, 0);
  }
  bins_[static_cast<std::size_t>(key - first_key_)] += count;
}

std::size_t SampleSummary::memory_bytes() const {
  return exact_.capacity() * sizeof(float) + bins_.capacity() * sizeof(std::uint64_t);
}

DistributionDistance distribution_distance(const SampleSummary& a, const SampleSummary& b) {
  if (!a.binned_ && !b.binned_) {
    return distribution_distance(std::vector<double>(a.exact_.begin(), a.exact_.end()),
                                 std::vector<double>(b.exact_.begin(), b.exact_.end()));
  }
  // Both sides as bins of the same width.
  const auto as_bins = [](const SampleSummary& s) {
    SampleSummary copy(s.bin_width_);
    if (s.binned_) {
      copy.first_key_ = s.first_key_;
      copy.bins_ = s.bins_;
    } else {
      for (const float v : s.exact_) copy.add_to_bin(v, 1);
    }
    Bins bins{copy.first_key_, std::move(copy.bins_), 0};
    for (const auto c : bins.counts) bins.total += c;
    return bins;
  };
  const Bins x = as_bins(a), y = as_bins(b);
  DistributionDistance d;
  d.n_recorded = static_cast<int>(std::min<std::size_t>(a.count_, std::numeric_limits<int>::max()));
  d.n_simulated = static_cast<int>(std::min<std::size_t>(b.count_, std::numeric_limits<int>::max()));
  if (x.total == 0 || y.total == 0) {
    d.wasserstein1 = d.kolmogorov_smirnov = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  // Sweep the bins of both from the lowest key: between consecutive centres the CDFs are constant.
  const std::int64_t from = std::min(x.first_key, y.first_key);
  const std::int64_t until = std::max(x.first_key + static_cast<std::int64_t>(x.counts.size()),
                                      y.first_key + static_cast<std::int64_t>(y.counts.size()));
  const auto count_at = [](const Bins& bins, std::int64_t key) -> std::uint64_t {
    const std::int64_t i = key - bins.first_key;
    return i >= 0 && i < static_cast<std::int64_t>(bins.counts.size()) ? bins.counts[static_cast<std::size_t>(i)] : 0;
  };
  const double n_x = static_cast<double>(x.total), n_y = static_cast<double>(y.total);
  std::uint64_t below_x = 0, below_y = 0;
  double largest_share = 0.0;
  for (std::int64_t key = from; key < until; ++key) {
    const std::uint64_t cx = count_at(x, key), cy = count_at(y, key);
    below_x += cx;
    below_y += cy;
    largest_share = std::max({largest_share, static_cast<double>(cx) / n_x, static_cast<double>(cy) / n_y});
    const double gap = std::abs(static_cast<double>(below_x) / n_x - static_cast<double>(below_y) / n_y);
    d.kolmogorov_smirnov = std::max(d.kolmogorov_smirnov, gap);
    if (key + 1 < until) d.wasserstein1 += gap * a.bin_width_;  // ∫ |F_x − F_y| dx to the next centre
  }
  d.wasserstein1_bound = a.bin_width_;
  d.kolmogorov_smirnov_bound = largest_share;
  return d;
}

}  // namespace rcsim::metrics
