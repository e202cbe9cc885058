#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/kernel/systemc_kernel.hpp"
#include "aesim/rungs/cycle_array.hpp"
#include "aesim/rungs/rung.hpp"
#include "aesim/tile/cycle_tile.hpp"

namespace aesim {
namespace {

// sim.fidelity=cycle: the tiles' real wires, Req/Ack, and a clocked receiver (the reference model
// or the Verilated RTL) under SystemC.
class CycleRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::Cycle; }
  RungCapabilities capabilities() const override {
    RungCapabilities can;
    can.exact = can.waveforms = can.receiver_model = true;
    return can;
  }
  void check(const SensorConfig& c) const override {
    if (c.bus.access != BusAccess::Aloha) {
      throw InputError(fmt::format("bus.access={} has no cycle-level model; the cycle fidelity models the "
                                   "aloha bus (use sim.fidelity=event)", to_string(c.bus.access)));
    }
    const AddressMap map(c.array);
    if (map.bus_bits() > kReceiverAddrWidth) {
      throw InputError(fmt::format("array.tile_rows: a {}-bit tile address exceeds the receiver's {} address bits",
                                   map.bus_bits(), kReceiverAddrWidth));
    }
    if (static_cast<unsigned>(c.receiver.fifo_depth) > kReceiverFifoCapacity) {
      throw InputError(fmt::format("receiver.fifo_depth: at most {} at the cycle fidelity (the receiver's FIFO)",
                                   kReceiverFifoCapacity));
    }
    if (std::round(c.receiver.tick * c.receiver.clock) > kReceiverMaxPrescale) {
      throw InputError(fmt::format("receiver.tick: at most {} clock cycles per tick", kReceiverMaxPrescale));
    }
  }
  double tick(const SensorConfig& config) const override { return receiver_tick(config.receiver); }
  void run(const RungRun& run, RunFacts& facts) const override {
    const ScopedKernel kernel;  // first, so the modules are gone before their context
    CycleArray array("imager", run, cycle_options(run));
    // The driver stops past sim.duration and receivers stop their clocks when idle, so the kernel
    // starves exactly when the run (and any last handshake) is done.
    run_until_starved(run.config.sim.duration);
    double tau_sum = 0;
    int measured = 0;
    for (const auto& tile : array.tiles()) {
      const CycleTile::Stats s = tile->stats();
      facts.protocol_violations += s.protocol_violations;
      facts.receiver_clock_edges += s.clock_edges;
      facts.scoreboard_beats += s.scoreboard_beats;
      facts.scoreboard_mismatches += s.scoreboard_mismatches;
      if (s.measured_tau > 0) {
        tau_sum += s.measured_tau;
        ++measured;
      }
    }
    facts.tau_s = measured > 0 ? tau_sum / measured : run.config.bus.t_event;
  }
};

}  // namespace

const Rung& cycle_rung() {
  static const CycleRung rung;
  return rung;
}

}  // namespace aesim
