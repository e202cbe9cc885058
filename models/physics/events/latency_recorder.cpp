#include "aesim/events/latency_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aesim {
namespace {

// Sign, exponent and the top 12 mantissa bits of a positive double: bins 2^-12 wide, relatively.
std::uint64_t bin_of(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits >> 40;
}

}  // namespace

void LatencyRecorder::bin(double wait) {
  if (!binned_) to_bins();
  Bin& b = bins_[bin_of(wait)];
  ++b.count;
  b.max = std::max(b.max, wait);
  binned_sum_ += wait;
  binned_max_ = std::max(binned_max_, wait);
  ++binned_count_;
}

void LatencyRecorder::to_bins() {
  binned_ = true;
  std::vector<double> exact;
  exact.swap(exact_);
  for (double v : exact) bin(v);
}

void LatencyRecorder::absorb(LatencyRecorder& other) {
  zeros_ += other.zeros_;
  if (!other.binned_ && !binned_ && exact_.size() + other.exact_.size() <= exact_limit_) {
    exact_.insert(exact_.end(), other.exact_.begin(), other.exact_.end());
  } else {
    if (!binned_) to_bins();
    for (double v : other.exact_) bin(v);
    for (const auto& [key, b] : other.bins_) {
      Bin& mine = bins_[key];
      mine.count += b.count;
      mine.max = std::max(mine.max, b.max);
    }
    binned_sum_ += other.binned_sum_;
    binned_max_ = std::max(binned_max_, other.binned_max_);
    binned_count_ += other.binned_count_;
  }
  other = LatencyRecorder(other.exact_limit_);
}

LatencyStats LatencyRecorder::stats() const {
  LatencyStats s;
  const std::uint64_t waits = binned_ ? binned_count_ : exact_.size();
  if (waits == 0) return s;
  const std::uint64_t n = waits + zeros_;
  // Nearest-rank 99th percentile over all delivered events, the zero waits first.
  const std::uint64_t rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(0.99 * static_cast<double>(n))));
  if (!binned_) {
    std::vector<double> sorted = exact_;
    std::sort(sorted.begin(), sorted.end());
    double sum = 0;
    for (double v : sorted) sum += v;
    s.mean = sum / static_cast<double>(n);
    s.p99 = rank <= zeros_ ? 0.0 : sorted[rank - zeros_ - 1];
    s.max = sorted.back();
    return s;
  }
  std::vector<std::pair<std::uint64_t, Bin>> ordered(bins_.begin(), bins_.end());
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  s.mean = binned_sum_ / static_cast<double>(n);
  s.max = binned_max_;
  if (rank > zeros_) {
    std::uint64_t seen = zeros_;
    for (const auto& [key, b] : ordered) {
      seen += b.count;
      if (seen >= rank) {
        s.p99 = b.max;
        break;
      }
    }
  }
  return s;
}

}  // namespace aesim
