#pragma once
#include <cstdint>

#include "aesim/array/address_map.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// A beat of a receiver's output stream as the event it carries: the stamp unwrapped (the counter
// wraps at 2^ts_width; beats come in stamp order, so a smaller stamp is a wrap) and turned into
// seconds with the receiver's tick, the address into a pixel of the tile, the flag into a ghost.
// Shared by every consumer of a receiver stream (StreamConsumer, ReceiverStreamFeed).
class BeatDecoder {
 public:
  BeatDecoder(std::uint32_t tile, const AddressMap& map, double tick, int ts_width)
      : tile_(tile), map_(map), tick_(tick), ts_modulus_(ts_width >= 64 ? 0 : (1ULL << ts_width)) {}

  AddressEvent decode(std::uint64_t ts, std::uint32_t addr, bool flags) {
    if (ts < last_ts_) ++wraps_;
    last_ts_ = ts;
    AddressEvent e;
    e.t = static_cast<double>(ts + wraps_ * ts_modulus_) * tick_;
    e.tile = tile_;
    e.bus_address = addr;
    const PixelAddress p = map_.locate(tile_, addr);
    e.x = p.x;
    e.y = p.y;
    e.flags = flags ? kGhostEvent : kNormalEvent;
    return e;
  }

 private:
  std::uint32_t tile_;
  const AddressMap& map_;
  double tick_;
  std::uint64_t ts_modulus_;
  std::uint64_t last_ts_ = 0, wraps_ = 0;
};

}  // namespace aesim
