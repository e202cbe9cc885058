#include "aesim/array/firing_schedule.hpp"

#include <algorithm>
#include <cmath>

#include "aesim/pixel/pixel_draws.hpp"

static_assert(sizeof(aesim::FiringSchedule::Slot) <= 56, "pixel record grew");

namespace aesim {
namespace {

// A tile's windows: about this many firings a pixel each, so that visiting every pixel once a
// window costs little beside its firings.
constexpr double kWindowFirings = 4;
// A moving scene's tile makes windows when they visit pixels at most this many times as often as
// the calendar would wake them (a visit in pixel order costs a fraction of a wake-up).
constexpr double kVisitsPerCalendarWake = 4;
// With shot noise an integration's electron count is Gamma(N): at N = 10 its spread is a third of
// the mean, and a window's firings exceed their expected count by the room's 3 per pixel (plus
// 64) with a probability far below one in 10^30.
constexpr double kWindowElectrons = 10;
// Below this many firings a pixel a window (a large array's tiles, whose windows end with the
// run's), a pixel's next firing is written whether or not it falls in the window: see
// IntegrateFire::Periodic::count_through.
constexpr double kSpeculateBelow = 2;

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
  std::vector<double> periods, thresholds;
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
      thresholds.push_back(threshold);
      pixels_.push_back(p);
      if (sensor_.shot_noise) shot_noise_.push_back({noise, threshold});
    }
  }
  for (const double period : periods) starting_rate_ += 1 / period;
  // A mostly dark tile gives back what it does not use.
  if (pixels_.size() < pixels_.capacity() / 2) pixels_.shrink_to_fit();
  // Shot noise keeps windows while every pixel's swing is at least kWindowElectrons: a window's
  // firings then stay so close to the mean count that the room made for them is never short.
  const bool swings = std::all_of(shot_noise_.begin(), shot_noise_.end(), [](const IntegrateFire::ShotNoise& n) {
    return n.threshold >= kWindowElectrons * kElectronCharge;
  });
  const bool still =
      std::all_of(pixels_.begin(), pixels_.end(), [](const Slot& p) { return p.next_boundary == kNoBoundary; });
  if (windows && !pixels_.empty() && swings) {
    keys_.reserve(entries.size());
    for (const WakeCalendar::Entry& e : entries) keys_.push_back(e.key);
    if (still) {
      windowed_ = true;
      if (shot_noise_.empty()) {
        periodic_.reserve(pixels_.size());
        for (const Slot& p : pixels_) periodic_.push_back(p.periodic());
        pixels_.clear();
        pixels_.shrink_to_fit();
      }
    } else {
      windowed_ = windows_pay(thresholds);
    }
    if (windowed_) return;
    keys_.clear();
    keys_.shrink_to_fit();
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

bool FiringSchedule::windows_pay(const std::vector<double>& thresholds) {
  const Photocurrents& pc = photocurrents_;
  const std::size_t frames = pc.frames();
  frame_rates_.assign(frames, 0.0);
  frame_changes_.assign(frames, 0);
  for (std::size_t s = 0; s < pixels_.size(); ++s) {
    const std::size_t index = std::size_t(y_of(keys_[s])) * cols_ + x_of(keys_[s]);
    double before = pc.frame_current(frames - 1, index);  // on a loop, the frame before the first
    for (std::size_t f = 0; f < frames; ++f) {
      const double current = pc.frame_current(f, index);
      if (current > 0) frame_rates_[f] += 1 / (thresholds[s] / current + sensor_.t_reset);
      if (current != before && (f > 0 || pc.loops())) ++frame_changes_[f];
      before = current;
    }
  }
  // Over the run: firings expected, light changes (each a calendar wake-up), and boundaries at
  // which some pixel of the tile changes (each ends a window).
  double firings = 0, changes = 0, change_boundaries = 0;
  const double period = pc.frame_period();
  const auto interval = [&](std::size_t frame, double length, bool starts_with_change) {
    firings += length * frame_rates_[frame];
    if (starts_with_change && frame_changes_[frame] > 0) {
      changes += frame_changes_[frame];
      change_boundaries += 1;
    }
  };
  if (pc.loops()) {
    const double cycle = period * static_cast<double>(frames);
    const double whole = std::floor(t_end_ / cycle);
    for (std::size_t f = 0; f < frames; ++f) interval(f, period * whole, false);
    for (std::size_t f = 0; f < frames; ++f) {
      changes += whole * frame_changes_[f];
      change_boundaries += whole * (frame_changes_[f] > 0);
    }
    for (std::size_t f = 0; f < frames && whole * cycle + static_cast<double>(f) * period < t_end_; ++f) {
      const double start = whole * cycle + static_cast<double>(f) * period;
      interval(f, std::min(period, t_end_ - start), true);
    }
  } else {
    for (std::size_t f = 0; f < frames && static_cast<double>(f) * period < t_end_; ++f) {
      const double start = static_cast<double>(f) * period;
      interval(f, f + 1 == frames ? t_end_ - start : std::min(period, t_end_ - start), f > 0);
    }
  }
  // Each window visits every pixel of the tile; the calendar pays a pop and a push for every
  // firing and every change of light, each several times a visit's cost.
  const double n = static_cast<double>(pixels_.size());
  const double visits = n * change_boundaries + firings / kWindowFirings;
  if (!(visits <= kVisitsPerCalendarWake * (firings + changes))) {
    frame_rates_.clear();
    frame_changes_.clear();
    return false;
  }
  return true;
}

std::uint64_t FiringSchedule::interval_at(double t) const {
  const Photocurrents& pc = photocurrents_;
  auto k = static_cast<std::uint64_t>(t / pc.frame_period());
  while (pc.boundary_time(k + 1) <= t) ++k;
  while (k > 0 && pc.boundary_time(k) > t) --k;
  return k;
}

double FiringSchedule::next_change_after(std::uint64_t k) const {
  const Photocurrents& pc = photocurrents_;
  const std::uint64_t frames = pc.frames();
  // A held sequence changes up to its last frame; a looped one repeats within `frames`.
  const std::uint64_t last = pc.loops() ? k + frames : frames - 1;
  for (std::uint64_t b = k + 1; b <= last; ++b) {
    if (frame_changes_[pc.frame_at(b)] > 0) return pc.boundary_time(b);
  }
  return kNever;
}

std::uint32_t FiringSchedule::boundary_after(std::uint64_t boundary, std::size_t index) const {
  const std::uint64_t b = photocurrents_.next_change(boundary, index);
  // A boundary past the run is as good as none (sim.duration * frame rate < 2^32 is validated).
  return b == Photocurrents::kNoChange || photocurrents_.boundary_time(b) > t_end_ ? kNoBoundary
                                                                                   : static_cast<std::uint32_t>(b);
}

std::size_t FiringSchedule::fill_windows(AddressEvent* out, std::size_t capacity, double until) {
  std::size_t filled = 0;
  const double last = std::min(until, t_end_);
  while (filled < capacity) {
    if (!made_) {
      if (!(made_to_ < last)) break;
      make_window(ahead_ ? t_end_ : last);
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

void FiringSchedule::make_window(double last) {
  // The window ends at `last`, at the next boundary where the tile's light changes, or after about
  // kWindowFirings firings a pixel at the rate of the light it starts in, whichever comes first;
  // and at least one representable step on, so that every window moves on.
  const std::size_t n = keys_.size();
  // A still tile's rate is the one it starts at (every pixel of it is lit: one dark all run has no
  // slot); a moving tile's, its light's in the frame the window starts in.
  double rate = starting_rate_, to = last;
  if (!frame_rates_.empty()) {
    const std::uint64_t k = interval_at(made_to_);
    rate = frame_rates_[photocurrents_.frame_at(k)];
    to = std::min(to, next_change_after(k));
  }
  if (rate > 0) to = std::min(to, made_to_ + kWindowFirings * static_cast<double>(n) / rate);
  to = std::max(to, std::nextafter(made_to_, last));
  std::unique_ptr<FiringWindow> window = FiringWindow::take();
  // The light is the same through the window (a pixel's change at its end comes after its firings
  // there), so a pixel fires at most (to - from) / period + 1 times in it, one more at each end for
  // rounding; room for a little over the sum, so that the loop below never has to grow it (the
  // writer would report a shortfall rather than write past it).
  const double most = (to - made_to_) * rate * (1 + 1e-9) + 3.0 * static_cast<double>(n) + 64;
  FiringWindow::Writer writer =
      window->start(made_to_, to, static_cast<std::size_t>((to - made_to_) * rate), static_cast<std::size_t>(most));
  Slot* const pixels = pixels_.data();
  const std::uint32_t* const keys = keys_.data();
  const bool noisy = !shot_noise_.empty();
  // Pixel by pixel, so in bus-address order; each pixel's firings in time order.
  if (!periodic_.empty()) {
    if ((to - made_to_) * rate < kSpeculateBelow * static_cast<double>(n)) {
      fire_periodic<true>(to, writer);
    } else {
      fire_periodic<false>(to, writer);
    }
  }
  const double counting_window = counting_window_;
  for (std::size_t i = 0; i < pixels_.size(); ++i) {
    const std::uint32_t key = keys[i];
    Slot& p = pixels[i];
    std::uint32_t all = 0, within = 0;
    const auto emit = [&writer, key, &all, &within, counting_window](double t, bool kept = true) {
      writer.add(t, key, kept);
      all += kept ? 1 : 0;
      within += kept && t <= counting_window ? 1 : 0;
    };
    for (;;) {
      const double boundary =
          p.next_boundary == kNoBoundary ? kNever : photocurrents_.boundary_time(p.next_boundary);
      // Firings up to the change (it falls at the window's end), then the new light, and any
      // firing the new light still puts at that instant.
      const double through = boundary < to ? boundary : to;
      if (noisy) {
        p.fire_through_noisy(sensor_, shot_noise_[i], through, emit);
      } else {
        p.fire_through(sensor_, no_noise_, through, emit);
      }
      if (!(boundary <= to)) break;
      const std::size_t index = std::size_t(y_of(key)) * cols_ + x_of(key);
      p.set_current(sensor_, boundary, photocurrents_.current(p.next_boundary, index));
      p.next_boundary = boundary_after(p.next_boundary, index);
    }
    if (counting_) {
      fired_[i] += all;
      fired_within_[i] += within;
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

template <bool speculate>
void FiringSchedule::fire_periodic(double to, FiringWindow::Writer& writer) {
  const std::size_t n = keys_.size();
  const std::uint32_t* const keys = keys_.data();
  double* const first = periodic_.first.data();
  double* const period = periodic_.period.data();
  std::uint32_t* const cycles = periodic_.cycles.data();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t key = keys[i];
    const auto emit = [&writer, key](double t, bool kept) { writer.add(t, key, kept); };
    using Periodic = IntegrateFire::Periodic;
    while (!__builtin_expect(Periodic::count_through<speculate>(first[i], period[i], cycles[i], to, emit), 1)) {
      ended_.push_back({static_cast<std::uint32_t>(i), cycles[i], first[i], period[i]});
      Periodic::restart(first[i], period[i], cycles[i], periodic_.integration[i], sensor_, emit);
    }
  }
}

void FiringSchedule::count_pixel_firings(double window) {
  counting_ = true;
  counting_window_ = window;
  fired_.assign(pixels_.size(), 0);
  fired_within_.assign(pixels_.size(), 0);
}

void FiringSchedule::pixel_firings(std::vector<PixelFirings>& out) const {
  out.clear();
  if (!counting_) return;
  const std::size_t n = keys_.size();
  out.reserve(n);
  const auto index = [this](std::size_t i) {
    return static_cast<std::uint32_t>(std::size_t(y_of(keys_[i])) * cols_ + x_of(keys_[i]));
  };
  if (periodic_.empty()) {
    for (std::size_t i = 0; i < n; ++i) out.push_back({index(i), fired_[i], fired_within_[i]});
    return;
  }
  const double window = counting_window_;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t cycles = periodic_.cycles[i];
    out.push_back({index(i), cycles,
                   IntegrateFire::Periodic::count_at_or_before(periodic_.first[i], periodic_.period[i], cycles,
                                                               window)});
  }
  for (const EndedCycles& e : ended_) {
    const IntegrateFire::Periodic::Firings ended =
        IntegrateFire::Periodic::ended_by_restart(e.first, e.period, e.cycles, window);
    out[e.pixel].all += ended.all;
    out[e.pixel].within += ended.within;
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
