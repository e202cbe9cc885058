#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
#include <thread>

#include "aesim/array/firing_schedule.hpp"
#include "aesim/rungs/event_level_buses.hpp"
#include "aesim/rungs/rung.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/process/interrupt.hpp"
#include "aesim/threads/worker_pool.hpp"

namespace aesim {
namespace {

// Windows of half an event per pixel, 128 Ki at least: a small array's tiles work through about
// five firings a pixel a window while its pixels' state is in cache, and a window's records (2 MB)
// are still in the caches when the merge reads them; with two windows waiting for the merge that
// suited the bright QCIF better than 256 Ki (AEDAT 2.0, .npy and .aedat4 written 2-8 % faster,
// side by side in event_rate_bench) or 1 Mi (a quarter slower). On large arrays half an event a
// pixel is 8 bytes a pixel of records in each buffer set, up to twice that as the per-tile vectors
// grow by doubling (growing them by a quarter fragmented the heap: 100 MB more at 2048x2048), and
// a tile's window of firings ends with the run's window, so each window visits every pixel of the
// tile: AEDAT written at 2048x2048 (1 s, uniform light) took 3.25 s and 400 MB with an eighth of
// an event a pixel, 2.8 s and 443 MB with a quarter, 2.4 s and 479 MB with a half, 2.0-2.4 s and
// 576 MB with one (/usr/bin/time aesim run ... --out big.aedat, before a still tile's pixels were
// kept as arrays).
constexpr double kMinWindowEvents = 131072;
constexpr double kWindowEventsPerPixel = 0.5;
// Run windows of at least this many firings a pixel let the tiles' windows run on past them.
constexpr double kAheadEventsPerPixel = 2;
// Arrays of at least this many pixels make their schedules on a second thread (see run()): at
// 64x64 one thread and two were even (0.56 and 0.59 ms, medians of seven 1 ms runs writing AEDAT,
// `wall_time_s`), at 96x96 two took 0.76 ms against 0.90, at 128x128 1.0-1.1 against 1.3-1.6.
constexpr double kSetUpThreadPixels = 8192;

// Firings pass from a tile's schedule to its bus a batch at a time (8 KiB, in L1).
using FiringBatch = std::array<AddressEvent, 256>;

// A tile whose schedule makes windows, on a bus that delivers or loses each firing as it fires: the
// log takes its pixels' firings from the schedule after the run instead of counting each as it
// comes (a counter reached a firing, out of the caches on a large array, was a seventh of a
// 2048x2048 run; a still tile's firings are not counted at all, but worked out from its periods).
void count_firings_in_schedule(const RungRun& run, FiringSchedule& schedule, EventBus& bus, std::size_t tile) {
  if (schedule.counts_pixel_firings() && bus.delivers_when_fired() &&
      run.log.add_firings_later(static_cast<std::uint32_t>(tile))) {
    schedule.count_pixel_firings(run.log.counting_window());
  }
}

// After the run: the firings a schedule counted (none unless count_firings_in_schedule set it to).
void add_firings(const RungRun& run, const FiringSchedule& schedule) {
  thread_local std::vector<PixelFirings> firings;
  schedule.pixel_firings(firings);
  run.log.add_pixel_firings(firings);
}

int thread_count(const RungRun& run) {
  int threads = run.config.sim.threads;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::min(threads, run.map.tiles());
}

// sim.fidelity=event: the exact event-driven reference. Every tile's firings come out of its
// FiringSchedule in time order, straight into its event-level bus, with no SystemC time (nothing
// else observes them); tiles on up to sim.threads threads.
//
// A run that keeps only counters simulates each tile to the end on its own (one tile's state in
// memory per thread). A run that keeps records advances all tiles together through time windows
// of a set number of events and hands each window over to the log, which merges and writes it on
// another thread while the tiles go on: memory holds the pixels and a window, not the run.
class EventRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::Event; }
  RungCapabilities capabilities() const override {
    RungCapabilities can;
    can.exact = true;
    return can;
  }
  void run(const RungRun& run, RunFacts& facts) const override {
    EventLevelBuses buses(run);
    const double t_end = run.config.sim.duration;
    WorkerPool pool(thread_count(run));
    const std::size_t tiles = static_cast<std::size_t>(run.map.tiles());
    auto schedule_of = [&](std::size_t t) {
      return std::make_unique<FiringSchedule>(run.config.pixel, run.config.sim, run.photocurrents, run.map,
                                              static_cast<std::uint32_t>(t));
    };
    if (!run.log.keeps_records()) {
      pool.for_each(tiles, [&](std::size_t t) {
        const auto schedule = schedule_of(t);
        count_firings_in_schedule(run, *schedule, buses[t], t);
        FiringBatch batch;
        while (const std::size_t n = schedule->fill(batch.data(), batch.size(), t_end)) {
          buses[t].request_all(batch.data(), n);
        }
        add_firings(run, *schedule);
      });
      buses.finish(run.config.bus, facts);
      return;
    }
    run.log.firings_come_in_order();
    const double pixels = static_cast<double>(run.map.rows()) * run.map.cols();
    const double window_events = run.request.window_events > 0 ? run.request.window_events
                                                               : std::max(kMinWindowEvents, kWindowEventsPerPixel * pixels);
    // Where a run window holds a few firings a pixel (small arrays), a tile's window of firings
    // runs on past it, kept for the next (a few firings a pixel of each tile held between run
    // windows: a few megabytes at most); on large arrays it ends with the run window, as the
    // memory of every tile's window held would be far more than the run window's.
    const bool ahead = window_events >= kAheadEventsPerPixel * pixels;
    std::vector<std::unique_ptr<FiringSchedule>> schedules(tiles);
    const auto make_schedule = [&](std::size_t t) {
      schedules[t] = schedule_of(t);
      schedules[t]->run_windows_ahead(ahead);
      count_firings_in_schedule(run, *schedules[t], buses[t], t);
    };
    // With one tile thread the merge runs on a thread of the log's own, idle until the first
    // window comes: on all but the smallest arrays the schedules are made on two threads, as many
    // as the run keeps busy after (at 2048x2048 their making is a sixth of a 1 s run, most of it
    // the pixels' mismatch draws, each from its own pixel's stream, so the same whichever thread
    // makes them). On a small one starting the thread (8-57 us to start and join) costs what it
    // saves.
    if (pool.threads() == 1 && tiles > 1 && pixels >= kSetUpThreadPixels) {
      WorkerPool(2).for_each(tiles, make_schedule);
    } else {
      pool.for_each(tiles, make_schedule);
    }
    // Each tile's firings a second in its last window (at first, in the light it starts in): the
    // records it will add in the next are foreseen from it, with an eighth and 64 to spare (a
    // still tile's count strays a few dozen from its mean), so that its buffer is made once to
    // that size instead of doubling past it (see EventLog::expect_records). A tile whose light
    // changes may still outgrow it; its buffer then doubles as before.
    std::vector<double> tile_rates(tiles);
    for (std::size_t t = 0; t < tiles; ++t) tile_rates[t] = schedules[t]->starting_rate();
    // `width` is a window of about window_events: first at the rate the tiles start at, up to the
    // first change of light (past it the rate may be anything), then at the rate of the window
    // before, growing at most 4x a window. The windows do not change the output (the merge is
    // exact), only its pace. Ramping up from a microsecond instead cost a large array a dozen short
    // windows, each visiting every pixel (a tenth of a 1 s run at 2048x2048).
    const double starting_rate = std::accumulate(tile_rates.begin(), tile_rates.end(), 0.0);
    double width = t_end * 1e-6;
    if (starting_rate > 0 && std::isfinite(starting_rate)) {
      const double first_change = run.photocurrents.frames() > 1 ? run.photocurrents.frame_period() : t_end;
      width = std::clamp(window_events / starting_rate, width, std::max(width, first_change));
    }
    // Where a run window costs the tiles little beside its firings (their windows run ahead, or
    // they have few lit pixels to visit a window), the windows taken ramp up from a 64th of
    // `width`, 4x a window, and taper off to a 16th at the end: the merge starts while the tiles
    // are on their first window, and after their last it has only a short one left to merge alone,
    // where a whole window at each end left one thread alone with it (one lit pixel in 1024x1024,
    // a million events: 14 -> 25 M events/s; the bright QCIF to .aedat4: 42-44 -> 49 M). Where
    // every window visits millions of pixels (2048x2048 under uniform light) each short window
    // costs a visit of them all, about as much as the merge alone at the end (AEDAT written 0-8 %
    // slower with them).
    std::size_t visited = 0;
    for (const auto& schedule : schedules) visited += schedule->window_pixels();
    const bool ramp = ahead || static_cast<double>(visited) * 8 <= window_events;
    double taken = ramp ? width / 64 : width;
    std::uint64_t fired = 0;
    // On one thread the merge runs beside it, on a thread of the log's own. On more, it is one more
    // item of each window's loop, first, merging the window before while the tiles fill this one:
    // a thread of its own beside them kept one more thread busy than the threads asked for, and
    // two tile threads then waited at each window's end for the one the merge had descheduled.
    const bool merge_in_pool = pool.threads() > 1;
    const std::size_t first_tile = merge_in_pool ? 1 : 0;
    for (double from = 0; from < t_end;) {
      if (ramp) taken = std::min(taken, std::max((t_end - from) / 2, width / 16));
      // A window never shrinks below one representable step, so the run always advances.
      const double until = std::min(t_end, std::max(from + taken, std::nextafter(from, t_end)));
      pool.for_each(first_tile + tiles, [&](std::size_t i) {
        if (i < first_tile) {
          run.log.merge_set_aside();
          return;
        }
        const std::size_t t = i - first_tile;
        const double foreseen = tile_rates[t] * (until - from);
        if (foreseen > 0 && std::isfinite(foreseen)) {
          run.log.expect_records(static_cast<std::uint32_t>(t), static_cast<std::size_t>(foreseen * 1.125) + 64);
        }
        FiringBatch batch;
        std::size_t fired_here = 0;
        while (const std::size_t n = schedules[t]->fill(batch.data(), batch.size(), until)) {
          buses[t].request_all(batch.data(), n);
          fired_here += n;
        }
        tile_rates[t] = static_cast<double>(fired_here) / (until - from);
      });
      from = until;
      if (from >= t_end) break;
      if (const int sig = interrupt_requested()) throw Interrupted(sig);
      // Every later firing comes after `until`; what a bus still holds is the earliest undecided.
      double before = until;
      for (std::size_t t = 0; t < tiles; ++t) before = std::min(before, buses[t].held_since());
      if (merge_in_pool) {
        run.log.set_aside(before);
      } else {
        run.log.hand_over(before);
      }
      const std::uint64_t now = run.log.totals().fired;
      const double in_window = static_cast<double>(now - fired);
      fired = now;
      const double measured = taken * std::max(window_events, 1.0) / std::max(in_window, 1.0);
      width = std::clamp(measured, width / 4, width * 4);
      taken = ramp ? std::min(width, taken * 4) : width;
    }
    pool.for_each(tiles, [&](std::size_t t) { add_firings(run, *schedules[t]); });
    buses.finish(run.config.bus, facts);
  }
};

}  // namespace

const Rung& event_rung() {
  static const EventRung rung;
  return rung;
}

}  // namespace aesim
