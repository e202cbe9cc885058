#pragma once
#include <cstdint>
#include <systemc>

namespace aesim {

class CycleTile;

// A port the caller may leave unbound: an Imager's tile ports are bound only where the tile's
// receiver is the caller's.
template <class T>
using OptionalOut = sc_core::sc_port<sc_core::sc_signal_inout_if<T>, 1, sc_core::SC_ZERO_OR_MORE_BOUND>;
template <class T>
using OptionalIn = sc_core::sc_port<sc_core::sc_signal_in_if<T>, 1, sc_core::SC_ZERO_OR_MORE_BOUND>;

// One tile's bus as ports, for a receiver that lives outside the Imager (a SystemC model of the
// caller's, or their RTL Verilated with `verilator --sc`): the caller binds each port to an
// sc_signal and their receiver's port to the same signal. Names, directions and widths are those
// of rtl/aer_receiver.v as `verilator --sc` declares them (bool for one bit, std::uint32_t for 2 to
// 32 bits). Directions are the Imager's.
//
// Required for a tile named in ImagerSpec::outside_receivers: `ack`; everything else is bound as
// the receiver needs it. `idle`, when bound, lets the tile stop the clock while the receiver is
// idle with Req low, as it does for its own receivers; unbound, the clock runs free until
// sim.duration and then stops once Req and Ack are low. The output stream (evt_*), when bound, is
// taken by the tile's consumer (one beat per rising edge with valid and ready) and becomes
// Imager::events(); unbound, what the receiver delivers is the caller's to collect. The stream's
// rules are checked as for aesim's receivers (protocol_violations()); that nothing vanishes
// (events written = beats taken + fifo_count) only where `events` and `fifo_count` are bound.
class TilePorts : public sc_core::sc_module {
 public:
  explicit TilePorts(const sc_core::sc_module_name& name);

  OptionalOut<bool> clk, rst_n;                                 // the tile's receiver clock and reset
  OptionalOut<bool> req, contention;                            // the bus's wired-OR lines
  OptionalOut<std::uint32_t> addr;                              // the 10-bit address
  OptionalIn<bool> ack;                                         // the receiver's acknowledge
  OptionalOut<std::uint32_t> ts;                                // the tick count, set before each rising edge
  OptionalOut<std::uint32_t> prescale, fifo_limit;              // the receiver's settings, constant
  OptionalOut<bool> discard_collisions, ts_external;
  OptionalIn<bool> idle;                                        // optional
  OptionalIn<bool> evt_valid, evt_flags;                        // optional: the output stream
  OptionalIn<std::uint32_t> evt_addr, evt_ts;
  OptionalOut<bool> evt_ready;
  OptionalIn<std::uint32_t> events, fifo_count;                 // optional: the stream's counters

  // Which tile these ports are, and when the run ends (s): called by the Imager.
  void attach(CycleTile& tile, std::uint32_t index, double duration);

 private:
  void end_of_elaboration() override;
  bool any_bound() const;

  CycleTile* tile_ = nullptr;
  std::uint32_t index_ = 0;
  double duration_ = 0;
};

}  // namespace aesim
