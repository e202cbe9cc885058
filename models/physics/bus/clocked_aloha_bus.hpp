#pragma once
#include <cstdint>
#include <systemc>
#include <vector>

#include "aesim/bus/event_bus.hpp"
#include "aesim/bus/handshake_rules.hpp"
#include "aesim/bus/wired_or_lines.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/receiver/receiver_signals.hpp"

namespace aesim {

// bus.access=aloha at the cycle fidelity: the pixel side of one tile's real wires. It drives the
// wires of a CycleTile, whose receiver answers on them.
//
// Wires: `addr` (wired-OR of every pixel driving), `req` (wired-OR of their requests),
// `contention` (high while two or more pixels drive: the contention detector), and `ack` from the
// receiver back to every pixel.
//
// A pixel that fires drives its address and Req at once and holds them until it sees Ack rise,
// then releases (4-phase handshake, pixel-side delays taken as zero). A firing that falls exactly
// on a receiver clock edge drives 1 ps later, so every receiver sees it at the next edge. There
// is no arbiter, so pixels firing before the receiver latches all drive together: the receiver
// latches the OR of their addresses with `contention` high, and every one of them is lost
// (Fate::Collided with contention detection, Fate::Ghost without). A pixel that fires while Ack is
// already high sees Ack at once and withdraws before the synchronizer can register it
// (Fate::Absorbed). An event the receiver latches but cannot store (FIFO full, drop policy) is
// Fate::Dropped. The transaction time tau (Req rise to Ack fall) is measured, and the handshake's
// rules checked on every change of Req and Ack (HandshakeRules).
class ClockedAlohaBus : public sc_core::sc_module, public EventBus {
 public:
  ClockedAlohaBus(const sc_core::sc_module_name& name, ReceiverSignals& wires, sc_core::sc_time clock_period,
                  bool contention_detect, EventLog& log);
  SC_HAS_PROCESS(ClockedAlohaBus);

  void request(const AddressEvent& firing) override;
  double measured_tau() const override;
  // Firings that fell on a clock edge and join the wires 1 ps later.
  bool joins_pending() const { return !deferred_.empty(); }
  std::uint64_t handshake_violations() const { return rules_.violations(); }

 private:
  void apply_deferred();
  void join(const AddressEvent& firing);
  void on_ack();
  void drive();

  ReceiverSignals& s_;
  sc_core::sc_time clock_period_;
  bool detect_;
  EventLog& log_;
  WiredOrLines<AddressEvent> lines_;  // the firings driving the wires
  std::vector<AddressEvent> seen_;    // those the last Ack released
  HandshakeRules rules_;
  std::vector<AddressEvent> deferred_;
  sc_core::sc_event deferred_event_;
  sc_core::sc_time transaction_start_;
  bool in_transaction_ = false;
  std::uint32_t overflows_seen_ = 0;
  double busy_time_ = 0;
  std::uint64_t transactions_ = 0;
};

}  // namespace aesim
