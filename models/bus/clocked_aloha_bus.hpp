#pragma once
#include <cstdint>
#include <memory>
#include <systemc>
#include <vector>

#include "array/address_map.hpp"
#include "bus/handshake_monitor.hpp"
#include "bus/tile_bus.hpp"
#include "receiver/event_log.hpp"
#include "receiver/reference_receiver.hpp"

namespace aesim {

// bus.access=aloha at the cycle fidelity: one tile's real wires and its receiver.
//
// Wires: `addr` (bus_bits lines, wired-OR of every pixel driving), `req` (wired-OR of their
// requests), `contention` (high while two or more pixels drive: the contention detector), and
// `ack` from the receiver back to every pixel.
//
// A pixel that fires drives its address and Req at once and holds them until it sees Ack rise,
// then releases (4-phase handshake, pixel-side delays taken as zero). There is no arbiter, so
// pixels firing before the receiver latches all drive together: the receiver latches the OR of
// their addresses with `contention` high, and every one of them is lost (Fate::Collided with
// contention detection, Fate::Ghost without). A pixel that fires while Ack is already high sees
// Ack at once and withdraws before the synchronizer can register it: it is absorbed and lost
// (Fate::Collided). So an event survives iff no other pixel fires in the window from the
// previous transaction's start to its own latch: about 3 cycles after its Req and up to ~6
// cycles before it. That window is asymmetric, unlike the event fidelity's textbook (t-tau, t+tau).
// The transaction time tau (Req rise to Ack fall) is measured and reported.
class ClockedAlohaBus : public TileBus {
 public:
  ClockedAlohaBus(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
                  const SensorConfig& config, EventLog& log, VcdRecorder* vcd);
  SC_HAS_PROCESS(ClockedAlohaBus);

  void request(const AddressEvent& firing) override;
  double measured_tau() const override;

  std::uint64_t protocol_violations() const { return monitor_.violations(); }
  std::uint64_t transactions() const { return transactions_; }
  std::uint64_t clock_edges() const { return receiver_.clock_edges(); }

 private:
  struct Driver {
    AddressEvent firing;
    sc_core::sc_time since;
  };
  void on_ack();
  void drive();

  // Wired-OR lines: every pixel that fires drives them, so they take many writers.
  sc_core::sc_signal<bool, sc_core::SC_MANY_WRITERS> req_, contention_;
  sc_core::sc_signal<std::uint32_t, sc_core::SC_MANY_WRITERS> addr_;
  sc_core::sc_signal<bool> ack_;
  ReferenceReceiver receiver_;
  HandshakeMonitor monitor_;
  EventLog& log_;
  bool detect_;
  std::vector<Driver> drivers_;
  sc_core::sc_time transaction_start_;
  bool in_transaction_ = false;
  double busy_time_ = 0;
  std::uint64_t transactions_ = 0;
};

}  // namespace aesim
