#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

namespace aesim {

// The least work an event-driven imager simulator can do per event, as a yardstick for the event
// rung measured in the same run: pop the earliest pixel from a calendar queue (a ring of buckets,
// each an intrusive unsorted list, no tie order), add its next period, push it back, append an
// 8-byte record to a cache-resident buffer. No physics, no bus, no merge, no files. Returns the
// events made from `t_begin` until `t_end` (s) by pixels whose next firings are `t` (s, each at or
// after `t_begin`; left at the next firing after `t_end`); `next_period(i)` is pixel i's next
// period (s): a constant for a still scene, a draw from the shot-noise law with it.
// `median_period` sizes the calendar's year.
template <typename NextPeriod>
std::uint64_t ceiling_probe(std::vector<double>& t, double median_period, double t_begin, double t_end,
                            NextPeriod&& next_period) {
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  const std::size_t pixels = t.size();
  std::size_t buckets = 16;
  while (buckets < pixels) buckets *= 2;
  const double per_width = static_cast<double>(buckets) / (2 * median_period);
  // Intrusive lists: a bucket is its first pixel, a pixel names the next; nothing is allocated per
  // event. A year of two median periods holds every pixel of a uniform scene.
  std::vector<std::uint32_t> head(buckets, kNone), next(pixels, kNone);
  auto push = [&](std::uint32_t i) {
    std::uint32_t& h = head[static_cast<std::size_t>(t[i] * per_width) & (buckets - 1)];
    next[i] = h;
    h = i;
  };
  for (std::uint32_t i = 0; i < pixels; ++i) push(i);
  std::vector<std::uint64_t> records;
  records.reserve(1 << 16);
  std::uint64_t events = 0;
  const std::size_t last = static_cast<std::size_t>(t_end * per_width);
  for (std::size_t now = static_cast<std::size_t>(t_begin * per_width); now <= last; ++now) {
    std::uint32_t& h = head[now & (buckets - 1)];
    std::uint32_t later = kNone;  // a later year's pixels met in this bucket
    while (h != kNone) {
      const std::uint32_t i = h;
      h = next[i];
      if (static_cast<std::size_t>(t[i] * per_width) != now) {
        next[i] = later;
        later = i;
        continue;
      }
      if (t[i] > t_end) continue;
      records.push_back((std::uint64_t(i) << 32) | static_cast<std::uint32_t>(t[i] * 1e6));
      if (records.size() == records.capacity()) {
        benchmark::DoNotOptimize(records.data());
        records.clear();
      }
      ++events;
      t[i] += next_period(i);
      push(i);
    }
    h = later;
  }
  benchmark::DoNotOptimize(records.data());
  return events;
}

}  // namespace aesim
