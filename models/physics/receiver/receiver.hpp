#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/receiver/receiver_cycle_model.hpp"
#include "aesim/receiver/receiver_signals.hpp"

namespace aesim {

// aesim's bundled receiver as a SystemC module: the reference model of rtl/aer_receiver.v
// (ReceiverCycleModel), with the RTL's ports under the names TilePorts uses (no _i/_o suffixes,
// the types `verilator --sc` gives: bool for one bit, std::uint32_t up to 32). It binds to an
// Imager tile's ports through sc_signals as any receiver outside the Imager does, and it is the
// module the Imager makes for its own tiles when a project's ReceiverFactory asks for the reference.
//
// The constructor's Config holds what the RTL fixes when it is built (address and stamp widths,
// FIFO capacity, drop or hold when full) and the settings; the settings' ports (prescale,
// fifo_limit, discard_collisions, ts_external) are optional and, where bound, replace the
// Config's from the first clock edge after reset on (they are constant during a run, as the RTL's
// configuration inputs are). Reset (rst_n low) is
// asynchronous, as in the RTL; `ts` is read only with ts_external.
class Receiver : public sc_core::sc_module {
 public:
  template <class T>
  using OptionalIn = sc_core::sc_port<sc_core::sc_signal_in_if<T>, 1, sc_core::SC_ZERO_OR_MORE_BOUND>;
  template <class T>
  using OptionalOut = sc_core::sc_port<sc_core::sc_signal_inout_if<T>, 1, sc_core::SC_ZERO_OR_MORE_BOUND>;

  sc_core::sc_in<bool> clk{"clk"}, rst_n{"rst_n"};
  sc_core::sc_in<bool> req{"req"};
  sc_core::sc_in<std::uint32_t> addr{"addr"};
  OptionalIn<bool> contention{"contention"};
  sc_core::sc_out<bool> ack{"ack"};
  OptionalIn<std::uint32_t> ts{"ts"}, prescale{"prescale"}, fifo_limit{"fifo_limit"};
  OptionalIn<bool> discard_collisions{"discard_collisions"}, ts_external{"ts_external"};
  // The output stream: a beat is taken at a rising edge with evt_valid and evt_ready high;
  // evt_ready unbound is a consumer that is always ready.
  OptionalOut<bool> evt_valid{"evt_valid"}, evt_flags{"evt_flags"};
  OptionalOut<std::uint32_t> evt_ts{"evt_ts"}, evt_addr{"evt_addr"};
  OptionalIn<bool> evt_ready{"evt_ready"};
  // Counters and status.
  OptionalOut<std::uint32_t> events{"events"}, collisions{"collisions"}, overflows{"overflows"},
      fifo_count{"fifo_count"};
  OptionalOut<bool> idle{"idle"};

  Receiver(const sc_core::sc_module_name& name, const ReceiverCycleModel::Config& config);
  SC_HAS_PROCESS(Receiver);

  // Binds every port to a tile's signals (aesim's own tiles).
  void bind(ReceiverSignals& s);

 private:
  void on_clock_or_reset();
  void drive();
  ReceiverCycleModel::Config settings() const;

  ReceiverCycleModel::Config config_;
  ReceiverCycleModel model_;
  bool configured_ = false;  // the settings' ports read since the last reset
};

}  // namespace aesim
