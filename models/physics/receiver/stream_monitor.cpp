#include "aesim/receiver/stream_monitor.hpp"

namespace aesim {

StreamMonitor::StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s) : sc_module(name), s_(s) {
  SC_METHOD(on_rise);
  sensitive << s_.clk.posedge_event();
  dont_initialize();
}

StreamView StreamMonitor::view() const {
  StreamView v;
  v.rst_n = s_.rst_n.read();
  v.valid = s_.evt_valid.read();
  v.ready = s_.evt_ready.read();
  v.flags = s_.evt_flags.read();
  v.ts = s_.evt_ts.read();
  v.addr = s_.evt_addr.read();
  v.events = s_.events.read();
  v.fifo_count = s_.fifo_count.read();
  v.fifo_limit = s_.fifo_limit.read();
  v.counters = counters_;
  return v;
}

}  // namespace aesim
