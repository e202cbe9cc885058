#include "aesim/array/fixed_step_array.hpp"
#include "aesim/kernel/systemc_kernel.hpp"
#include "aesim/rungs/event_level_buses.hpp"
#include "aesim/rungs/rung.hpp"

namespace aesim {
namespace {

// sim.fidelity=fixed_step: every pixel integrated on a clock of period sim.step
// (array/fixed_step_array), into the event-level buses.
class FixedStepRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::FixedStep; }
  RungCapabilities capabilities() const override {
    RungCapabilities can;
    can.shot_noise = false;
    can.stepped = true;
    return can;
  }
  void run(const RungRun& run, RunFacts& facts) const override {
    const ScopedKernel kernel;  // first, so the modules are gone before their context
    EventLevelBuses buses(run);
    FixedStepArray array("fixed_step", run.config.pixel, run.config.sim, run.photocurrents, run.map, buses.pointers());
    run_until_starved(run.config.sim.duration);
    buses.finish(run.config.bus, facts);
    facts.multi_fire_steps = array.multi_fire_steps();
  }
};

}  // namespace

const Rung& fixed_step_rung() {
  static const FixedStepRung rung;
  return rung;
}

}  // namespace aesim
