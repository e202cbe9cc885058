#include "aesim/array/queue_model.hpp"
#include "aesim/rungs/event_level_buses.hpp"
#include "aesim/rungs/rung.hpp"

namespace aesim {
namespace {

// sim.fidelity=queue: the source paper's event queue (eq. 1 and 3, array/queue_model), in queue
// order into the event-level buses. No pixel physics, no SystemC.
class QueueRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::Queue; }
  RungCapabilities capabilities() const override { return {}; }
  void run(const RungRun& run, RunFacts& facts) const override {
    EventLevelBuses buses(run);
    for (const AddressEvent& e : queue_events(run.config.pixel, run.config.sim, run.photocurrents, run.map, &facts.empty_queue_frames)) {
      buses[e.tile].request(e);
    }
    buses.finish(run.config.bus, facts);
  }
};

}  // namespace

const Rung& queue_rung() {
  static const QueueRung rung;
  return rung;
}

}  // namespace aesim
