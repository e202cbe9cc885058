#include "receiver/reference_receiver.hpp"

#include <cmath>

namespace aesim {

ReferenceReceiver::ReferenceReceiver(const sc_core::sc_module_name& name, std::uint32_t tile,
                                     const AddressMap& map, double clock_hz, bool contention_detect,
                                     EventLog& log)
    : sc_module(name),
      tile_(tile),
      map_(map),
      detect_(contention_detect),
      log_(log),
      // A whole number of picoseconds, so edges fall exactly on SystemC's time grid.
      period_(static_cast<double>(std::max<long long>(1, std::llround(1e12 / clock_hz))), sc_core::SC_PS) {
  SC_THREAD(run);
}

void ReferenceReceiver::run() {
  const sc_core::sc_time zero = sc_core::SC_ZERO_TIME;
  ack.write(false);
  for (;;) {
    if (!req.read()) wait(req.posedge_event());
    // The first edge strictly after now: a Req rising exactly on an edge is seen at the next.
    const auto now = sc_core::sc_time_stamp().value();
    const auto p = period_.value();
    sc_core::sc_time next = sc_core::sc_time::from_value((now / p + 1) * p);
    for (;;) {
      const sc_core::sc_time delay = next - sc_core::sc_time_stamp();
      if (delay > zero) wait(delay);
      edge();
      if (!acking_ && !sync1_ && !sync2_ && !req.read()) break;
      next += period_;
    }
  }
}

void ReferenceReceiver::edge() {
  ++edges_;
  const bool seen = sync2_;
  sync2_ = sync1_;
  sync1_ = req.read();
  if (!acking_ && seen) {
    const bool collided = contention.read();
    acking_ = true;
    ack.write(true);
    if (collided && detect_) {
      ++collisions_;
      return;
    }
    AddressEvent e;
    e.t = sc_core::sc_time_stamp().to_seconds();
    e.tile = tile_;
    e.bus_address = addr.read();
    const PixelAddress p = map_.locate(tile_, e.bus_address);
    e.x = p.x;
    e.y = p.y;
    e.flags = collided ? kGhostEvent : kNormalEvent;
    log_.output(e);
  } else if (acking_ && !seen) {
    acking_ = false;
    ack.write(false);
  }
}

}  // namespace aesim
