#include "receiver/event_log.hpp"

#include <algorithm>
#include <tuple>

namespace aesim {

void EventLog::finish() {
  std::stable_sort(events_.begin(), events_.end(), [](const AddressEvent& a, const AddressEvent& b) {
    return std::tie(a.t, a.tile, a.bus_address) < std::tie(b.t, b.tile, b.bus_address);
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
  }
  return sum;
}

}  // namespace aesim
