#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/receiver/receiver_signals.hpp"

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
  // For a receiver that does not report idle (one outside the tile, with its idle wire left
  // unconnected): run free until `until`, then stop once Req and Ack are both low. Set before the
  // simulation starts.
  void run_free_then_stop_when_quiet(sc_core::sc_time until) {
    free_running_until_ = until;
    stop_when_quiet_ = true;
  }
  const sc_core::sc_time& period() const { return period_; }

 private:
  void run();

  ReceiverSignals& s_;
  sc_core::sc_time period_;
  unsigned prescale_;
  std::uint64_t ts_mask_;
  sc_core::sc_time free_running_until_;
  bool stop_when_quiet_ = false;
  std::uint64_t edges_ = 0;
};

}  // namespace aesim
