#include "receiver/stream_monitor.hpp"

namespace aesim {

StreamMonitor::StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s) : sc_module(name), s_(s) {
  SC_METHOD(on_rise);
  sensitive << s_.clk.posedge_event();
  dont_initialize();
}

void StreamMonitor::on_rise() {
  if (pending_) violations_ += broken();
  pending_ = false;
  if (!s_.rst_n.read()) {
    taken_ = 0;
    stalled_ = false;
    return;
  }
  pending_ = true;
  // The values before this edge: a beat offered and not taken must be offered again, unchanged.
  if (s_.evt_valid.read() && s_.evt_ready.read()) ++taken_;
  stalled_ = s_.evt_valid.read() && !s_.evt_ready.read();
  held_ts_ = s_.evt_ts.read();
  held_addr_ = s_.evt_addr.read();
  held_flags_ = s_.evt_flags.read();
}

unsigned StreamMonitor::broken() const {
  if (!s_.rst_n.read()) return 0;
  unsigned n = 0;
  if (stalled_ && (!s_.evt_valid.read() || s_.evt_ts.read() != held_ts_ || s_.evt_addr.read() != held_addr_ ||
                   s_.evt_flags.read() != held_flags_)) {
    ++n;
  }
  if (s_.events.read() != taken_ + s_.fifo_count.read()) ++n;
  if (s_.fifo_count.read() > s_.fifo_limit.read()) ++n;
  return n;
}

}  // namespace aesim
