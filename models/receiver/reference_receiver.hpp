#pragma once
#include <cstdint>
#include <systemc>

#include "array/address_map.hpp"
#include "receiver/event_log.hpp"

namespace aesim {

// The SystemC reference receiver of one tile: the cycle-exact model the Verilog receiver is
// verified against. On every rising edge of its clock (period P = 1/receiver.clock, edges at
// k*P from t = 0), with registered semantics (every decision uses the values held before the
// edge):
//   sync1 <= req; sync2 <= sync1                      two-flop synchronizer on the async Req
//   IDLE  and sync2: latch address and contention, raise Ack, go to ACK
//   ACK   and !sync2: drop Ack, go to IDLE
// So Ack rises on the 3rd edge after Req rises and falls on the 3rd edge after Req falls; a
// change exactly on an edge is seen at the next one. The latched event is timestamped at the
// latch edge. A flagged collision is discarded when bus.contention_detect is on; otherwise the
// OR'd address is output like any event (the simulator labels it a ghost).
//
// The clock is stopped while the receiver is idle with Req and both synchronizer flops low:
// nothing can change until Req rises, so edges are only simulated during transactions, with the
// same result as a free-running clock.
class ReferenceReceiver : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> req;
  sc_core::sc_in<std::uint32_t> addr;
  sc_core::sc_in<bool> contention;
  sc_core::sc_out<bool> ack;

  ReferenceReceiver(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
                    double clock_hz, bool contention_detect, EventLog& log);
  SC_HAS_PROCESS(ReferenceReceiver);

  std::uint64_t collisions_discarded() const { return collisions_; }
  std::uint64_t clock_edges() const { return edges_; }
  const sc_core::sc_time& period() const { return period_; }

 private:
  void run();
  void edge();

  std::uint32_t tile_;
  const AddressMap& map_;
  bool detect_;
  EventLog& log_;
  sc_core::sc_time period_;
  bool sync1_ = false, sync2_ = false, acking_ = false;
  std::uint64_t collisions_ = 0, edges_ = 0;
};

}  // namespace aesim
