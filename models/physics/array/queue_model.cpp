#include "aesim/array/queue_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

std::vector<std::uint32_t> queue_order(const std::vector<double>& values, double full_scale_rate, double frame_time,
                                       QueueBudget* budget, QueueSpread spread) {
  QueueBudget default_budget;
  QueueBudget& b = budget != nullptr ? *budget : default_budget;
  std::vector<std::uint32_t> queue;
  const double p_max = values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
  if (!(p_max > 0)) return queue;  // a black frame enters nothing
  // Per pixel: Literal, round(P_max / P_i) (it enters at the passes that are multiples); Even, its
  // count c_i. 0: never enters.
  std::vector<std::uint64_t> per_pixel(values.size(), 0);
  double passes = 0, entries = 0;
  if (spread == QueueSpread::Literal) {
    passes = std::round(full_scale_rate * p_max * frame_time);
    if (!(passes >= 1)) return queue;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (values[i] > 0) {
        per_pixel[i] = static_cast<std::uint64_t>(std::max(1.0, std::min(std::round(p_max / values[i]), 1e18)));
        entries += std::floor(passes / static_cast<double>(per_pixel[i]));
      }
    }
  } else {
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double count = values[i] > 0 ? std::round(full_scale_rate * values[i] * frame_time) : 0.0;
      per_pixel[i] = static_cast<std::uint64_t>(std::min(count, 1e18));
      passes = std::max(passes, count);
      entries += count;
    }
    if (!(passes >= 1)) return queue;
  }
  b.visits += passes * static_cast<double>(values.size());
  if (!(b.visits <= b.max_visits)) {
    throw InputError(fmt::format("the event queues would visit pixels {:.3g} times (limit {:.3g}, a hundred per {}); "
                                 "lower the rate or raise {}", b.visits, b.max_visits, b.limit, b.limit));
  }
  b.entries += entries;
  if (!(b.entries <= b.max_entries)) {
    throw InputError(fmt::format("the event queues would hold {:.3g} events (limit {:.3g}, {}); lower the rate or raise "
                                 "{}", b.entries, b.max_entries, b.limit, b.limit));
  }
  queue.reserve(static_cast<std::size_t>(entries));
  // The budget bounds passes x pixels to 1e10-ish, so n * c_i stays far below 2^127.
  const auto n_max = static_cast<std::uint64_t>(passes);
  for (std::uint64_t n = 1; n <= n_max; ++n) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::uint64_t v = per_pixel[i];
      if (v == 0) continue;
      const bool enters = spread == QueueSpread::Literal
                              ? n % v == 0
                              : static_cast<unsigned __int128>(n) * v / n_max >
                                    static_cast<unsigned __int128>(n - 1) * v / n_max;
      if (enters) queue.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return queue;
}

std::vector<AddressEvent> queue_events(const PixelParams& pixel, const SimParams& sim,
                                       const Photocurrents& photocurrents, const AddressMap& map,
                                       std::uint64_t* empty_lit_frames) {
  const double f_max = pixel.i_max / pixel.threshold_charge();
  const double duration = sim.duration;
  const bool still = photocurrents.frames() == 1;
  const double frame_time = still ? duration : photocurrents.boundary_time(1);
  std::vector<AddressEvent> events;
  std::vector<double> values(photocurrents.pixels());
  QueueBudget budget{sim.max_events, sim.max_events * 100};
  for (std::uint64_t k = 0;; ++k) {
    const double start = static_cast<double>(k) * frame_time;
    if (start >= duration) break;
    for (std::size_t i = 0; i < values.size(); ++i) {
      values[i] = pixel.i_max > 0 ? (photocurrents.current(still ? 0 : k, i) - pixel.i_dark) / pixel.i_max : 0.0;
    }
    const double length = std::min(frame_time, duration - start);
    const std::vector<std::uint32_t> queue = queue_order(values, f_max, length, &budget);
    if (queue.empty() && empty_lit_frames && *std::max_element(values.begin(), values.end()) > 0) ++*empty_lit_frames;
    for (std::size_t j = 0; j < queue.size(); ++j) {
      const std::uint32_t x = queue[j] % static_cast<std::uint32_t>(map.cols());
      const std::uint32_t y = queue[j] / static_cast<std::uint32_t>(map.cols());
      AddressEvent e = map.event_at({x, y});
      e.t = queue_entry_time(start, length, j, queue.size());
      events.push_back(e);
    }
  }
  return events;
}

}  // namespace aesim
