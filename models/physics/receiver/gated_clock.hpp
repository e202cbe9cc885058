#pragma once
#include <cstdint>
#include <systemc>

#include "receiver/receiver_signals.hpp"

namespace aesim {

// The receiver clock: rising edges at k * period (k = 1, 2, ...), falling edges half a period
// later, exactly as a free-running clock started at t = 0. It is stopped (at a falling edge)
// whenever the receiver reports idle with Req low, and restarted at the next edge after Req
// rises: the receiver cannot change state meanwhile, so no result differs. Before each rising
// edge k it drives the external timestamp a free-running counter latches there, the ticks
// completed by that edge, floor(k / prescale) mod 2^ts_width. Releases reset at t = 0.
class GatedClock : public sc_core::sc_module {
 public:
  GatedClock(const sc_core::sc_module_name& name, ReceiverSignals& s, sc_core::sc_time period, unsigned prescale,
             int ts_width, sc_core::sc_time free_running_until = sc_core::SC_ZERO_TIME);
  SC_HAS_PROCESS(GatedClock);

  std::uint64_t edges() const { return edges_; }
  const sc_core::sc_time& period() const { return period_; }

 private:
  void run();

  ReceiverSignals& s_;
  sc_core::sc_time period_;
  unsigned prescale_;
  std::uint64_t ts_mask_;
  sc_core::sc_time free_running_until_;
  std::uint64_t edges_ = 0;
};

}  // namespace aesim
