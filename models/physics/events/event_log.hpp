#pragma once
#include <algorithm>
#include <cstdint>
#include <optional>
#include <memory>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/events/event_merger.hpp"
#include "aesim/events/event_stream.hpp"
#include "aesim/events/latency_recorder.hpp"
#include "aesim/events/pixel_firings.hpp"
#include "aesim/events/truth_record.hpp"

namespace aesim {

template <typename Buffer>
class BufferHandOff;

// Set bits of a word, without the library call __builtin_popcount becomes on a baseline x86-64.
inline unsigned ones(std::uint32_t v) {
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  return (((v + (v >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24;
}

// Counters of docs/reference.md section 5, per tile. `collided` counts fired events lost to collisions,
// whether detected (Fate::Collided, Fate::Absorbed) or not (Fate::Ghost); `ghost` counts the wrong events the
// receiver output for undetected collisions; `delivered` counts every output event, ghosts too.
struct TileCounters {
  std::uint64_t fired = 0, delivered = 0, collided = 0, ghost = 0, dropped = 0, pending = 0;
  // The fraction of fired events lost to collisions (0 when none fired).
  double collision_fraction() const {
    return fired ? static_cast<double>(collided) / static_cast<double>(fired) : 0.0;
  }
};

// What a run keeps of its records beyond counters.
struct LogOutputs {
  bool events = true;             // the receivers' output events
  bool truth = false;             // a TruthRecord per fired event
  EventStream* stream = nullptr;  // where they go; null: into the log's own collector (events(), truth())
};

// The record of a run, filled in by the bus models (fates) and the receivers (output). Each tile
// records apart, so tiles may be simulated on separate threads (one thread per tile at a time).
// Records are streamed, not hoarded: at each hand_over() the rung names a time before which no
// tile will produce another record, and the records before it are merged in order (EventMerger)
// into the stream while the tiles go on, on a background thread (hand_over) or on one of the
// rung's own (set_aside). A run that keeps no events holds
// counters only, so memory does not grow with the run's length.
class EventLog {
 public:
  EventLog(int tiles, LogOutputs outputs);
  EventLog(int tiles, bool keep_truth) : EventLog(tiles, LogOutputs{true, keep_truth, nullptr}) {}
  EventLog(EventLog&&) noexcept;
  EventLog& operator=(EventLog&&) noexcept;
  ~EventLog();

  // Counts firings per pixel (y * cols + x) in all and within [0, window], and output events per
  // pixel (the histogram image) in all and, without ghosts, within the window (the sizing
  // metrics). Tiles on separate threads touch separate pixels. An output whose address names no
  // pixel of its tile (a ghost, the OR of several addresses, may name a column past a narrow edge
  // tile or a row past the bottom; a receiver under test may put out anything) is counted in its
  // tile's counters but at no pixel. The 1 bits the bus carried are summed per pixel after the
  // run rather than per event.
  void count_pixels(const AddressMap& map, double window);
  void fired(const AddressEvent& firing) { fired_all(&firing, 1); }
  // fired() for each of a batch of one tile's firings (a bus serves one tile), with the counters
  // summed in registers and added once: the event rung's buses take 256 firings a call.
  void fired_all(const AddressEvent* firings, std::size_t n) {
    if (n == 0) return;
    Tile& tile = tiles_[firings[0].tile];
    tile.counters.fired += n;
    if (pixels_.empty()) {
      tile.address_ones += address_ones_of(firings, n);
    } else if (tile.firings_added_later) {
      // Counted as delivered by add_pixel_firings(): each of these was not.
      for (std::size_t i = 0; i < n; ++i) uncount_output(pixel_of(firings[i]), firings[i]);
    } else {
      for (std::size_t i = 0; i < n; ++i) count_fired(pixel_of(firings[i]), firings[i]);
    }
  }
  // For a tile whose schedule works out each pixel's firings (FiringSchedule::pixel_firings) and
  // whose bus delivers every firing the moment it fires (fired_and_delivered) or loses it
  // (fired_all): its firings are not counted per pixel as they come, and add_pixel_firings() adds
  // them after the run, each as fired and output; a lost firing takes its output back. On a large
  // array a counter reached a firing missed the caches. False, and nothing changed, when the log
  // counts no pixels (count_pixels was not called).
  bool add_firings_later(std::uint32_t tile) {
    if (pixels_.empty()) return false;
    tiles_[tile].firings_added_later = true;
    return true;
  }
  // The time up to which firings are counted apart (count_pixels' window).
  double counting_window() const { return window_; }
  // A tile's pixels' firings, for a tile marked by add_firings_later().
  void add_pixel_firings(const std::vector<PixelFirings>& firings) {
    for (const PixelFirings& f : firings) {
      PixelCounts& p = pixels_[f.index];
      p.fired += f.all;
      p.fired_in_window += f.within;
      p.output += f.all;
      p.output_in_window += f.within;
    }
  }
  // fired_all() then, for each firing, resolve(firing, Fate::Delivered, firing.t) and
  // output(firing): a batch of one tile's firings delivered the moment they fired, as most are on
  // a free bus. The same counts and records in the same order, each pixel's counters reached once.
  void fired_and_delivered(const AddressEvent* firings, std::size_t n);
  // Said by a caller whose firings reach fired_and_delivered() in (time, bus address) order, tile
  // by tile, as a FiringSchedule makes them: the log then does not check each against the one
  // before as it records it (a third of its work a firing). Events output otherwise (a ghost) are
  // checked still.
  void firings_come_in_order() { firings_in_order_ = true; }
  // Said by a caller that can foresee about how many records a tile will add before the next
  // hand-over: its buffer is made that large at once. Grown as records come, a buffer doubles,
  // and one a little past a power of two holds twice what it needs in each of the sets the tiles
  // and the merge pass round (a 2048x2048 array's ~512 records a tile a window would take 1,024).
  void expect_records(std::uint32_t tile, std::size_t n) {
    if (!outputs_.events) return;
    UninitializedGrowthVector<TileEvent>& events = filling_.events[tile];
    if (events.capacity() < events.size() + n) events.reserve(events.size() + n);
  }
  // A pixel's four counters side by side: one cache line touched per event, not four.
  struct PixelCounts {
    std::uint32_t fired = 0, fired_in_window = 0, output = 0, output_in_window = 0;
  };
  // Every pixel's counters (y * cols + x; empty unless count_pixels was called), read in place: a
  // large array's are tens of megabytes, which the per-pixel copies below each take again.
  const std::vector<PixelCounts>& pixel_counts() const { return pixels_; }
  std::vector<std::uint32_t> fired_per_pixel() const { return per_pixel(&PixelCounts::fired); }
  std::vector<std::uint32_t> window_per_pixel() const { return per_pixel(&PixelCounts::fired_in_window); }
  // Output events per pixel, ghosts included; and real (non-ghost) ones within the window.
  std::vector<std::uint32_t> output_per_pixel() const { return per_pixel(&PixelCounts::output); }
  std::vector<std::uint32_t> window_output_per_pixel() const { return per_pixel(&PixelCounts::output_in_window); }
  // 1 bits of the addresses of every fired event: what the bus lines carried.
  std::uint64_t address_ones() const;
  // Every fired event is resolved exactly once, when its fate is known.
  void resolve(const AddressEvent& firing, Fate fate, double t_deliver = 0) {
    Tile& tile = tiles_[firing.tile];
    switch (fate) {
      case Fate::Delivered: tile.latencies.add(t_deliver - firing.t); break;
      case Fate::Collided:
      case Fate::Absorbed:
      case Fate::Ghost: ++tile.counters.collided; break;
      case Fate::Dropped: ++tile.counters.dropped; break;
      case Fate::Pending: ++tile.counters.pending; break;
    }
    if (outputs_.truth) filling_.truth[firing.tile].push_back({firing, fate, t_deliver});
  }
  // The receiver's output: a delivered event, or a ghost (flags & kGhostEvent).
  void output(const AddressEvent& e) {
    Tile& tile = tiles_[e.tile];
    ++tile.counters.delivered;
    const bool ghost = (e.flags & kGhostEvent) != 0;
    if (ghost) ++tile.counters.ghost;
    if (!pixels_.empty() && map_->names_pixel(e)) count_output(pixel_of(e), e, ghost);
    if (outputs_.events) {
      UninitializedGrowthVector<TileEvent>& events = filling_.events[e.tile];
      const TileEvent record = TileEvent::of(e);
      if (!events.empty() && record.before(events.back())) filling_.events_in_order[e.tile] = 0;
      events.push_back(record);
    }
  }

  // Called by a rung while none of its tiles runs: no tile will output an event, or resolve a
  // firing, earlier than `before`. Passes those records on (in the background) and hands the
  // tiles fresh buffers.
  void hand_over(double before);
  // hand_over() for a rung that merges on its own threads, beside its tiles, instead of on one
  // more: sets the records aside with `before` and hands the tiles the buffers of the batch set
  // aside before (merged by then). merge_set_aside() merges them, on one thread, while the tiles
  // record into the new buffers; it does nothing when nothing is set aside. A batch set aside is
  // merged before the next one is set aside, and by finish() at the latest.
  void set_aside(double before);
  void merge_set_aside();
  // Whether records (events or truth) are kept, so that their order across tiles matters.
  bool keeps_records() const { return outputs_.events || outputs_.truth; }
  // After the run: passes on everything left and waits until the stream has it all. Rethrows an
  // error the stream raised.
  void finish();

  // With LogOutputs::stream null, what the log collected (merged in order by finish()).
  const std::vector<AddressEvent>& events() const { return collector_->events(); }
  const std::vector<TruthRecord>& truth() const { return collector_->truth(); }
  std::vector<TileCounters> tiles() const;
  TileCounters totals() const;
  LatencyStats latency() const { return latency_.stats(); }

 private:
  // A cache line of its own: each tile's counters are written on every event by the thread
  // running that tile.
  struct alignas(64) Tile {
    TileCounters counters;
    LatencyRecorder latencies;
    std::uint64_t address_ones = 0;
    bool firings_added_later = false;  // see add_firings_later()
  };
  std::vector<Tile> tiles_;
  LogOutputs outputs_;
  std::unique_ptr<EventCollector> collector_;
  std::unique_ptr<EventMerger> merger_;
  // Merging (and the stream's writing) on a thread of its own, behind the tiles: while the tiles
  // fill window k+2, window k is merged and written and window k+1 waits, so that a window the
  // tiles finish quickly does not make them wait for a slow merge, nor the merge for the tiles, as
  // long as the two keep pace on average (bright QCIF to .aedat4: 39 -> 44 M events/s against one
  // window at a time), for a third window's records in memory. Made at the first hand_over().
  std::unique_ptr<BufferHandOff<TileRecords>> pipeline_;
  // Fresh buffers for the tiles: every tile's events in order so far (none yet).
  void start_filling() { std::fill(filling_.events_in_order.begin(), filling_.events_in_order.end(), 1); }
  TileRecords filling_;  // the tiles' records since the last hand-over
  bool firings_in_order_ = false;  // see firings_come_in_order()
  TileRecords set_aside_;  // set aside and not yet merged when set_aside_pending_
  double set_aside_before_ = 0;
  bool set_aside_pending_ = false;
  LatencyRecorder latency_;
  PixelCounts& pixel_of(const AddressEvent& e) { return pixels_[std::size_t(e.y) * std::size_t(map_->cols()) + e.x]; }
  void count_fired(PixelCounts& p, const AddressEvent& firing) const {
    ++p.fired;
    p.fired_in_window += firing.t <= window_ ? 1 : 0;
  }
  void count_output(PixelCounts& p, const AddressEvent& e, bool ghost) const {
    ++p.output;
    p.output_in_window += !ghost && e.t <= window_ ? 1 : 0;
  }
  void uncount_output(PixelCounts& p, const AddressEvent& firing) const {
    --p.output;
    p.output_in_window -= firing.t <= window_ ? 1 : 0;
  }
  static std::uint64_t address_ones_of(const AddressEvent* firings, std::size_t n) {
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) sum += ones(firings[i].bus_address);
    return sum;
  }
  std::vector<std::uint32_t> per_pixel(std::uint32_t PixelCounts::*field) const {
    std::vector<std::uint32_t> out;
    out.reserve(pixels_.size());
    for (const PixelCounts& p : pixels_) out.push_back(p.*field);
    return out;
  }
  std::vector<PixelCounts> pixels_;
  std::optional<AddressMap> map_;  // with the pixels counted
  double window_ = 0;
};

}  // namespace aesim
