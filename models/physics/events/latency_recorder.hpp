#pragma once
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace aesim {

struct LatencyStats {
  double mean = 0, p99 = 0, max = 0;  // s, fire to delivery, over delivered events
};

// Fire-to-delivery waits of one tile's delivered events, in bounded memory. Zero waits (most buses
// deliver at once) are only counted. Nonzero waits are kept exactly up to `exact_limit`; past that
// (a saturated arbitrated bus, where every event waits) they go into bins of 1/4096 relative width
// that remember their largest wait, so the 99th percentile is reported high by less than 0.025 %
// while memory stays bounded however long the run. Mean and maximum stay exact.
class LatencyRecorder {
 public:
  explicit LatencyRecorder(std::size_t exact_limit = 1u << 20) : exact_limit_(exact_limit) {}

  void add(double wait) {
    if (!(wait > 0)) {
      ++zeros_;
    } else if (!binned_ && exact_.size() < exact_limit_) {
      exact_.push_back(wait);
    } else {
      bin(wait);
    }
  }
  // add(0) n times.
  void add_zeros(std::uint64_t n) { zeros_ += n; }
  // Takes `other`'s waits (tiles are recorded apart and combined in tile order after the run).
  void absorb(LatencyRecorder& other);
  LatencyStats stats() const;

 private:
  struct Bin {
    std::uint64_t count = 0;
    double max = 0;
  };
  void bin(double wait);
  void to_bins();

  std::size_t exact_limit_;
  std::vector<double> exact_;
  bool binned_ = false;
  std::unordered_map<std::uint64_t, Bin> bins_;
  double binned_sum_ = 0, binned_max_ = 0;
  std::uint64_t binned_count_ = 0;
  std::uint64_t zeros_ = 0;
};

}  // namespace aesim
