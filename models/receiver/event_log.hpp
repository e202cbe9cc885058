#pragma once
#include <cstdint>
#include <vector>

#include "bus/address_event.hpp"

namespace aesim {

// What a run produced, per tile and in total: the receiver's output plus the fate counters of
// SPEC section 5.
struct TileCounters {
  std::uint64_t fired = 0, delivered = 0, collided = 0, ghost = 0, dropped = 0;
};

class EventLog {
 public:
  explicit EventLog(int tiles) : tiles_(static_cast<std::size_t>(tiles)) {}

  void fired(std::uint32_t tile) { ++tiles_[tile].fired; }
  void deliver(const AddressEvent& e) {
    ++tiles_[e.tile].delivered;
    if (e.flags & kGhostEvent) ++tiles_[e.tile].ghost;
    events_.push_back(e);
  }
  // Orders delivered events by (time, tile, address) so outputs do not depend on the order
  // in which simultaneous processes ran.
  void finish();

  const std::vector<AddressEvent>& events() const { return events_; }
  const std::vector<TileCounters>& tiles() const { return tiles_; }
  TileCounters totals() const;

 private:
  std::vector<TileCounters> tiles_;
  std::vector<AddressEvent> events_;
};

}  // namespace aesim
