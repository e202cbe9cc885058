#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/receiver/stream_rules.hpp"

namespace aesim {

// StreamRules on a receiver's wires, checked on the rising edge (one activation per cycle).
class StreamMonitor : public sc_core::sc_module {
 public:
  StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s);
  SC_HAS_PROCESS(StreamMonitor);

  std::uint64_t violations() const { return rules_.violations(view()); }
  // For a receiver whose `events` and `fifo_count` outputs are not connected.
  void without_counters() { counters_ = false; }

 private:
  void on_rise() { rules_.edge(view()); }
  StreamView view() const;

  ReceiverSignals& s_;
  StreamRules rules_;
  bool counters_ = true;
};

}  // namespace aesim
