#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/array/firing_window.hpp"
#include "aesim/array/wake_calendar.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/events/pixel_firings.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/pixel/integrate_fire.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// One tile's pixels in firing order, from one place: the exact event-driven model without a
// SystemC process per pixel. Each pixel's next wake-up (its next firing, computed in closed form
// by IntegrateFire, or the next frame boundary where its own light changes) sits in a calendar
// queue keyed by (time, bus address), so firings come out in time order, ties in address order.
// A pixel dark in every frame never gets a slot; a pixel whose next wake-up is past the end of
// the run leaves the queue. Cost follows the events, not the pixels.
//
// A still tile needs no queue: it makes its firings a window of about four firings a pixel at a
// time, and counting-sorts them (FiringWindow). Same firings, same order, about twice the
// calendar's rate. A moving scene's tile does the same, its windows ending where its light
// changes, when that costs less than the calendar; with shot noise too, while every pixel's swing
// is at least ten electrons (each firing then draws the next integration's electron count).
class FiringSchedule {
 public:
  // `windows`: a tile may make its firings a window at a time (see fill_windows); false keeps
  // every tile on the calendar (tests compare the two).
  FiringSchedule(const PixelParams& pixel, const SimParams& sim, const Photocurrents& photocurrents,
                 const AddressMap& map, std::uint32_t tile, bool windows = true);

  // The next firing at or before sim.duration; false when none remains.
  bool next(AddressEvent& firing) { return fill(&firing, 1, t_end_) == 1; }
  // The next firing at or before `until`; false when none remains that early (the schedule then
  // stands at `until`: light changes up to it are applied).
  bool next(AddressEvent& firing, double until) { return fill(&firing, 1, until) == 1; }
  // The next firings at or before `until`, up to `capacity` of them, into `out` in order; fewer
  // than `capacity` when none remains that early (as next()). A batch costs one call, not one an
  // event.
  std::size_t fill(AddressEvent* out, std::size_t capacity, double until) {
    return windowed_ ? fill_windows(out, capacity, until) : fill_from_calendar(out, capacity, until);
  }
  // Whether the tile's firings come from windows rather than the calendar.
  bool windowed() const { return windowed_; }
  // The pixels each of its windows visits: every lit one where the tile's firings come from
  // windows, none on the calendar.
  std::size_t window_pixels() const { return windowed_ ? keys_.size() : 0; }
  // Whether a window may run on past the time fill() was asked up to, its later firings kept for
  // the next calls: a caller that asks a little at a time (a streaming run's windows) then does not
  // cut a tile's window short at each ask, each cut one more visit of every pixel, for the memory
  // of the window the tile keeps between calls (up to about kWindowFirings firings a pixel). Off
  // unless set.
  void run_windows_ahead(bool on) { ahead_ = on; }
  // The tile's mean firings per second in the light it starts in (shot noise spreads them about
  // it): what a caller sizing its first window of time on it can expect, until the light changes.
  double starting_rate() const { return starting_rate_; }
  // Whether the schedule can count its own pixels' firings (count_pixel_firings): a tile whose
  // firings come from windows, which visit its pixels one after the other.
  bool counts_pixel_firings() const { return windowed_; }
  // From now on (before any firing is taken), keeps each pixel's firings, in all and at or before
  // `window`, for pixel_firings(). A still tile without shot noise works them out from each
  // pixel's first firing, period and cycle count when asked (the times count_through gives its
  // firings, so the same count); another windowed tile counts them as its windows make them, in
  // registers while it is at the pixel.
  void count_pixel_firings(double window);
  // Each pixel's firings so far (as count_pixel_firings set out), into `out`; none without
  // count_pixel_firings.
  void pixel_firings(std::vector<PixelFirings>& out) const;

  // A lit pixel's state: 56 bytes, plus 8 in the calendar and 4 per bucket (about one a pixel):
  // 68 bytes per lit pixel; a still tile's 28 (PeriodicPixels; 56 with shot noise) and its 4-byte
  // bus address, with no calendar (a still scene's photocurrents are not held; see
  // Photocurrents). Its bus address is its key in the calendar, its coordinates follow from it.
  // Derived, not a member, so that next_boundary sits in IntegrateFire's tail padding.
  struct Slot : IntegrateFire {
    std::uint32_t next_boundary;  // kNoBoundary when its light never changes again
  };
  static constexpr std::uint32_t kNoBoundary = 0xFFFFFFFFu;

 private:
  double wake_time(const Slot& p) const {
    const double boundary = p.next_boundary == kNoBoundary ? kNever : photocurrents_.boundary_time(p.next_boundary);
    return std::min(p.next_fire(), boundary);
  }

  const Photocurrents& photocurrents_;
  IntegrateFire::Sensor sensor_;
  double t_end_;
  std::uint32_t tile_;
  std::uint32_t cols_;
  std::uint32_t x0_ = 0, y0_ = 0, xbits_ = 0;  // the tile's origin and the address layout
  // From a bus address within the tile: (y_local << xbits) | x_local.
  std::uint32_t x_of(std::uint32_t bus_address) const { return x0_ + (bus_address & ((1u << xbits_) - 1)); }
  std::uint32_t y_of(std::uint32_t bus_address) const { return y0_ + (bus_address >> xbits_); }
  IntegrateFire::ShotNoise& noise(std::uint32_t slot) { return shot_noise_.empty() ? no_noise_ : shot_noise_[slot]; }
  std::uint32_t boundary_after(std::uint64_t boundary, std::size_t index) const;
  std::size_t fill_from_calendar(AddressEvent* out, std::size_t capacity, double until);
  // A tile makes its firings a window at a time: each pixel's firings up to the window's end, in
  // pixel order, counting-sorted by time (FiringWindow). The same firings in the same order as the
  // calendar's, for about half the work a firing; the calendar is not built. A window ends where
  // the tile's light next changes, so its light is the same throughout. Taken by a still tile, and
  // by a moving one when its windows would visit pixels no more than kVisitsPerCalendarWake times
  // as often as the calendar would wake them (windows_pay); with shot noise, while every swing
  // holds ten electrons or more.
  std::size_t fill_windows(AddressEvent* out, std::size_t capacity, double until);
  void make_window(double last);
  // A still tile's pixels without shot noise, into a window ending at `to`.
  template <bool speculate>
  void fire_periodic(double to, FiringWindow::Writer& writer);
  // For a moving scene: each frame's firing rate and count of changed pixels over the tile; true
  // when windows cost less than the calendar over the run.
  bool windows_pay(const std::vector<double>& thresholds);
  // The frame interval (boundary k to k + 1) holding time t, and the time of the first boundary
  // after k at which some pixel of the tile changes (kNever if none).
  std::uint64_t interval_at(double t) const;
  double next_change_after(std::uint64_t k) const;

  std::vector<Slot> pixels_;  // empty for a still tile without shot noise: periodic_ holds its pixels
  // A still tile without shot noise keeps its pixels as IntegrateFire::Periodic, each field an
  // array: half the state (28 bytes a pixel, not 56), and its windows read 20 bytes a pixel and
  // write 4 (the cycles), where a whole record was read and written back for each pixel a window
  // (on large arrays a window holds under one firing a pixel, so that is most of its work).
  struct PeriodicPixels {
    std::vector<double> first, period, integration;
    std::vector<std::uint32_t> cycles;
    bool empty() const { return first.empty(); }
    void reserve(std::size_t n) {
      first.reserve(n);
      period.reserve(n);
      integration.reserve(n);
      cycles.reserve(n);
    }
    void push_back(const IntegrateFire::Periodic& p) {
      first.push_back(p.first);
      period.push_back(p.period);
      integration.push_back(p.integration);
      cycles.push_back(p.cycles);
    }
  };
  PeriodicPixels periodic_;
  // A periodic pixel re-anchored after 2^30 cycles (restart): the cycles it had run then, a firing
  // more at the restart, and their times; rare enough to keep apart.
  struct EndedCycles {
    std::uint32_t pixel;  // its place in periodic_
    std::uint32_t cycles;
    double first, period;
  };
  std::vector<EndedCycles> ended_;
  // With count_pixel_firings, a windowed tile's firings per slot of pixels_ (empty for a
  // periodic_ tile), and the counting window.
  std::vector<std::uint32_t> fired_, fired_within_;
  double counting_window_ = 0;
  bool counting_ = false;
  std::vector<IntegrateFire::ShotNoise> shot_noise_;  // per pixel, only with pixel.shot_noise
  IntegrateFire::ShotNoise no_noise_;                 // untouched: without shot noise nothing is random
  WakeCalendar calendar_;

  bool windowed_ = false;
  bool ahead_ = false;                    // see run_windows_ahead()
  std::vector<std::uint32_t> keys_;       // windows: each pixel's bus address
  double starting_rate_ = 0;              // see starting_rate()
  std::vector<double> frame_rates_;       // windows, moving: the tile's firings per second in each frame
  std::vector<std::uint32_t> frame_changes_;  // windows, moving: pixels whose light changes into each frame
  double made_to_ = 0;                    // windows: firings up to this time are made
  std::unique_ptr<FiringWindow> made_;    // windows: the window made last, while any is left
  const FiringWindow::Firing* next_ = nullptr;  // windows: its first firing not yet taken
};

}  // namespace aesim
