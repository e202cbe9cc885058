#include "aesim/events/event_log.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "aesim/threads/buffer_hand_off.hpp"

namespace aesim {
namespace {

// Nonzero waits kept exactly before binning: up to 4 Mi doubles (32 MB) over the whole run.
constexpr std::size_t kExactLatencies = std::size_t(1) << 22;

}  // namespace

const char* to_string(Fate fate) {
  switch (fate) {
    case Fate::Delivered: return "delivered";
    case Fate::Collided:
    case Fate::Absorbed: return "collided";
    case Fate::Ghost: return "ghost";
    case Fate::Dropped: return "dropped";
    case Fate::Pending: return "pending";
  }
  return "?";
}

EventLog::EventLog(int tiles, LogOutputs outputs)
    : outputs_(outputs), collector_(std::make_unique<EventCollector>()), filling_(static_cast<std::size_t>(tiles)),
      set_aside_(static_cast<std::size_t>(tiles)), latency_(kExactLatencies) {
  const std::size_t n = static_cast<std::size_t>(tiles);
  tiles_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    tiles_.push_back(Tile{{}, LatencyRecorder(std::max<std::size_t>(4096, kExactLatencies / n)), 0, false});
  }
  EventStream& out = outputs_.stream ? *outputs_.stream : static_cast<EventStream&>(*collector_);
  merger_ = std::make_unique<EventMerger>(n, out);
  start_filling();
}

EventLog::EventLog(EventLog&&) noexcept = default;
EventLog& EventLog::operator=(EventLog&&) noexcept = default;
EventLog::~EventLog() = default;

void EventLog::count_pixels(const AddressMap& map, double window) {
  pixels_.assign(static_cast<std::size_t>(map.rows()) * static_cast<std::size_t>(map.cols()), PixelCounts{});
  window_ = window;
  map_ = map;
}

void EventLog::fired_and_delivered(const AddressEvent* firings, std::size_t n) {
  if (n == 0) return;
  const std::uint32_t t = firings[0].tile;
  Tile& tile = tiles_[t];
  tile.counters.fired += n;
  // A firing is never a ghost (the receiver makes those), and it waited for nothing.
  tile.latencies.add_zeros(n);
  tile.counters.delivered += n;
  if (pixels_.empty()) {
    tile.address_ones += address_ones_of(firings, n);
  } else if (!tile.firings_added_later) {
    for (std::size_t i = 0; i < n; ++i) {
      PixelCounts& p = pixel_of(firings[i]);
      count_fired(p, firings[i]);
      count_output(p, firings[i], false);
    }
  }
  if (outputs_.truth) {
    std::vector<TruthRecord>& truth = filling_.truth[t];
    for (std::size_t i = 0; i < n; ++i) truth.push_back({firings[i], Fate::Delivered, firings[i].t});
  }
  if (outputs_.events) {
    // Grown once and written in place: a push_back an event checked the capacity every time.
    UninitializedGrowthVector<TileEvent>& events = filling_.events[t];
    const std::size_t at = events.size();
    events.resize(at + n);
    TileEvent* out = events.data() + at;
    if (firings_in_order_) {
      for (std::size_t i = 0; i < n; ++i) out[i] = TileEvent::of(firings[i]);
      return;
    }
    // Checked as they are copied, each against the one before (the tile's last so far for the
    // first), so that the merge need not read them all to know.
    TileEvent last = at > 0 ? out[-1] : TileEvent::of(firings[0]);
    bool disordered = false;
    for (std::size_t i = 0; i < n; ++i) {
      const TileEvent e = TileEvent::of(firings[i]);
      out[i] = e;
      disordered |= e.before(last);
      last = e;
    }
    if (disordered) filling_.events_in_order[t] = 0;
  }
}

void EventLog::hand_over(double before) {
  if (!outputs_.events && !outputs_.truth) return;
  if (!pipeline_) {
    const std::size_t tiles = tiles_.size();
    pipeline_ = std::make_unique<BufferHandOff<TileRecords>>([tiles] { return TileRecords(tiles); });
  }
  // The tiles get back the buffers of a batch before, emptied by its merge.
  EventMerger& merger = *merger_;
  pipeline_->post(filling_, [&merger, before](TileRecords& batch) { merger.merge(batch, before); });
  start_filling();
}

void EventLog::set_aside(double before) {
  if (!keeps_records()) return;
  merge_set_aside();
  std::swap(filling_, set_aside_);
  start_filling();
  set_aside_before_ = before;
  set_aside_pending_ = true;
}

void EventLog::merge_set_aside() {
  if (!set_aside_pending_) return;
  set_aside_pending_ = false;
  merger_->merge(set_aside_, set_aside_before_);
}

void EventLog::finish() {
  merge_set_aside();
  if (pipeline_) {
    hand_over(std::numeric_limits<double>::infinity());
    pipeline_->drain();
    pipeline_.reset();
  } else if (keeps_records()) {
    // Nothing is being merged in the background: the rest is merged here, without a thread.
    merger_->merge(filling_, std::numeric_limits<double>::infinity());
  }
  for (Tile& t : tiles_) latency_.absorb(t.latencies);
}

std::vector<TileCounters> EventLog::tiles() const {
  std::vector<TileCounters> out;
  for (const Tile& t : tiles_) out.push_back(t.counters);
  return out;
}

std::uint64_t EventLog::address_ones() const {
  std::uint64_t n = 0;
  if (!pixels_.empty()) {
    // Each firing of a pixel put the pixel's address on the bus.
    const auto cols = static_cast<std::size_t>(map_->cols());
    for (std::size_t i = 0; i < pixels_.size(); ++i) {
      const auto x = static_cast<std::uint32_t>(i % cols), y = static_cast<std::uint32_t>(i / cols);
      n += static_cast<std::uint64_t>(pixels_[i].fired) * ones(map_->bus_address({x, y}));
    }
    return n;
  }
  for (const Tile& t : tiles_) n += t.address_ones;
  return n;
}

TileCounters EventLog::totals() const {
  TileCounters sum;
  for (const Tile& tile : tiles_) {
    const TileCounters& t = tile.counters;
    sum.fired += t.fired;
    sum.delivered += t.delivered;
    sum.collided += t.collided;
    sum.ghost += t.ghost;
    sum.dropped += t.dropped;
    sum.pending += t.pending;
  }
  return sum;
}

}  // namespace aesim
