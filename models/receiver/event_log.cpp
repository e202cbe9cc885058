#include "receiver/event_log.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace aesim {

const char* to_string(Fate fate) {
  switch (fate) {
    case Fate::Delivered: return "delivered";
    case Fate::Collided: return "collided";
    case Fate::Ghost: return "ghost";
    case Fate::Dropped: return "dropped";
    case Fate::Pending: return "pending";
  }
  return "?";
}

EventLog::EventLog(int tiles, bool keep_truth)
    : tiles_(static_cast<std::size_t>(tiles)), keep_truth_(keep_truth) {}

void EventLog::resolve(const AddressEvent& firing, Fate fate, double t_deliver) {
  TileCounters& c = tiles_[firing.tile];
  switch (fate) {
    case Fate::Delivered: latencies_.push_back(t_deliver - firing.t); break;
    case Fate::Collided:
    case Fate::Ghost: ++c.collided; break;
    case Fate::Dropped: ++c.dropped; break;
    case Fate::Pending: ++c.pending; break;
  }
  if (keep_truth_) truth_.push_back({firing, fate, t_deliver});
}

void EventLog::output(const AddressEvent& e) {
  ++tiles_[e.tile].delivered;
  if (e.flags & kGhostEvent) ++tiles_[e.tile].ghost;
  events_.push_back(e);
}

void EventLog::finish() {
  std::stable_sort(events_.begin(), events_.end(), [](const AddressEvent& a, const AddressEvent& b) {
    return std::tie(a.t, a.tile, a.bus_address) < std::tie(b.t, b.tile, b.bus_address);
  });
  std::stable_sort(truth_.begin(), truth_.end(), [](const TruthRecord& a, const TruthRecord& b) {
    return std::tie(a.firing.t, a.firing.tile, a.firing.bus_address) <
           std::tie(b.firing.t, b.firing.tile, b.firing.bus_address);
  });
}

TileCounters EventLog::totals() const {
  TileCounters sum;
  for (const TileCounters& t : tiles_) {
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
  if (latencies_.empty()) return s;
  std::vector<double> sorted = latencies_;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0;
  for (double v : sorted) sum += v;
  s.mean = sum / static_cast<double>(sorted.size());
  // Nearest-rank 99th percentile.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(sorted.size())));
  s.p99 = sorted[std::max<std::size_t>(rank, 1) - 1];
  s.max = sorted.back();
  return s;
}

}  // namespace aesim
