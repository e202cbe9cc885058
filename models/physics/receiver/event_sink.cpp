#include "aesim/receiver/event_sink.hpp"

namespace aesim {

EventSink::EventSink(const sc_core::sc_module_name& name, ReceiverSignals& s, StreamConsumer consumer)
    : sc_module(name), s_(s), consumer_(std::move(consumer)) {
  s_.evt_ready.write(true);
  SC_METHOD(on_clock);
  sensitive << s_.clk.posedge_event();
  dont_initialize();
}

void EventSink::on_clock() {
  s_.evt_ready.write(consumer_.edge(s_.evt_valid.read(), s_.evt_ready.read(), s_.evt_ts.read(), s_.evt_addr.read(),
                                    s_.evt_flags.read()));
}

}  // namespace aesim
