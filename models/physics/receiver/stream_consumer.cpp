#include "aesim/receiver/stream_consumer.hpp"

namespace aesim {

StreamConsumer::StreamConsumer(std::uint32_t tile, const AddressMap& map, double tick, int ts_width, EventLog& log)
    : tile_(tile), map_(map), tick_(tick), ts_modulus_(ts_width >= 64 ? 0 : (1ULL << ts_width)), log_(log) {}

void StreamConsumer::take(std::uint64_t ts, std::uint32_t addr, bool flags) {
  if (ts < last_ts_) ++wraps_;
  last_ts_ = ts;
  AddressEvent e;
  e.t = static_cast<double>(ts + wraps_ * ts_modulus_) * tick_;
  e.tile = tile_;
  e.bus_address = addr;
  const PixelAddress p = map_.locate(tile_, e.bus_address);
  e.x = p.x;
  e.y = p.y;
  e.flags = flags ? kGhostEvent : kNormalEvent;
  log_.output(e);
}

}  // namespace aesim
