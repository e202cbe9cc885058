#include "array/firing_schedule.hpp"

#include <algorithm>

#include "pixel/pixel_draws.hpp"

static_assert(sizeof(aesim::FiringSchedule::Pixel) <= 72, "pixel record grew");

namespace aesim {
namespace {

// Written with bitwise operators so the compiler selects with conditional moves: heap keys are
// random, and mispredicted branches were most of the cost.
inline bool before(const FiringSchedule::Entry& a, const FiringSchedule::Entry& b) {
  return (a.t < b.t) | ((a.t == b.t) & (a.key < b.key));
}

}  // namespace

FiringSchedule::FiringSchedule(const SensorConfig& config, const Photocurrents& light, const AddressMap& map,
                               std::uint32_t tile)
    : light_(light),
      sensor_(pixel_sensor(config)),
      t_end_(config.sim.duration),
      tile_(tile),
      cols_(static_cast<std::uint32_t>(map.cols())) {
  const std::uint32_t tx = tile % static_cast<std::uint32_t>(map.tiles_per_row());
  const std::uint32_t ty = tile / static_cast<std::uint32_t>(map.tiles_per_row());
  const std::uint32_t x0 = tx * static_cast<std::uint32_t>(config.array.tile_cols);
  const std::uint32_t y0 = ty * static_cast<std::uint32_t>(config.array.tile_rows);
  const std::uint32_t x1 = std::min<std::uint32_t>(x0 + config.array.tile_cols, cols_);
  const std::uint32_t y1 = std::min<std::uint32_t>(y0 + config.array.tile_rows, static_cast<std::uint32_t>(map.rows()));
  for (std::uint32_t y = y0; y < y1; ++y) {
    for (std::uint32_t x = x0; x < x1; ++x) {
      const std::uint32_t index = y * cols_ + x;
      const double current = light.current(0, index);
      const std::uint32_t boundary = boundary_after(0, index);
      if (!(current > 0) && boundary == kNoBoundary) continue;  // dark for the whole run
      Pixel p;
      SplitMix64 noise = shot_noise_stream(config, index);
      p.core = IntegrateFire(sensor_, pixel_threshold(config, index), 0.0, current, initial_fraction(config, index),
                             noise);
      p.next_boundary = boundary;
      p.x = static_cast<std::uint16_t>(x);
      p.y = static_cast<std::uint16_t>(y);
      p.bus_address = map.bus_address({x, y});
      const double t = wake_time(p);
      if (!(t <= t_end_)) continue;  // nothing happens to it within the run
      heap_.push_back({t, p.bus_address, static_cast<std::uint32_t>(pixels_.size())});
      pixels_.push_back(p);
      if (sensor_.shot_noise) shot_noise_.push_back(noise);
    }
  }
  for (std::size_t i = heap_.size(); i-- > 0;) sift_down(i);
}

std::uint32_t FiringSchedule::boundary_after(std::uint64_t boundary, std::size_t index) const {
  const std::uint64_t b = light_.next_change(boundary, index);
  // A boundary past the run is as good as none (sim.duration * frame rate < 2^32 is validated).
  return b == Photocurrents::kNoChange || light_.boundary_time(b) > t_end_ ? kNoBoundary
                                                                           : static_cast<std::uint32_t>(b);
}

double FiringSchedule::wake_time(const Pixel& p) const {
  const double boundary = p.next_boundary == kNoBoundary ? kNever : light_.boundary_time(p.next_boundary);
  return std::min(p.core.next_fire(), boundary);
}

void FiringSchedule::sift_down(std::size_t i) {
  const std::size_t n = heap_.size();
  const Entry moving = heap_[i];
  for (;;) {
    const std::size_t first = 4 * i + 1;
    if (first >= n) break;
    std::size_t best = first;
    const std::size_t last = std::min(first + 4, n);
    for (std::size_t c = first + 1; c < last; ++c) {
      if (before(heap_[c], heap_[best])) best = c;
    }
    if (!before(heap_[best], moving)) break;
    heap_[i] = heap_[best];
    i = best;
  }
  heap_[i] = moving;
}

void FiringSchedule::replace_top(double t) {
  // Bottom-up: a pixel's next wake-up usually lands behind most others, so walk the hole down to
  // a leaf along the smallest children, then move the entry back up the little it needs.
  Entry moving = heap_.front();
  moving.t = t;
  const std::size_t n = heap_.size();
  Entry* h = heap_.data();
  std::size_t i = 0;
  for (;;) {
    const std::size_t first = 4 * i + 1;
    std::size_t best = first;
    if (first + 3 < n) {
      // A full family of four: a branch-free tournament.
      const std::size_t a = first + static_cast<std::size_t>(before(h[first + 1], h[first]));
      const std::size_t b = first + 2 + static_cast<std::size_t>(before(h[first + 3], h[first + 2]));
      best = before(h[b], h[a]) ? b : a;
    } else {
      if (first >= n) break;
      for (std::size_t c = first + 1; c < n; ++c) {
        if (before(h[c], h[best])) best = c;
      }
    }
    h[i] = h[best];
    i = best;
  }
  while (i > 0) {
    const std::size_t parent = (i - 1) / 4;
    if (!before(moving, heap_[parent])) break;
    heap_[i] = heap_[parent];
    i = parent;
  }
  heap_[i] = moving;
}

void FiringSchedule::pop_top() {
  heap_.front() = heap_.back();
  heap_.pop_back();
  if (!heap_.empty()) sift_down(0);
}

bool FiringSchedule::next(AddressEvent& firing) {
  while (!heap_.empty()) {
    const std::uint32_t slot = heap_.front().slot;
    Pixel& p = pixels_[slot];
    const double t_fire = p.core.next_fire();
    const double t_boundary = p.next_boundary == kNoBoundary ? kNever : light_.boundary_time(p.next_boundary);
    const bool fires = fires_first(t_fire, t_boundary);
    if (fires) {
      firing.t = t_fire;
      firing.x = p.x;
      firing.y = p.y;
      firing.tile = tile_;
      firing.bus_address = p.bus_address;
      firing.flags = kNormalEvent;
      p.core.fire(sensor_, rng(slot));
    } else {
      const std::size_t index = std::size_t(p.y) * cols_ + p.x;
      p.core.set_current(sensor_, t_boundary, light_.current(p.next_boundary, index));
      p.next_boundary = boundary_after(p.next_boundary, index);
    }
    const double t_next = wake_time(p);
    if (t_next <= t_end_) {
      replace_top(t_next);
    } else {
      pop_top();
    }
    if (fires) return true;
  }
  return false;
}

}  // namespace aesim
