#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/receiver/stream_consumer.hpp"

namespace aesim {

// A StreamConsumer on a receiver's wires: at each rising edge it takes the beat the wires offer
// and drives ready for the next cycle.
class EventSink : public sc_core::sc_module {
 public:
  EventSink(const sc_core::sc_module_name& name, ReceiverSignals& s, StreamConsumer consumer);
  SC_HAS_PROCESS(EventSink);

 private:
  void on_clock();

  ReceiverSignals& s_;
  StreamConsumer consumer_;
};

}  // namespace aesim
