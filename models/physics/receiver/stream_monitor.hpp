#pragma once
#include <cstdint>
#include <systemc>

#include "receiver/receiver_signals.hpp"

namespace aesim {

// Watches a receiver's output at every falling clock edge:
//  - while valid is high and ready low, the beat (timestamp, address, flags) must not change and
//    valid must not fall;
//  - nothing vanishes: events written equal beats taken plus words still in the FIFO, and the
//    FIFO never holds more than its limit.
class StreamMonitor : public sc_core::sc_module {
 public:
  StreamMonitor(const sc_core::sc_module_name& name, ReceiverSignals& s);
  SC_HAS_PROCESS(StreamMonitor);

  std::uint64_t violations() const { return violations_; }

 private:
  void on_rise();
  void on_fall();

  ReceiverSignals& s_;
  bool stalled_ = false;
  std::uint32_t held_ts_ = 0, held_addr_ = 0;
  bool held_flags_ = false;
  std::uint64_t taken_ = 0, violations_ = 0;
};

}  // namespace aesim
