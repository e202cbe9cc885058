#include "receiver/stream_monitor.hpp"

namespace aesim {

StreamMonitor::StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s) : sc_module(name), s_(s) {
  SC_METHOD(on_rise);
  sensitive << s_.clk.posedge_event();
  dont_initialize();
  SC_METHOD(on_fall);
  sensitive << s_.clk.negedge_event();
  dont_initialize();
}

void StreamMonitor::on_rise() {
  if (!s_.rst_n.read()) {
    taken_ = 0;
    stalled_ = false;
    return;
  }
  // The values before this edge: a beat offered and not taken must be offered again, unchanged.
  if (s_.evt_valid.read() && s_.evt_ready.read()) ++taken_;
  stalled_ = s_.evt_valid.read() && !s_.evt_ready.read();
  held_ts_ = s_.evt_ts.read();
  held_addr_ = s_.evt_addr.read();
  held_flags_ = s_.evt_flags.read();
}

void StreamMonitor::on_fall() {
  if (!s_.rst_n.read()) return;
  if (stalled_ && (!s_.evt_valid.read() || s_.evt_ts.read() != held_ts_ || s_.evt_addr.read() != held_addr_ ||
                   s_.evt_flags.read() != held_flags_)) {
    ++violations_;
  }
  if (s_.events.read() != taken_ + s_.fifo_count.read()) ++violations_;
  if (s_.fifo_count.read() > s_.fifo_limit.read()) ++violations_;
}

}  // namespace aesim
