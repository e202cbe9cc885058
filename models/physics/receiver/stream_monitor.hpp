#pragma once
#include <cstdint>
#include <systemc>

#include "receiver/receiver_signals.hpp"

namespace aesim {

// Watches a receiver's output after every rising clock edge:
//  - while valid is high and ready low, the beat (timestamp, address, flags) must not change and
//    valid must not fall;
//  - nothing vanishes: events written equal beats taken plus words still in the FIFO, and the
//    FIFO never holds more than its limit.
// The outputs are registered, so what they hold after an edge they still hold at the next rising
// edge (or when the run ends, the clock stopped): one process on the rising edge checks the last
// edge's outputs, then latches this edge's inputs, where a falling-edge process would cost a
// second activation per cycle.
class StreamMonitor : public sc_core::sc_module {
 public:
  StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s);
  SC_HAS_PROCESS(StreamMonitor);

  std::uint64_t violations() const { return violations_ + (pending_ ? broken() : 0); }

 private:
  void on_rise();
  // Rules the outputs break now, after the last edge.
  unsigned broken() const;

  ReceiverSignals& s_;
  bool stalled_ = false;
  bool pending_ = false;  // an edge's outputs not yet checked
  std::uint32_t held_ts_ = 0, held_addr_ = 0;
  bool held_flags_ = false;
  std::uint64_t taken_ = 0, violations_ = 0;
};

}  // namespace aesim
