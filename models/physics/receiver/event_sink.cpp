#include "receiver/event_sink.hpp"

namespace aesim {

EventSink::EventSink(const sc_core::sc_module_name& name, ReceiverSignals& s, std::uint32_t tile,
                     const AddressMap& map, double tick, int ts_width, EventLog& log)
    : sc_module(name),
      s_(s),
      tile_(tile),
      map_(map),
      tick_(tick),
      ts_modulus_(ts_width >= 64 ? 0 : (1ULL << ts_width)),
      log_(log) {
  s_.evt_ready.write(true);
  SC_METHOD(on_clock);
  sensitive << s_.clk.posedge_event();
  dont_initialize();
}

void EventSink::on_clock() {
  if (s_.evt_valid.read() && s_.evt_ready.read()) {
    const std::uint64_t ts = s_.evt_ts.read();
    if (ts < last_ts_) ++wraps_;
    last_ts_ = ts;
    AddressEvent e;
    e.t = static_cast<double>(ts + wraps_ * ts_modulus_) * tick_;
    e.tile = tile_;
    e.bus_address = s_.evt_addr.read();
    const PixelAddress p = map_.locate(tile_, e.bus_address);
    e.x = p.x;
    e.y = p.y;
    e.flags = s_.evt_flags.read() ? kGhostEvent : kNormalEvent;
    log_.output(e);
  }
  ++cycle_;
  s_.evt_ready.write(ready_ ? ready_(cycle_) : true);
}

}  // namespace aesim
