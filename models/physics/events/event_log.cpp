#include "events/event_log.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "containers/min_heap.hpp"

namespace aesim {
namespace {

// (time, tile, address) as a pair of numbers, so comparisons inline.
struct OrderKey {
  double t;
  std::uint64_t rest;  // tile << 32 | bus address
  bool operator<(const OrderKey& o) const { return t < o.t || (t == o.t && rest < o.rest); }
};
OrderKey key_of(const AddressEvent& e) { return {e.t, (std::uint64_t(e.tile) << 32) | e.bus_address}; }
OrderKey key_of(const TruthRecord& r) { return key_of(r.firing); }

// Sorts each tile's records if needed (simultaneous SystemC processes may have run in any order),
// then merges the tiles in order through a heap of their heads, emptying them.
template <typename T>
std::vector<T> merge_tiles(const std::vector<std::vector<T>*>& parts) {
  auto less = [](const T& a, const T& b) { return key_of(a) < key_of(b); };
  std::size_t total = 0;
  for (auto* p : parts) {
    if (!std::is_sorted(p->begin(), p->end(), less)) std::stable_sort(p->begin(), p->end(), less);
    total += p->size();
  }
  std::vector<T> out;
  out.reserve(total);
  struct Head {
    OrderKey key;
    std::size_t part, pos;
  };
  struct Before {
    bool operator()(const Head& a, const Head& b) const { return a.key < b.key; }
  };
  std::vector<Head> heads;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!parts[i]->empty()) heads.push_back({key_of(parts[i]->front()), i, 0});
  }
  MinHeap<Head, Before, 2> heap;
  heap.assign(std::move(heads));
  while (!heap.empty()) {
    Head h = heap.top();
    const std::vector<T>& part = *parts[h.part];
    out.push_back(part[h.pos]);
    if (++h.pos < part.size()) {
      h.key = key_of(part[h.pos]);
      heap.replace_top(h);
    } else {
      heap.pop();
    }
  }
  for (auto* p : parts) std::vector<T>().swap(*p);
  return out;
}

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

EventLog::EventLog(int tiles, bool keep_truth) : tiles_(static_cast<std::size_t>(tiles)), keep_truth_(keep_truth) {}

void EventLog::resolve(const AddressEvent& firing, Fate fate, double t_deliver) {
  Tile& tile = tiles_[firing.tile];
  switch (fate) {
    case Fate::Delivered:
      // Most buses deliver at once; only waits are stored, zero ones are counted.
      if (t_deliver > firing.t) {
        tile.latencies.push_back(t_deliver - firing.t);
      } else {
        ++tile.zero_latencies;
      }
      break;
    case Fate::Collided:
    case Fate::Absorbed:
    case Fate::Ghost: ++tile.counters.collided; break;
    case Fate::Dropped: ++tile.counters.dropped; break;
    case Fate::Pending: ++tile.counters.pending; break;
  }
  if (keep_truth_) tile.truth.push_back({firing, fate, t_deliver});
}

void EventLog::output(const AddressEvent& e) {
  Tile& tile = tiles_[e.tile];
  ++tile.counters.delivered;
  if (e.flags & kGhostEvent) ++tile.counters.ghost;
  tile.events.push_back(e);
}

void EventLog::finish() {
  std::vector<std::vector<AddressEvent>*> events;
  std::vector<std::vector<TruthRecord>*> truth;
  for (Tile& t : tiles_) {
    events.push_back(&t.events);
    truth.push_back(&t.truth);
    latencies_.insert(latencies_.end(), t.latencies.begin(), t.latencies.end());
    zero_latencies_ += t.zero_latencies;
    std::vector<double>().swap(t.latencies);
  }
  events_ = merge_tiles(events);
  truth_ = merge_tiles(truth);
}

std::vector<TileCounters> EventLog::tiles() const {
  std::vector<TileCounters> out;
  for (const Tile& t : tiles_) out.push_back(t.counters);
  return out;
}

std::uint64_t EventLog::address_ones() const {
  std::uint64_t n = 0;
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

LatencyStats EventLog::latency() const {
  LatencyStats s;
  const std::size_t n = latencies_.size() + zero_latencies_;
  if (latencies_.empty()) return s;
  std::vector<double> sorted = latencies_;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0;
  for (double v : sorted) sum += v;
  s.mean = sum / static_cast<double>(n);
  // Nearest-rank 99th percentile over all delivered events, the zero waits first.
  const std::size_t rank = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(n))));
  s.p99 = rank <= zero_latencies_ ? 0.0 : sorted[rank - zero_latencies_ - 1];
  s.max = sorted.back();
  return s;
}

}  // namespace aesim
