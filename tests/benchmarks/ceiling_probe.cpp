#include "ceiling_probe.hpp"

#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

namespace aesim {

std::uint64_t ceiling_probe(const std::vector<double>& periods, const std::vector<double>& phases, double t_end) {
  struct Entry {
    double t;
    std::uint32_t pixel;
  };
  std::size_t buckets = 16;
  while (buckets < periods.size()) buckets *= 2;
  std::vector<double> sorted = periods;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double width = 2 * sorted[sorted.size() / 2] / static_cast<double>(buckets);
  std::vector<std::vector<Entry>> ring(buckets);
  for (std::uint32_t i = 0; i < periods.size(); ++i) {
    ring[static_cast<std::size_t>(phases[i] / width) & (buckets - 1)].push_back({phases[i], i});
  }
  std::vector<std::uint64_t> records;
  records.reserve(1 << 16);
  std::uint64_t events = 0;
  const std::size_t last = static_cast<std::size_t>(t_end / width);
  for (std::size_t now = 0; now <= last; ++now) {
    std::vector<Entry>& bucket = ring[now & (buckets - 1)];
    // Entries pushed back into this bucket are served in this pass too.
    for (std::size_t k = 0; k < bucket.size();) {
      const Entry e = bucket[k];
      if (e.t >= static_cast<double>(now + 1) * width) {
        ++k;  // a later year's entry
        continue;
      }
      bucket[k] = bucket.back();
      bucket.pop_back();
      if (e.t > t_end) continue;
      records.push_back((std::uint64_t(e.pixel) << 32) | static_cast<std::uint32_t>(e.t * 1e6));
      if (records.size() == records.capacity()) {
        benchmark::DoNotOptimize(records.data());
        records.clear();
      }
      ++events;
      const Entry again{e.t + periods[e.pixel], e.pixel};
      ring[static_cast<std::size_t>(again.t / width) & (buckets - 1)].push_back(again);
    }
  }
  benchmark::DoNotOptimize(records.data());
  return events;
}

}  // namespace aesim
