#include "array/firing_schedule.hpp"

#include <algorithm>
#include <cmath>

#include "pixel/pixel_draws.hpp"

static_assert(sizeof(aesim::FiringSchedule::Slot) <= 56, "pixel record grew");

namespace aesim {
namespace {

// A periodic tile's windows: about this many firings a pixel each, so that visiting every pixel
// once a window costs little beside its firings.
constexpr double kWindowFirings = 4;
// With shot noise an integration's electron count is Gamma(N): at N = 10 its spread is a third of
// the mean, and a window's firings exceed their expected count by the room's 3 per pixel (plus
// 64) with a probability far below one in 10^30.
constexpr double kWindowElectrons = 10;

}  // namespace

FiringSchedule::FiringSchedule(const PixelParams& pixel, const SimParams& sim, const Photocurrents& photocurrents,
                               const AddressMap& map, std::uint32_t tile, bool windows)
    : photocurrents_(photocurrents),
      sensor_(pixel_sensor(pixel)),
      t_end_(sim.duration),
      tile_(tile),
      cols_(static_cast<std::uint32_t>(map.cols())),
      calendar_(0, 0) {
  x0_ = tile % static_cast<std::uint32_t>(map.tiles_per_row()) * static_cast<std::uint32_t>(map.tile_cols());
  y0_ = tile / static_cast<std::uint32_t>(map.tiles_per_row()) * static_cast<std::uint32_t>(map.tile_rows());
  xbits_ = static_cast<std::uint32_t>(map.xbits());
  std::vector<WakeCalendar::Entry> entries;
  std::vector<double> periods;
  const std::uint32_t x1 = std::min<std::uint32_t>(x0_ + map.tile_cols(), cols_);
  const std::uint32_t y1 = std::min<std::uint32_t>(y0_ + map.tile_rows(), static_cast<std::uint32_t>(map.rows()));
  // Sized once for every pixel of the tile: grown by doubling, the vectors of thousands of tiles
  // left freed blocks the allocator could not reuse (60 MiB more resident at 2048x2048).
  const std::size_t tile_pixels = std::size_t(x1 - x0_) * (y1 - y0_);
  pixels_.reserve(tile_pixels);
  entries.reserve(tile_pixels);
  periods.reserve(tile_pixels);
  for (std::uint32_t y = y0_; y < y1; ++y) {
    for (std::uint32_t x = x0_; x < x1; ++x) {
      const std::uint32_t index = y * cols_ + x;
      const double current = photocurrents.current(0, index);
      const std::uint32_t boundary = boundary_after(0, index);
      if (!(current > 0) && boundary == kNoBoundary) continue;  // dark for the whole run
      SplitMix64 noise = shot_noise_stream(sim.seed, index);
      const double threshold = pixel_threshold(pixel, sim.seed, index);
      Slot p;
      static_cast<IntegrateFire&>(p) =
          IntegrateFire(sensor_, threshold, 0.0, current, initial_fraction(pixel, sim.seed, index), noise);
      p.next_boundary = boundary;
      const double t = wake_time(p);
      if (!(t <= t_end_)) continue;  // nothing happens to it within the run
      entries.push_back({t, map.bus_address({x, y}), static_cast<std::uint32_t>(pixels_.size())});
      if (current > 0) periods.push_back(threshold / current + sensor_.t_reset);
      pixels_.push_back(p);
      if (sensor_.shot_noise) shot_noise_.push_back({noise, threshold});
    }
  }
  // A mostly dark tile gives back what it does not use.
  if (pixels_.size() < pixels_.capacity() / 2) pixels_.shrink_to_fit();
  // Shot noise keeps windows while every pixel's swing is at least kWindowElectrons: a window's
  // firings then stay so close to the mean count that the room made for them is never short.
  periodic_ = windows && !pixels_.empty() &&
              std::all_of(pixels_.begin(), pixels_.end(), [](const Slot& p) { return p.next_boundary == kNoBoundary; }) &&
              std::all_of(shot_noise_.begin(), shot_noise_.end(), [](const IntegrateFire::ShotNoise& n) {
                return n.threshold >= kWindowElectrons * kElectronCharge;
              });
  if (periodic_) {
    // Every pixel is lit (a pixel dark all run has no slot), so the rate is the sum of its rates.
    for (const double period : periods) rate_ += 1 / period;
    window_ = kWindowFirings * static_cast<double>(pixels_.size()) / rate_;
    keys_.reserve(entries.size());
    for (const WakeCalendar::Entry& e : entries) keys_.push_back(e.key);
    return;
  }
  // A year of twice the median period keeps the brighter half of the pixels, and most of their
  // neighbours in brightness, in the buckets; the light of the first frame sets it.
  double horizon = t_end_;
  if (!periods.empty()) {
    auto middle = periods.begin() + static_cast<std::ptrdiff_t>(periods.size() / 2);
    std::nth_element(periods.begin(), middle, periods.end());
    horizon = std::min(2 * *middle, t_end_);
  }
  calendar_ = WakeCalendar(pixels_.size(), horizon);
  for (const WakeCalendar::Entry& e : entries) calendar_.push(e.slot, e.t, e.key);
}

std::uint32_t FiringSchedule::boundary_after(std::uint64_t boundary, std::size_t index) const {
  const std::uint64_t b = photocurrents_.next_change(boundary, index);
  // A boundary past the run is as good as none (sim.duration * frame rate < 2^32 is validated).
  return b == Photocurrents::kNoChange || photocurrents_.boundary_time(b) > t_end_ ? kNoBoundary
                                                                                   : static_cast<std::uint32_t>(b);
}

std::size_t FiringSchedule::fill_periodic(AddressEvent* out, std::size_t capacity, double until) {
  std::size_t filled = 0;
  const double last = std::min(until, t_end_);
  while (filled < capacity) {
    if (!made_) {
      if (!(made_to_ < last)) break;
      // At least one representable step, so that every window moves on.
      make_window(std::min(last, std::max(made_to_ + window_, std::nextafter(made_to_, last))));
      continue;
    }
    // Through locals: the events' stores would make the compiler reload members every time.
    const FiringWindow::Firing* next = next_;
    const auto room = static_cast<std::ptrdiff_t>(capacity - filled);
    const FiringWindow::Firing* const end = made_->end() - next > room ? next + room : made_->end();
    const std::uint32_t tile = tile_, x0 = x0_, y0 = y0_, xbits = xbits_, xmask = (1u << xbits_) - 1;
    for (; next != end && next->t <= until; ++next) {
      AddressEvent& e = out[filled++];
      e.t = next->t;
      e.x = x0 + (next->key & xmask);
      e.y = y0 + (next->key >> xbits);
      e.tile = tile;
      e.bus_address = next->key;
      e.flags = kNormalEvent;
    }
    next_ = next;
    if (next_ == made_->end()) {
      FiringWindow::give_back(std::move(made_));
    } else if (!(next_->t <= until)) {
      break;
    }
  }
  return filled;
}

void FiringSchedule::make_window(double to) {
  std::unique_ptr<FiringWindow> window = FiringWindow::take();
  const std::size_t n = pixels_.size();
  // A pixel fires at most (to - from) / period + 1 times in the window, one more at each end for
  // rounding; room for a little over the sum, so that the loop below never has to grow it (the
  // writer would report a shortfall rather than write past it).
  const double most = (to - made_to_) * rate_ * (1 + 1e-9) + 3.0 * static_cast<double>(n) + 64;
  FiringWindow::Writer writer =
      window->start(made_to_, to, static_cast<std::size_t>((to - made_to_) * rate_), static_cast<std::size_t>(most));
  Slot* const pixels = pixels_.data();
  const std::uint32_t* const keys = keys_.data();
  // Pixel by pixel, so in bus-address order; each pixel's firings in time order.
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t key = keys[i];
    if (shot_noise_.empty()) {
      pixels[i].fire_through(sensor_, no_noise_, to, [&writer, key](double t) { writer.add(t, key); });
    } else {
      pixels[i].fire_through_noisy(sensor_, shot_noise_[i], to, [&writer, key](double t) { writer.add(t, key); });
    }
  }
  window->finish(writer);
  made_to_ = to;
  if (window->first() == window->end()) {
    FiringWindow::give_back(std::move(window));
  } else {
    next_ = window->first();
    made_ = std::move(window);
  }
}

std::size_t FiringSchedule::fill_from_calendar(AddressEvent* out, std::size_t capacity, double until) {
  std::size_t filled = 0;
  WakeCalendar::Entry top;
  const auto time_of = [this](std::uint32_t slot) { return wake_time(pixels_[slot]); };
  while (filled < capacity && calendar_.peek(top, time_of) && top.t <= until) {
    calendar_.pop();
    const std::uint32_t slot = top.slot;
    // Large arrays stream through their pixels' state in time order: fetch the next pixel's record
    // while this one is worked on.
    if (const WakeCalendar::Entry* after = calendar_.following()) __builtin_prefetch(&pixels_[after->slot]);
    Slot& p = pixels_[slot];
    // Under light that never changes again the wake-up is the firing, at the time it was queued.
    const bool still = p.next_boundary == kNoBoundary;
    const double t_fire = still ? top.t : p.next_fire();
    const double t_boundary = still ? kNever : photocurrents_.boundary_time(p.next_boundary);
    if (fires_first(t_fire, t_boundary)) {
      AddressEvent& firing = out[filled++];
      firing.t = t_fire;
      firing.x = x_of(top.key);
      firing.y = y_of(top.key);
      firing.tile = tile_;
      firing.bus_address = top.key;
      firing.flags = kNormalEvent;
      p.fire(sensor_, noise(slot));
    } else {
      const std::size_t index = std::size_t(y_of(top.key)) * cols_ + x_of(top.key);
      p.set_current(sensor_, t_boundary, photocurrents_.current(p.next_boundary, index));
      p.next_boundary = boundary_after(p.next_boundary, index);
    }
    const double t_next = p.next_boundary == kNoBoundary ? p.next_fire() : wake_time(p);
    if (t_next <= t_end_) calendar_.push(slot, t_next, top.key);
  }
  return filled;
}

}  // namespace aesim
