#include "aesim/emulator/emulator.hpp"

#include <cmath>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

#include "aesim/array/queue_model.hpp"
#include "aesim/random/splitmix64.hpp"
#include "aesim/scene/resample.hpp"

namespace aesim {

std::vector<EmulatedEvent> emulate(const std::vector<Image>& frames, const EmulatorSettings& s) {
  std::vector<EmulatedEvent> events;
  SplitMix64 rng = stream_for(s.seed, Stream::EmulatorChaos, 0);
  QueueBudget budget{s.max_events, s.max_events * 100, "--max-events"};
  const Image* previous = nullptr;
  Image prepared_previous;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const int w = s.width > 0 ? s.width : frames[k].width;
    const int h = s.height > 0 ? s.height : frames[k].height;
    const Image frame = clip_levels(resample_area(frames[k], w, h), s.clip_low, s.clip_high);
    std::vector<std::uint32_t> queue;
    switch (s.behaviour) {
      case Behaviour::Intensity: queue = queue_order(intensity_map(frame, s.threshold).pixels, s.f_max, 1.0, &budget, s.spread); break;
      case Behaviour::Edge: queue = queue_order(edge_map(frame, s.threshold).pixels, s.f_max, 1.0, &budget, s.spread); break;
      case Behaviour::Motion:
        if (previous) queue = queue_order(motion_map(frame, *previous, s.threshold).pixels, s.f_max, 1.0, &budget, s.spread);
        break;
      case Behaviour::Centroid:
        if (previous) {
          if (const auto c = motion_centroid(frame, *previous, s.threshold)) {
            queue.push_back(static_cast<std::uint32_t>(std::lround(c->second)) * static_cast<std::uint32_t>(w) +
                            static_cast<std::uint32_t>(std::lround(c->first)));
          }
        }
        break;
    }
    // Random entries can at most double the queue: charge them before they exist.
    budget.entries += s.chaos_in > 0 ? static_cast<double>(queue.size()) : 0.0;
    if (!(budget.entries <= budget.max_entries)) {
      throw InputError(fmt::format("--chaos-in: the frames would hold up to {:.3g} events (limit {:.3g}, --max-events)",
                                   budget.entries, budget.max_entries));
    }
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i : queue) {
      if (s.chaos_out <= 0 || uniform01(rng) >= s.chaos_out) kept.push_back(i);
      if (s.chaos_in > 0 && uniform01(rng) < s.chaos_in) {
        kept.push_back(static_cast<std::uint32_t>(uniform01(rng) * static_cast<double>(w) * h));
      }
    }
    for (std::size_t j = 0; j < kept.size(); ++j) {
      const double t = queue_entry_time(static_cast<double>(k) / s.frame_rate, 1.0 / s.frame_rate, j, kept.size());
      events.push_back({t, kept[j] % static_cast<std::uint32_t>(w), kept[j] / static_cast<std::uint32_t>(w),
                        static_cast<std::uint32_t>(k)});
    }
    prepared_previous = frame;
    previous = &prepared_previous;
  }
  return events;
}

}  // namespace aesim
